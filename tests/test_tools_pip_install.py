"""tools/pip_install.py: the Makefile's installer prints progress a person can follow.

Real pip, offline: three small wheels (a needs b, b needs c) are written to a folder
and installed from it into a prefix.
"""

from __future__ import annotations

import base64
import hashlib
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from conftest import REPO

SCRIPT = REPO / 'tools' / 'pip_install.py'


def write_wheel(folder: Path, name: str, requires: list[str]) -> None:
    dist_info = f'{name}-1.0.dist-info'
    files = {
        f'{name}_module.py': 'VALUE = 1\n',
        f'{dist_info}/METADATA': ''.join(['Metadata-Version: 2.1\n', f'Name: {name}\n',
                                          'Version: 1.0\n',
                                          *(f'Requires-Dist: {r}\n' for r in requires)]),
        f'{dist_info}/WHEEL': 'Wheel-Version: 1.0\nGenerator: test\nRoot-Is-Purelib: true\n'
                              'Tag: py3-none-any\n',
    }
    record = []
    for path, text in files.items():
        digest = base64.urlsafe_b64encode(hashlib.sha256(text.encode()).digest()).rstrip(b'=')
        record.append(f'{path},sha256={digest.decode()},{len(text.encode())}')
    record.append(f'{dist_info}/RECORD,,')
    files[f'{dist_info}/RECORD'] = '\n'.join(record) + '\n'
    with zipfile.ZipFile(folder / f'{name}-1.0-py3-none-any.whl', 'w') as wheel:
        for path, text in files.items():
            wheel.writestr(path, text)


@pytest.fixture
def wheels(tmp_path: Path) -> Path:
    folder = tmp_path / 'wheels'
    folder.mkdir()
    write_wheel(folder, 'nodltesta', ['nodltestb'])
    write_wheel(folder, 'nodltestb', ['nodltestc'])
    write_wheel(folder, 'nodltestc', [])
    return folder


def install(wheels: Path, prefix: Path, *requirements: str) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k != 'PIP_REQUIRE_VIRTUALENV'}
    return subprocess.run([sys.executable, str(SCRIPT), '--no-index', '--find-links', str(wheels),
                           '--prefix', str(prefix), *requirements],
                          capture_output=True, text=True, timeout=120, env=env)


def test_one_line_per_package_then_a_summary(wheels: Path, tmp_path: Path) -> None:
    result = install(wheels, tmp_path / 'prefix', 'nodltesta')
    assert result.returncode == 0, result.stdout + result.stderr
    lines = result.stdout.splitlines()
    assert [line for line in lines if 'resolving' in line] == [
        '  resolving [1] nodltesta-1.0-py3-none-any.whl', '  resolving [2] nodltestb-1.0-py3-none-any.whl',
        '  resolving [3] nodltestc-1.0-py3-none-any.whl']
    assert '  installing 3 packages (this takes a while the first time)' in lines
    assert lines[-1].startswith('  installed 3 packages in ')
    # pip's own chatter is not repeated
    assert not [line for line in lines if not line.startswith('  ')], lines
    assert list((tmp_path / 'prefix').rglob('nodltestc_module.py'))


def test_a_failure_shows_the_end_of_pips_output(wheels: Path, tmp_path: Path) -> None:
    result = install(wheels, tmp_path / 'prefix', 'nodltest-missing')
    assert result.returncode != 0
    assert 'ERROR: ' in result.stdout
    assert 'pip failed; the end of its output:' in result.stderr
    assert 'nodltest-missing' in result.stderr
