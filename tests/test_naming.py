"""Expanding ROS names against a node (as rcl does) and the reverse, for describe."""

from __future__ import annotations

import itertools

import pytest

from nodl_schema.naming import expand, fully_qualified, relativize


@pytest.mark.parametrize('namespace, name, fqn', [
    ('/', 'driver', '/driver'),
    ('', 'driver', '/driver'),
    ('/robot', 'driver', '/robot/driver'),
    ('/robot/', 'driver', '/robot/driver'),
    ('robot', 'driver', '/robot/driver'),
    ('/a/b', 'driver', '/a/b/driver'),
])
def test_fully_qualified(namespace: str, name: str, fqn: str) -> None:
    assert fully_qualified(namespace, name) == fqn


@pytest.mark.parametrize('name, namespace, expected', [
    # private names
    ('~', '/robot', '/robot/driver'),
    ('~', '/', '/driver'),
    ('~/scan', '/robot', '/robot/driver/scan'),
    ('~/scan', '/', '/driver/scan'),
    ('~/a/b', '/x/y', '/x/y/driver/a/b'),
    # relative names
    ('scan', '/robot', '/robot/scan'),
    ('scan', '/', '/scan'),
    ('a/b', '/x/y', '/x/y/a/b'),
    ('driver', '/robot', '/robot/driver'),
    # absolute names stay
    ('/scan', '/robot', '/scan'),
    ('/scan', '/', '/scan'),
    ('/robot/driver/scan', '/other', '/robot/driver/scan'),
    # substitutions
    ('{node}', '/robot', '/robot/driver'),
    ('{node}/scan', '/robot', '/robot/driver/scan'),
    ('{node}/scan', '/', '/driver/scan'),
    ('/{node}/scan', '/robot', '/driver/scan'),
    ('{ns}/scan', '/robot', '/robot/scan'),
    ('{namespace}/scan', '/a/b', '/a/b/scan'),
    ('{ns}', '/robot', '/robot'),
    ('scan/{node}', '/robot', '/robot/scan/driver'),
    ('{namespace}/{node}/x', '/r', '/r/driver/x'),
])
def test_expand(name: str, namespace: str, expected: str) -> None:
    assert expand(name, 'driver', namespace) == expected


def test_expand_tolerates_namespaces_written_without_or_with_extra_slashes() -> None:
    assert expand('scan', 'driver', 'robot') == '/robot/scan'
    assert expand('scan', 'driver', '/robot/') == '/robot/scan'
    assert expand('~/scan', 'driver', 'robot/') == '/robot/driver/scan'


_NAMES = ['x', 'x/y', '/x', '/x/y', '~', '~/x', '~/x/y', '{node}', '{node}/x', 'x/{node}',
          '{ns}/x', '{namespace}/x', '{namespace}/{node}', 'drv', 'drv/x', 'a/x']
_NAMESPACES = ['/', '/a', '/a/b']


@pytest.mark.parametrize('name, namespace', list(itertools.product(_NAMES, _NAMESPACES)))
def test_expand_agrees_with_rcl(name: str, namespace: str) -> None:
    """rcl itself (through rclpy) is the reference for every valid namespace."""
    from rclpy.expand_topic_name import expand_topic_name

    assert expand(name, 'drv', namespace) == expand_topic_name(name, 'drv', namespace)


@pytest.mark.parametrize('name, namespace, expected', [
    ('/robot/driver', '/robot', '~'),
    ('/robot/driver/scan', '/robot', '~/scan'),
    ('/robot/driver/a/b', '/robot', '~/a/b'),
    ('/robot/scan', '/robot', 'scan'),
    ('/robot/sub/scan', '/robot', 'sub/scan'),
    ('/scan', '/robot', '/scan'),
    ('/other/scan', '/robot', '/other/scan'),
    # a sibling whose name merely starts with the node's name is not under the node
    ('/robot/driver2/scan', '/robot', 'driver2/scan'),
    ('/robotics/scan', '/robot', '/robotics/scan'),
    # the namespace itself is not "under" it
    ('/robot', '/robot', '/robot'),
    # root namespace: names under the node are private, the rest stays absolute
    ('/driver', '/', '~'),
    ('/driver/scan', '/', '~/scan'),
    ('/scan', '/', '/scan'),
    ('/a/b', '/', '/a/b'),
    ('/x/y/driver/scan', '/x/y', '~/scan'),
    ('/x/y/scan', '/x/y', 'scan'),
    ('/x/scan', '/x/y', '/x/scan'),
])
def test_relativize(name: str, namespace: str, expected: str) -> None:
    assert relativize(name, 'driver', namespace) == expected


@pytest.mark.parametrize('name', ['/driver', '/driver/scan', '/scan', '/robot/driver',
                                  '/robot/driver/scan', '/robot/scan', '/robot/driver2/x',
                                  '/robotics/x', '/a/b/c', '/robot'])
@pytest.mark.parametrize('namespace', ['/', '/robot', '/robot/', 'robot'])
def test_relativize_then_expand_gives_the_name_back(name: str, namespace: str) -> None:
    short = relativize(name, 'driver', namespace)
    assert expand(short, 'driver', namespace) == name
    assert len(short) <= len(name)
