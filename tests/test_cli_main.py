"""The ``nodl`` entry point (nodl.cli.main)."""

from __future__ import annotations

import gc
import sys
from pathlib import Path

import pytest

from nodl.cli import main as cli

VALID = Path(__file__).parent / 'fixtures' / 'valid' / 'node_laser_driver.nodl.yaml'


def test_the_command_freezes_what_is_left_before_the_interpreter_ends(monkeypatch: pytest.MonkeyPatch) -> None:
    """Run as the command (no arguments given), main moves what is still alive out of the
    collector's generations before the process ends (the interpreter's shutdown then does not
    walk it all again); a caller passing arguments (a test, a tool) keeps its collector as it was."""
    frozen: list[bool] = []
    monkeypatch.setattr(gc, 'freeze', lambda: frozen.append(True))
    assert cli.main(['validate', '-q', str(VALID)]) == 0
    assert frozen == []
    monkeypatch.setattr(sys, 'argv', ['nodl', 'validate', '-q', str(VALID)])
    assert cli.main() == 0
    assert frozen == [True]
