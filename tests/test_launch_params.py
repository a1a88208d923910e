"""Parameter values as launch types them and parameter files read with positions
(nodl.launch.params)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from nodl.launch.errors import LaunchProblem
from nodl.launch.params import coerce_to_type, get_typed_value, load_parameter_file, yaml_value


@pytest.mark.parametrize('text, data_type, value', [
    ('true', None, True), ('1', None, 1), ('1.0', None, 1.0), ('[1, 2]', None, [1, 2]),
    ("'1'", None, '1'), ('1e5', None, '1e5'), ('7', str, '7'), ('7', float, 7.0), ('1', bool, True),
    ('[a, b]', ('list', str), ['a', 'b']),
])
def test_coerce_to_type(text: str, data_type: Any, value: Any) -> None:
    got = coerce_to_type(text, data_type)
    assert got == value and type(got) is type(value)


@pytest.mark.parametrize('text, data_type', [('{a: 1}', None), ('[1, a]', None), ('x', int), ('2', bool)])
def test_coerce_to_type_refuses(text: str, data_type: Any) -> None:
    with pytest.raises(LaunchProblem) as caught:
        coerce_to_type(text, data_type)
    assert caught.value.code == 'NODL518'


_WORDS = ['5.0', '1', '-1', '+1', '0x1F', '0o17', '017', '0b101', '1_000', '1e5', '1.0e+5', '.inf',
          '.NaN', 'true', 'True', 'yes', 'No', 'on', 'OFF', 'y', 'n', 'null', 'Null', '~', '2001-12-14',
          '1:20', '+.5', '.5', '5.', '_', 'a/b', '/x', '-', '--', '---', '...', 'a-b', '0.1.2', '09',
          'a b', '[1]', "'1'", '# c', 'a: 1', '1 # c', '!!str 1', '&a 1', '*a', '', ' 1', '1\n',
          '0', '-0', '+0', '00', '007', '-0.0', '+0.', '05.0', '10', '123456789012345678901234567890',
          '1.5', '-2.25', '3.', 'ON', 'oN', 'NULL', 'nULL', 'Off', 'YES', 'yES', 'tRUE', '١٢']


def test_yaml_value_types_as_safe_load() -> None:
    # yaml_value skips PyYAML's scanner for one plain word; it must type every text as
    # safe_load does (the value, its type and whether it raises), plain words or not.
    import random

    import yaml

    rng = random.Random(9)
    texts = _WORDS + [''.join(rng.choice('aeynoTFx019_.+-/:e ') for _ in range(rng.randint(1, 6)))
                      for _ in range(20000)]
    for text in texts:
        try:
            expected: Any = yaml.safe_load(text)
        except yaml.YAMLError as exc:
            expected = type(exc)
        try:
            got: Any = yaml_value(text)
        except yaml.YAMLError as exc:
            got = type(exc)
        if expected != expected and got != got:  # .nan
            continue
        assert (got, type(got)) == (expected, type(expected)), text


def test_value_sep_lists_are_uniform() -> None:
    assert get_typed_value(['1', '2'], None) == [1, 2]
    with pytest.raises(LaunchProblem):
        get_typed_value(['1', 'true'], None, can_be_str=False)


def test_parameter_files_keep_positions_and_both_typings(tmp_path: Path) -> None:
    path = tmp_path / 'p.yaml'
    path.write_text('/**:\n  ros__parameters:\n    a: y\n    b:\n      c: 1e5\n'
                    'ns:\n  n:\n    ros__parameters: {d: 1}\n')
    loaded = load_parameter_file(path)
    assert loaded.keys == ['/**', 'ns/n'] and not loaded.diagnostics
    star, named = loaded.nodes
    assert star.parameters == {'a': 'y', 'b.c': '1e5'}  # PyYAML, as launch_ros reads it
    assert star.rcl_parameters == {'a': True, 'b.c': 100000.0}  # rcl, as a node reads it
    assert star.positions == {'a': (3, 5), 'b.c': (5, 7)} and named.line == 8


def test_rcl_and_launch_ros_read_aliases_and_merge_keys_each_their_way(tmp_path: Path) -> None:
    import yaml

    path = tmp_path / 'p.yaml'
    text = ('/**:\n  ros__parameters:\n    a: &a {long_name: 1, b: 1}\n'
            '    <<: [*a, {long_name: 2, c: 2}]\n    d: *a\n')
    path.write_text(text)
    loaded = load_parameter_file(path)
    assert loaded.diagnostics == []  # (YAML the strict reader reads)
    # rcl: every alias refused (the file fails), the anchor ignored, '<<' no merge key
    assert [(d.code, d.line, d.column) for d in loaded.rcl_diagnostics] == [
        ('NODL711', 3, 8), ('NODL712', 4, 5), ('NODL710', 4, 10), ('NODL710', 5, 8)]
    assert loaded.rcl_refuses
    # launch_ros (a composable node): what yaml.safe_load gives, merge order included
    (star,) = loaded.composable_nodes
    expected = yaml.safe_load(text)['/**']['ros__parameters']
    assert star.parameters == {'a.long_name': 1, 'a.b': 1, 'long_name': expected['long_name'],
                               'b': 1, 'c': 2, 'd.long_name': 1, 'd.b': 1}
    assert star.positions['c'] == (4, 29) and star.positions['a.b'] == (3, 26)
    # a file without anchors is read alike by both: one reading, no rcl problem
    plain = tmp_path / 'plain.yaml'
    plain.write_text('/**:\n  ros__parameters:\n    a: 1\n')
    loaded = load_parameter_file(plain)
    assert loaded.rcl_diagnostics == [] and not loaded.rcl_refuses
    assert loaded.composable_nodes is loaded.nodes


def test_a_bad_parameter_file_is_coded(tmp_path: Path) -> None:
    path = tmp_path / 'bad.yaml'
    path.write_text('/**:\n  x: 1\n')
    (problem,) = load_parameter_file(path).diagnostics
    assert (problem.code, problem.line) == ('NODL517', 2)
    assert load_parameter_file(tmp_path / 'missing.yaml').diagnostics[0].code == 'NODL517'
    # a path that exists but cannot be read is a diagnostic too, not an escaping OSError
    (folder,) = load_parameter_file(tmp_path).diagnostics
    assert folder.code == 'NODL517' and 'Is a directory' in folder.message


def test_unsafe_text_in_a_parameter_file_is_an_error_at_the_character(tmp_path: Path) -> None:
    """A parameter name or string value holding a control character (NODL221) or a Trojan
    Source bidi control (NODL222) is an error at the character (a raw one, or the escape of a
    double-quoted scalar); RLM in right-to-left text is no finding; the values are kept."""
    hostile = Path(__file__).parent / 'fixtures' / 'launch' / 'text_safety' / 'hostile.params.yaml'
    loaded = load_parameter_file(hostile)
    assert [(d.code, d.line, d.column, d.severity.value) for d in loaded.diagnostics] == [
        ('NODL222', 4, 8, 'error'), ('NODL221', 5, 14, 'error'), ('NODL222', 6, 24, 'error')]
    assert "the parameter name 'la\\u202ebel'" in loaded.diagnostics[0].message
    (node,) = loaded.nodes
    assert node.parameters['prompt'] == '\x1b[2J' and node.parameters['rtl'] == 'שלום\u200f'
    key = tmp_path / 'key.yaml'
    key.write_text('"/a\\u2066b":\n  ros__parameters:\n    x: 1\n', encoding='utf-8')
    assert [(d.code, d.line, d.column) for d in load_parameter_file(key).diagnostics] == [('NODL222', 1, 4)]


def test_a_substituted_text_read_for_many_nodes_is_parsed_once() -> None:
    """The text of one ParameterFile launch_ros evaluated once for many nodes is read once
    (twenty nodes of nav2's bringup read one such file): the same name and text give the same
    reading; another text (or another name) is read on its own."""
    from nodl.launch.params import parse_parameter_text

    text = '/**:\n  ros__parameters:\n    speed: 0.5\n'
    first = parse_parameter_text('/tmp/params_a.yaml', text)
    assert parse_parameter_text('/tmp/params_a.yaml', text) is first
    assert [n.parameters for n in first.nodes] == [{'speed': 0.5}]
    other = parse_parameter_text('/tmp/params_a.yaml', text.replace('0.5', '0.75'))
    assert other is not first and [n.parameters for n in other.nodes] == [{'speed': 0.75}]
    assert parse_parameter_text('/tmp/params_b.yaml', text) is not first
