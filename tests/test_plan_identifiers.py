"""Names to identifiers: shapes, keywords, collisions, determinism."""

from __future__ import annotations

import keyword

from nodl.plan.identifiers import CPP_KEYWORDS, IdentifierScope, is_identifier, pascal_case, snake_case


def test_snake_case_of_ros_names() -> None:
    assert snake_case('~/cmd_vel') == 'cmd_vel'
    assert snake_case('/robot/laserScan') == 'robot_laser_scan'
    assert snake_case('camera.frame_id') == 'camera_frame_id'
    assert snake_case('HTTPServer') == 'http_server'
    assert snake_case('~') == '_'
    assert snake_case('{node}/x') == 'node_x'


def test_pascal_case() -> None:
    assert pascal_case('laser_driver') == 'LaserDriver'
    assert pascal_case('camera_lifecycle') == 'CameraLifecycle'
    assert pascal_case('3d_mapper') == 'N3dMapper'
    assert pascal_case('') == 'Node'


def test_keywords_are_renamed_per_language() -> None:
    python = IdentifierScope()
    assert python.assign(['class', 'import', 'match']) == {
        'class': 'class_', 'import': 'import_', 'match': 'match'}
    cpp = IdentifierScope(keywords=CPP_KEYWORDS)
    assert cpp.assign(['delete', 'new', 'value']) == {
        'delete': 'delete_', 'new': 'new_', 'value': 'value'}
    assert all(is_identifier(i) and not keyword.iskeyword(i)
               for i in IdentifierScope().assign(['for', 'while', '0start', '~']).values())


def test_collisions_are_broken_deterministically() -> None:
    names = ['a/b', 'a_b', '~/a/b', 'aB']
    first = IdentifierScope().assign(names, 'pub_{}')
    again = IdentifierScope().assign(list(reversed(names)), 'pub_{}')
    assert first == again
    # the name that already is an identifier keeps the plain form
    assert first['a_b'] == 'pub_a_b'
    assert len(set(first.values())) == len(names)
    assert sorted(first.values()) == ['pub_a_b', 'pub_a_b_2', 'pub_a_b_3', 'pub_a_b_4']


def test_reserved_names_are_avoided() -> None:
    scope = IdentifierScope(reserved={'on_configure'})
    assert scope.assign(['configure'], 'on_{}') == {'configure': 'on_configure_2'}
    assert scope.unique('on_configure') == 'on_configure_3'
