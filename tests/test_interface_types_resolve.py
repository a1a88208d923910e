"""Resolving type names in the ament index and in a package's source (interface_types.resolve)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl.interface_types import InterfaceIndex, TypeName, interface_index
from nodl.interface_types.resolve import parse_type_name

VENV = str(Path(sys.prefix))
SOURCE = FIXTURES / 'interface_types' / 'types_pkg'


@pytest.fixture(scope='module')
def index() -> InterfaceIndex:
    return InterfaceIndex([VENV], [str(SOURCE)])


@pytest.mark.parametrize('text, namespace, status, found', [
    ('std_msgs/msg/String', 'msg', 'ok', 'std_msgs/msg/String'),
    ('std_msgs/String', 'msg', 'short', 'std_msgs/msg/String'),
    ('std_srvs/Trigger', 'srv', 'short', 'std_srvs/srv/Trigger'),
    ('test_msgs/action/Fibonacci', 'action', 'ok', 'test_msgs/action/Fibonacci'),
    ('std_msgs/srv/String', 'srv', 'wrong_kind', 'std_msgs/msg/String'),
    ('std_msgs/String', 'srv', 'wrong_kind', 'std_msgs/msg/String'),
    ('types_pkg/msg/Status', 'msg', 'ok', 'types_pkg/msg/Status'),
    ('types_pkg/srv/Reset', 'srv', 'ok', 'types_pkg/srv/Reset'),
])
def test_resolution(index: InterfaceIndex, text: str, namespace: str, status: str, found: str) -> None:
    resolution = index.resolve(text, namespace)
    assert resolution.status == status
    assert str(resolution.type) == found


def test_unknown_type_suggests_close_names(index: InterfaceIndex) -> None:
    resolution = index.resolve('sensor_msgs/msg/LaserScn', 'msg')
    assert resolution.status == 'unknown_type' and not resolution.found
    assert resolution.suggestions[0] == 'sensor_msgs/msg/LaserScan'


def test_unknown_and_interfaceless_packages(index: InterfaceIndex) -> None:
    assert index.resolve('no_such_msgs/msg/X', 'msg').status == 'unknown_package'
    assert index.resolve('rclpy/msg/X', 'msg').status == 'no_interfaces'  # installed, no types
    assert index.resolve('std_mgs/msg/String', 'msg').suggestions == ('std_msgs',)


def test_first_prefix_wins_and_files_prefer_idl(tmp_path: Path) -> None:
    overlay = tmp_path / 'overlay'
    (overlay / 'share' / 'ament_index' / 'resource_index' / 'rosidl_interfaces').mkdir(parents=True)
    (overlay / 'share' / 'ament_index' / 'resource_index' / 'rosidl_interfaces' / 'std_msgs'
     ).write_text('msg/Only.msg\nmsg/Only.idl\n', encoding='utf-8')
    index = InterfaceIndex([str(overlay), VENV])
    assert index.resolve('std_msgs/msg/String', 'msg').status == 'unknown_type'
    assert index.file('std_msgs/msg/Only') == str(overlay / 'share' / 'std_msgs' / 'msg' / 'Only.idl')
    assert index.prefix_of('std_msgs') == str(overlay)


def test_source_package_shadows_and_lists_its_types(index: InterfaceIndex) -> None:
    package = index.package('types_pkg')
    assert package is not None and package.origin == 'source'
    assert package.names() == ['types_pkg/msg/Broken', 'types_pkg/msg/Status', 'types_pkg/srv/Reset']
    assert 'types_pkg' in index.interface_packages()


def test_one_index_per_run_inside_a_snapshot() -> None:
    from nodl.ament_index import snapshot

    with snapshot():
        assert interface_index(prefixes=[VENV]) is interface_index(prefixes=[VENV])
    assert interface_index(prefixes=[VENV]) is not interface_index(prefixes=[VENV])


def test_type_names() -> None:
    assert parse_type_name('a_msgs/srv/B') == TypeName('a_msgs', 'srv', 'B')
    assert str(TypeName('a_msgs', 'msg', 'B')) == 'a_msgs/msg/B'
    with pytest.raises(ValueError):
        parse_type_name('a_msgs/B')
