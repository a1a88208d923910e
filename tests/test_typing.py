"""The public API is typed: mypy accepts the whole library."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from conftest import REPO


def test_mypy_accepts_the_library(tmp_path: Path) -> None:
    result = subprocess.run(
        [sys.executable, '-m', 'mypy', 'nodl_schema', '--ignore-missing-imports',
         '--cache-dir', str(tmp_path / 'mypy-cache')],
        cwd=REPO, text=True, capture_output=True, timeout=240)
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_package_is_marked_typed() -> None:
    assert (REPO / 'nodl_schema' / 'py.typed').is_file()
