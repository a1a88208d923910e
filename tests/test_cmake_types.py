"""ament_nodl checks the endpoint types at build time (AMENT_NODL_CHECK_TYPES), with a real
colcon build of two packages: one with the check (it fails, at the type: values), one that
turns it off (it builds).

The build uses this tree's ament_nodl CMake files and this tree's library (a `nodl` command
next to them runs `python -m nodl` from the tree), not the installed copies.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO

VENV = Path(sys.prefix)


@pytest.fixture(scope='module')
def build(tmp_path_factory: pytest.TempPathFactory) -> str:
    root = tmp_path_factory.mktemp('types_ws')
    prefix = root / 'ament_nodl_prefix'
    shutil.copytree(REPO / 'ros' / 'ament_nodl' / 'cmake', prefix / 'share' / 'ament_nodl' / 'cmake')
    shutil.copy(REPO / 'ros' / 'ament_nodl' / 'cmake' / 'ament_nodl-config.cmake',
                prefix / 'share' / 'ament_nodl' / 'cmake' / 'ament_nodlConfig.cmake')
    (prefix / 'bin').mkdir()
    command = prefix / 'bin' / 'nodl'
    command.write_text(f'#!/bin/sh\nPYTHONPATH="{REPO}" exec "{sys.executable}" -m nodl "$@"\n',
                       encoding='utf-8')
    command.chmod(0o755)
    src = root / 'src'
    shutil.copytree(FIXTURES / 'colcon_types', src)
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)
    env.update(AMENT_PREFIX_PATH=str(VENV), CMAKE_PREFIX_PATH=f'{prefix}{os.pathsep}{VENV}',
               PATH=os.pathsep.join([str(VENV / 'bin'), env.get('PATH', '')]),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    result = subprocess.run([str(VENV / 'bin' / 'colcon'), 'build', '--continue-on-error',
                             '--event-handlers', 'console_direct+'], cwd=root, env=env, text=True,
                            capture_output=True, timeout=300)
    return result.stdout + result.stderr


def test_the_check_fails_the_build_at_the_type_values(build: str) -> None:
    assert 'Failed   <<< types_bad' in build, build
    talker = 'types_bad/nodl/talker.nodl.yaml'
    assert f"{talker}:7:13: error: 'std_msgs/msg/Strng'" in build and '[NODL251]' in build, build
    assert f"{talker}:11:13: error: package 'sensor_msgs'" in build and '[NODL255]' in build, build
    assert f'{talker}:15:13: warning:' in build and '[NODL257]' in build, build


def test_the_check_can_be_turned_off(build: str) -> None:
    assert 'Finished <<< types_off' in build, build
