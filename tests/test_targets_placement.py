"""Definitions placed by name: what the command line's first target names (nodl.targets.placement)."""

from __future__ import annotations

from pathlib import Path

from conftest import FIXTURES, REPO
from nodl.targets.placement import names_definitions


def test_the_first_target_names_definitions_or_a_launch_file(tmp_path: Path) -> None:
    assert names_definitions(str(REPO / 'examples' / 'laser_driver.nodl.yaml'))
    assert names_definitions('demo_nodes_cpp')  # PACKAGE of PACKAGE EXECUTABLE
    assert not names_definitions(str(FIXTURES / 'analysis' / 'launch' / 'system.launch.xml'))
    assert not names_definitions('missing.launch.py')  # named as a launch file: its reader says why
    assert not names_definitions(str(tmp_path / 'missing.yaml'))
    assert not names_definitions(str(tmp_path))
    launch = tmp_path / 'bringup.yaml'  # a launch file by its text, not its name
    launch.write_text('launch:\n- node: {pkg: demo_nodes_cpp, exec: talker}\n')
    assert not names_definitions(str(launch))
