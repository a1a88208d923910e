"""rcl's rules for a parameter file's YAML (nodl.launch.rcl_yaml): which node keys apply to a
node started as a process and to a composable node, and how rcl types a value.  Checked against
real rclpy nodes through the resolution in tests/test_launch_parameter_values.py."""

from __future__ import annotations

import math
from typing import Any

import pytest

from nodl.launch.rcl_yaml import (
    match_composable_parameter_keys,
    match_parameter_file_nodes,
    rcl_scalar,
    rcl_yaml_value,
)


def test_process_key_matching() -> None:
    keys = ['/**', '/*', '/ns/n', 'ns/n', '/**/n', '/ns/*', '/other', 'n', '/ns/**', '/*/*']
    assert match_parameter_file_nodes(keys, '/ns/n') == ['/**', '/ns/n', 'ns/n', '/**/n', '/ns/*',
                                                         '/ns/**', '/*/*']
    assert match_parameter_file_nodes(keys, '/n') == ['/**', '/*', '/**/n', 'n']


def test_composable_key_matching() -> None:
    keys = ['/ns/n', '/**', '/*', 'ns/n', '/ns/*', '**']
    assert match_composable_parameter_keys(keys, 'n', '/ns') == ['/**', '**', '/ns/n', 'ns/n']
    assert match_composable_parameter_keys(keys, None, '/ns') == ['/**', '**']
    assert match_composable_parameter_keys(['/n', 'n'], 'n', '/') == ['/n', 'n']


@pytest.mark.parametrize('text, quoted, value', [
    ('true', False, True), ('Y', False, True), ('off', False, False), ('yes', True, 'yes'),
    ('12', False, 12), ('-0x1f', False, -31), ('010', False, 8), ('0', False, 0),
    ('1e5', False, 100000.0), ('.5', False, 0.5), ('-.inf', False, -math.inf), ('1_000', False, '1_000'),
    ('1e999', False, '1e999'), ('9223372036854775808', False, 9.223372036854776e18),
    ('12', True, '12'), ('abc', False, 'abc'), ('', False, ''),
    # past int64 in any base: strtoll fails; 5,000 digits also passed Python's int() limit
    ('1' * 5000, False, '1' * 5000), ('0' * 50 + '10', False, 8), ('0x' + '0' * 40 + '1f', False, 31),
    ('-' + '7' * 30, False, -7.777777777777778e29), ('0x' + 'f' * 300, False, '0x' + 'f' * 300),
])
def test_rcl_scalar_typing(text: str, quoted: bool, value: Any) -> None:
    got = rcl_scalar(text, quoted=quoted)
    assert type(got) is type(value) and got == value


def test_rcl_yaml_value() -> None:
    assert rcl_yaml_value('[1, 2]') == [1, 2]
    assert rcl_yaml_value("['a', y]") == ['a', True]
    assert rcl_yaml_value('!!str 5') == '5'
    assert rcl_yaml_value('{a: 1}') == '{a: 1}'


def test_parameter_file_matching() -> None:
    keys = ['/**', '/*', '/ns/n', 'ns/n', '/**/n', '/ns/*', '/other', 'n']
    assert match_parameter_file_nodes(keys, '/ns/n') == ['/**', '/ns/n', 'ns/n', '/**/n', '/ns/*']
    assert match_parameter_file_nodes(keys, '/n') == ['/**', '/*', '/**/n', 'n']
    assert match_composable_parameter_keys(['/ns/n', '/**', '/*', 'ns/n'], 'n', '/ns') == ['/**', '/ns/n', 'ns/n']
