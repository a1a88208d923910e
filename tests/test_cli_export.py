"""`nodl export`: run as a real process, as users run it."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import yaml

from conftest import FIXTURES, REPO

DIALECTS = FIXTURES / 'dialects'
PREFIX = DIALECTS / 'include' / 'prefix'


def nodl(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    result = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                            capture_output=True, timeout=60, env=env)
    assert 'Traceback' not in result.stdout + result.stderr, result.stderr
    return result


def test_export_is_a_registered_verb() -> None:
    result = nodl('--help')
    assert result.returncode == 0
    assert 'export' in result.stdout


def test_convert_then_export_round_trip(tmp_path: Path) -> None:
    converted = nodl('convert', str(DIALECTS / 'genparamlib' / 'gripper_controller.yaml'),
                     '-o', str(tmp_path))
    assert converted.returncode == 0, converted.stdout + converted.stderr
    definition = tmp_path / 'gripper_controller.nodl.yaml'
    out = tmp_path / 'params.yaml'
    result = nodl('export', 'genparamlib', str(definition), '-o', str(out))
    assert result.returncode == 0, result.stdout + result.stderr
    assert 'wrote' in result.stderr and '(6 parameters)' in result.stderr
    data = yaml.safe_load(out.read_text())
    assert list(data) == ['gripper_controller']  # the file name gives the namespace back
    assert data['gripper_controller']['gains']['position']['p']['validation'] == {'gt_eq<>': [0.0]}


def test_export_of_a_node_writes_main_only_unless_asked(tmp_path: Path) -> None:
    env = dict(os.environ, AMENT_PREFIX_PATH=str(PREFIX))
    node = DIALECTS / 'include' / 'arm_driver' / 'nodl' / 'arm_driver.nodl.yaml'
    main_only = nodl('export', 'genparamlib', str(node), '-o', '-', env=env)
    assert main_only.returncode == 0, main_only.stderr
    assert yaml.safe_load(main_only.stdout) == {'arm_driver': {'joint_count': {
        'type': 'int', 'default_value': 6, 'description': 'How many joints the driver commands.'}}}
    everything = nodl('export', 'genparamlib', str(node), '-o', '-', '--with-mixins',
                      '--namespace', 'arm', env=env)
    assert everything.returncode == 0, everything.stderr
    tree = yaml.safe_load(everything.stdout)['arm']
    assert set(tree) == {'heartbeat', 'limits', 'joint_count'}  # never the base's use_sim_time


def test_export_errors_are_one_line(tmp_path: Path) -> None:
    missing = nodl('export', 'genparamlib', str(tmp_path / 'nope.nodl.yaml'), '-o', '-')
    assert missing.returncode == 2 and 'no such file' in missing.stderr
    bad_name = tmp_path / 'my-node.nodl.yaml'
    bad_name.write_text('nodl_version: 2\n')
    result = nodl('export', 'genparamlib', str(bad_name), '-o', '-')
    assert result.returncode == 2 and '--namespace' in result.stderr
    invalid = nodl('export', 'genparamlib',
                   str(DIALECTS / 'include' / 'arm_driver' / 'nodl' / 'broken.nodl.yaml'), '-o', '-')
    assert invalid.returncode == 1 and 'error:' in invalid.stderr and invalid.stdout == ''


def test_export_of_a_registered_node_and_of_an_unregistered_one() -> None:
    env = dict(os.environ, AMENT_PREFIX_PATH=str(REPO / 'tests' / 'fixtures' / 'index' / 'first'))
    result = nodl('export', 'genparamlib', 'alpha', 'talker', '-o', '-', env=env)
    assert result.returncode == 0, result.stderr
    assert yaml.safe_load(result.stdout) == {'talker': {'period': {
        'type': 'double', 'default_value': 0.5, 'description': 'Seconds between two messages.'}}}
    missing = nodl('export', 'genparamlib', 'alpha', 'nobody', '-o', '-', env=env)
    assert missing.returncode == 2 and missing.stdout == ''  # not found: as a missing file
    assert "registers no node definition for 'nobody'" in missing.stderr
