"""What a file given as a launch file is, when it is something else (launch/file_kind.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl.launch.file_kind import not_a_launch_file

FIXTURES = Path(__file__).parent / 'fixtures'
OTHER = FIXTURES / 'launch' / 'not_launch'


@pytest.mark.parametrize(('path', 'what'), [
    (FIXTURES / 'analysis' / 'prefix' / 'share' / 'nav' / 'nodl' / 'planner.nodl.yaml',
     'a NoDL node definition'),
    (FIXTURES / 'analysis' / 'prefix' / 'share' / 'nav' / 'package.xml',
     'a package manifest (package.xml)'),
    (OTHER / 'params.yaml', 'a ROS parameter file'),
    (OTHER / 'notes.md', 'neither an XML, a YAML nor a Python launch file'),
    (OTHER / 'tool.py', 'a Python file without generate_launch_description()'),
    (OTHER / 'robot.urdf', 'an XML file whose root element is <robot>, not <launch>'),
    (OTHER / 'settings.yaml', "a YAML file without the key 'launch' (its keys: 'settings')"),
], ids=lambda v: v.name if isinstance(v, Path) else None)
def test_a_file_that_is_no_launch_file_is_named(path: Path, what: str) -> None:
    assert not_a_launch_file(str(path)) == what


@pytest.mark.parametrize('name', ['checks.launch.xml', 'system.launch.yaml', 'system.launch.py',
                                  'broken_params.launch.xml'])
def test_a_launch_file_is_left_to_its_reader(name: str) -> None:
    assert not_a_launch_file(str(FIXTURES / 'analysis' / 'launch' / name)) is None
