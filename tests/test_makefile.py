"""The Makefile: a .venv of another interpreter is rebuilt; a wrong interpreter is refused.

The ROS 2 wheels exist for CPython 3.11 only. These run the real make on throwaway
virtual environment folders (``VENV=...``); nothing is installed (``make -n`` prints
the recipe, and the refusal stops before anything is made).
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

from conftest import REPO
from test_python_versions import find_interpreter


def make(*args: str) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ('MAKEFLAGS', 'MAKELEVEL', 'MFLAGS')}
    return subprocess.run(['make', '--no-print-directory', *args], cwd=REPO, env=env, text=True,
                          capture_output=True, timeout=120)


def test_a_venv_of_another_python_is_rebuilt(tmp_path: Path) -> None:
    venv = tmp_path / 'venv'
    made = subprocess.run([find_interpreter('3.12'), '-m', 'venv', '--without-pip', str(venv)],
                          capture_output=True, text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    # up to date by the timestamps: only the interpreter makes it stale
    (venv / '.deps').touch()
    (venv / '.installed').touch()
    result = make('-n', 'install', f'VENV={venv}')
    assert result.returncode == 0, result.stderr
    assert 'if [ -n "yes" ]' in result.stdout
    assert f'make: {venv} was made with Python 3.12 or its interpreter is gone' in result.stdout
    assert f'rm -rf {venv}' in result.stdout


def test_a_venv_of_the_right_python_is_kept(tmp_path: Path) -> None:
    venv = tmp_path / 'venv'
    made = subprocess.run([find_interpreter('3.11'), '-m', 'venv', '--without-pip', str(venv)],
                          capture_output=True, text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    result = make('-n', 'install', f'VENV={venv}')
    assert result.returncode == 0, result.stderr
    assert 'if [ -n "" ]' in result.stdout


def test_an_interpreter_that_cannot_load_the_wheels_is_refused(tmp_path: Path) -> None:
    python = find_interpreter('3.12')
    result = make('install', f'PYTHON={python}', f'VENV={tmp_path / "venv"}')
    assert result.returncode != 0
    assert f"make: '{python}' is not Python 3.11, which the ROS 2 wheels need." in result.stdout
    assert not (tmp_path / 'venv').exists()
