"""`nodl show nodl://PACKAGE/NAME`: a registered interface definition, as users run it."""

from __future__ import annotations

import os
import subprocess
import sys

import yaml

from conftest import FIXTURES, REPO

PREFIX = FIXTURES / 'dialects' / 'include' / 'prefix'


def show(*args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, AMENT_PREFIX_PATH=str(PREFIX))
    result = subprocess.run([sys.executable, '-m', 'nodl', 'show', *args], cwd=REPO,
                            env=env, text=True, capture_output=True, timeout=60)
    assert 'Traceback' not in result.stdout + result.stderr, result.stderr
    return result


def test_shows_a_registered_interface_definition() -> None:
    result = show('nodl://arm_common/heartbeat')
    assert result.returncode == 0, result.stderr
    shown = yaml.safe_load(result.stdout)
    assert shown['publishers'][0]['name'] == '/heartbeat'
    assert 'heartbeat.period' in shown['parameters']


def test_layers_name_the_reference() -> None:
    result = show('nodl://arm_common/heartbeat', '--layers')
    assert result.returncode == 0, result.stderr
    assert '# layer: nodl://arm_common/heartbeat' in result.stdout


def test_an_unknown_name_lists_what_the_package_registers() -> None:
    result = show('nodl://arm_common/nope')
    assert result.returncode == 2  # not registered: as a missing file
    assert "registers no interface definition 'nope' (it registers: heartbeat)" in result.stderr
    assert result.stdout == ''
