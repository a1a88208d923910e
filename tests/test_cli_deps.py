"""`nodl deps`: the files of its package a node definition needs, run as users (and CMake) run it."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from conftest import FIXTURES, REPO

NODE = FIXTURES / 'colcon' / 'relative_mixins' / 'nodl' / 'sensor_node.nodl.yaml'


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    result = subprocess.run([sys.executable, '-m', 'nodl_schema', *args], cwd=REPO, text=True,
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


def test_an_invalid_file_has_no_dependencies(tmp_path: Path) -> None:
    # what is wrong with it is `nodl validate`'s to say (at build time, with positions)
    bad = tmp_path / 'bad.nodl.yaml'
    bad.write_text('nodl_version: 2\nmixins: [a.yaml\n')
    result = nodl('deps', str(bad))
    assert (result.returncode, result.stdout) == (0, '')
