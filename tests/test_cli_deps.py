"""`nodl deps`: the files of its package a node definition needs, run as users (and CMake) run it."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from conftest import FIXTURES, REPO

NODE = FIXTURES / 'colcon' / 'relative_mixins' / 'nodl' / 'sensor_node.nodl.yaml'


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    result = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                            capture_output=True, timeout=60)
    assert 'Traceback' not in result.stdout + result.stderr, result.stderr
    return result


def test_lists_the_relative_mixins_one_per_line() -> None:
    result = nodl('deps', str(NODE))
    assert result.returncode == 0, result.stderr
    assert result.stdout == 'diagnostics.yaml\ncommon/limits.nodl.yaml\n../shared/heartbeat.nodl.yaml\n'
    assert result.stderr == ''


def test_a_node_with_only_index_references_has_none() -> None:
    node = REPO / 'examples' / 'workspace' / 'src' / 'laser_driver' / 'nodl' / 'laser_driver_node.nodl.yaml'
    result = nodl('deps', str(node))
    assert (result.returncode, result.stdout) == (0, '')


def test_a_missing_file_is_a_usage_error(tmp_path: Path) -> None:
    result = nodl('deps', str(tmp_path / 'nope.nodl.yaml'))
    assert result.returncode == 2
    assert result.stderr == f'nodl deps: {tmp_path / "nope.nodl.yaml"}: no such file\n'


def test_an_invalid_file_is_an_error_not_silence() -> None:
    """A file that is no valid node definition: its errors, exit 1, nothing listed (a build
    that installs what deps lists would otherwise go on without a word)."""
    bad = FIXTURES / 'deps' / 'invalid.nodl.yaml'
    result = nodl('deps', str(bad))
    assert (result.returncode, result.stdout) == (1, '')
    assert f'{bad}:' in result.stderr and 'error' in result.stderr
    other = FIXTURES / 'launch' / 'not_launch' / 'settings.yaml'
    result = nodl('deps', str(other))
    assert (result.returncode, result.stdout) == (1, '')
    assert 'expected a node definition' in result.stderr


def test_a_mixin_outside_the_package_is_never_listed() -> None:
    """../../shared/x escapes the package (the folder of package.xml): an error (NODL532),
    the path not listed; the mixin inside is."""
    node = FIXTURES / 'deps' / 'escaping_pkg' / 'nodl' / 'node.nodl.yaml'
    result = nodl('deps', str(node))
    assert (result.returncode, result.stdout) == (1, 'limits.yaml\n')
    assert "the mixin '../../shared/heartbeat.nodl.yaml' leads outside the package" in result.stderr
    assert '[NODL532]' in result.stderr


def test_json_lists_the_files_and_the_problems() -> None:
    result = nodl('deps', str(NODE), '--format', 'json')
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout) == {
        'files': ['diagnostics.yaml', 'common/limits.nodl.yaml', '../shared/heartbeat.nodl.yaml'],
        'diagnostics': []}
    assert result.stderr == ''
    # only the formats that show a listing are offered
    sarif = nodl('deps', str(NODE), '--format', 'sarif')
    assert sarif.returncode == 2 and "invalid choice: 'sarif'" in sarif.stderr
