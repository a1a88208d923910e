"""Parameter precedence and typing (nodl.launch.parameter_values) against REAL rclpy nodes.

Every case of tests/fixtures/launch/parameter_precedence.yaml is resolved twice: by a real
rclpy node (in this process, one context per case) given the command line launch_ros
writes for the launch entry, and by the launch reader + :func:`parameter_overrides`.
Composable nodes (loaded by a container, which cannot run here) follow launch_ros's
``to_parameters_list``, pinned by the unit cases below.
"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path
from typing import Any

import pytest
import yaml

from conftest import FIXTURES
from nodl.launch import load_launch
from nodl.launch.model import ParameterSource, SourceLocation
from nodl.launch.parameter_values import composable_overrides, parameter_overrides

TABLE = yaml.safe_load((FIXTURES / 'launch' / 'parameter_precedence.yaml').read_text(encoding='utf-8'))
CASES: list[dict[str, Any]] = TABLE['cases']
#: Parameters every rclpy node declares itself.
_OWN = {'use_sim_time', 'start_type_description_service'}


def _setup(case: dict[str, Any], tmp_path: Path) -> tuple[str | None, str | None, dict[str, str]]:
    paths = {}
    for key, text in (case.get('files') or {}).items():
        path = tmp_path / f'{key}.yaml'
        path.write_text(text, encoding='utf-8')
        paths[key] = str(path)
    return case.get('name', 'n'), case.get('namespace', '/ns'), paths


def _word(word: Any, paths: dict[str, str]) -> Any:
    return paths[word[1:]] if isinstance(word, str) and word.startswith('@') else word


def _launch_ros_argv(case: dict[str, Any], name: str | None, namespace: str | None,
                     paths: dict[str, str], tmp_path: Path) -> list[str]:
    """The ROS arguments launch_ros's Node writes for the entry (launch_ros/actions/node.py)."""
    argv = ['--ros-args', *[_word(w, paths) for w in case.get('ros_args', [])], '--ros-args']
    if name is not None:
        argv += ['-r', f'__node:={name}']
    if namespace is not None:
        argv += ['-r', f'__ns:={namespace}']
    for item in case.get('global', []):
        if isinstance(item, dict):
            (key, value), = item.items()
            argv += ['-p', f'{key}:={value}']
        else:
            argv += ['--params-file', _word(item, paths)]
    fully = name is not None and namespace is not None
    for index, item in enumerate(case.get('parameters', [])):
        if isinstance(item, dict) and 'parameter' in item:
            key, value = item['parameter']
            argv += ['-p', f'{key}:={yaml.dump(value)}']
        elif isinstance(item, dict):
            node_key = f"{'' if namespace == '/' else namespace}/{name}" if fully else '/**'
            path = tmp_path / f'launch_params_{index}.yaml'
            path.write_text(yaml.dump({node_key: {'ros__parameters': item}}, default_flow_style=False))
            argv += ['--params-file', str(path)]
        else:
            argv += ['--params-file', _word(item, paths)]
    return argv


def _rclpy_values(argv: list[str]) -> dict[str, Any]:
    import rclpy
    from rclpy.node import Node

    context = rclpy.Context()
    rclpy.init(context=context, args=[])
    try:
        node = Node('talker', cli_args=argv, context=context, use_global_arguments=False,
                    start_parameter_services=False, enable_rosout=False,
                    automatically_declare_parameters_from_overrides=True)
        try:
            values = {k: p.value for k, p in node._parameters.items() if k not in _OWN}
            return {k: list(v) if isinstance(v, (list, tuple)) or type(v).__name__ == 'ndarray' else v
                    for k, v in values.items()}
        finally:
            node.destroy_node()
    finally:
        rclpy.shutdown(context=context)


def _launch_file(case: dict[str, Any], name: str | None, namespace: str | None,
                 paths: dict[str, str], tmp_path: Path) -> Path:
    lines = []
    for item in case.get('global', []):
        if isinstance(item, dict):
            (key, value), = item.items()
            lines.append(f'SetParameter(name={key!r}, value={value!r}),')
        else:
            lines.append(f'SetParametersFromFile({_word(item, paths)!r}),')
    parameters = []
    for item in case.get('parameters', []):
        if isinstance(item, dict) and 'parameter' in item:
            parameters.append(f'Parameter({item["parameter"][0]!r}, {item["parameter"][1]!r})')
        else:
            parameters.append(repr(_word(item, paths)))
    ros_args = [_word(w, paths) for w in case.get('ros_args', [])]
    lines.append(f'Node(package="p", executable="talker", name={name!r}, namespace={namespace!r}, '
                 f'ros_arguments={ros_args!r}, parameters=[{", ".join(parameters)}]),')
    path = tmp_path / 'case.launch.py'
    path.write_text(textwrap.dedent('''\
        from launch import LaunchDescription
        from launch_ros.actions import Node, SetParameter, SetParametersFromFile
        from launch_ros.descriptions import Parameter
        def generate_launch_description():
            return LaunchDescription([
        ''') + ''.join(f'        {line}\n' for line in lines) + '    ])\n', encoding='utf-8')
    return path


def _same(actual: dict[str, Any], expected: dict[str, Any]) -> bool:
    def one(a: Any, e: Any) -> bool:
        if isinstance(e, float) and isinstance(a, float):
            return a == e or (math.isinf(a) and math.isinf(e) and (a > 0) == (e > 0))
        if isinstance(e, list):
            return isinstance(a, list) and len(a) == len(e) and all(one(x, y) for x, y in zip(a, e, strict=True))
        return type(a) is type(e) and a == e
    return actual.keys() == expected.keys() and all(one(actual[k], expected[k]) for k in expected)


@pytest.mark.parametrize('case', CASES, ids=[c['id'] for c in CASES])
def test_rclpy_receives_the_expected_values(case: dict[str, Any], tmp_path: Path) -> None:
    name, namespace, paths = _setup(case, tmp_path)
    values = _rclpy_values(_launch_ros_argv(case, name, namespace, paths, tmp_path))
    assert _same(values, case['expected']), values


@pytest.mark.parametrize('case', CASES, ids=[c['id'] for c in CASES])
def test_the_launch_reader_resolves_what_rclpy_receives(case: dict[str, Any], tmp_path: Path) -> None:
    name, namespace, paths = _setup(case, tmp_path)
    result = load_launch(_launch_file(case, name, namespace, paths, tmp_path), {})
    assert result.ok, [str(d) for d in result.diagnostics]
    (node,) = result.nodes
    fqn = f"{namespace if namespace not in (None, '/') else ''}/{name or 'talker'}"
    overrides = parameter_overrides(node, None if name else fqn)
    values = {k: v.value for k, v in overrides.items()}
    assert _same(values, case['expected']), values


def test_an_override_says_where_it_was_written(tmp_path: Path) -> None:
    params = tmp_path / 'p.yaml'
    params.write_text('/**:\n  ros__parameters:\n    x: 1\n/ns/n:\n  ros__parameters:\n    x: 3\n')
    main = tmp_path / 'm.launch.xml'
    main.write_text(f'<launch>\n<node pkg="p" exec="e" name="n" namespace="ns">\n'
                    f'  <param from="{params}"/>\n  <param name="y" value="2"/>\n</node>\n</launch>\n')
    (node,) = load_launch(main, {}).nodes
    overrides = parameter_overrides(node)
    assert overrides['x'][1:] == (3, str(params), 6, 5, 'node', 'file', '/ns/n')
    assert overrides['y'][1:] == (2, str(main), 4, 3, 'node', 'values', '/ns/n')  # its <param>


def test_an_unnamed_node_needs_its_full_name(tmp_path: Path) -> None:
    main = tmp_path / 'm.launch.xml'
    main.write_text('<launch><node pkg="p" exec="e"/></launch>')
    (node,) = load_launch(main, {}).nodes
    assert node.name is None and node.fqn is None
    with pytest.raises(ValueError):
        parameter_overrides(node)
    assert parameter_overrides(node, '/e') == {}


def _file_source(path: Path, origin: str = 'node') -> ParameterSource:
    return ParameterSource('file', origin, SourceLocation('l.launch.xml', 1, 1), path=str(path))


def _values_source(values: dict[str, Any], origin: str = 'node') -> ParameterSource:
    return ParameterSource('values', origin, SourceLocation('l.launch.xml', 2, 1), values=values)


def test_composable_overrides_follow_launch_ros(tmp_path: Path) -> None:
    # to_parameters_list: per file /** then the exact name (whatever their order), a later
    # equal key replaces an earlier one whole, wildcards other than /** never apply, values
    # typed by PyYAML ('y' stays a string, '1e5' too), later sources win.
    one = tmp_path / 'one.yaml'
    one.write_text('/ns/n:\n  ros__parameters: {x: 1, z: 1}\n/**:\n  ros__parameters: {x: 2, w: y}\n'
                   '/ns/*:\n  ros__parameters: {v: 1}\nns:\n  n:\n    ros__parameters: {x: 5, u: 1e5}\n')
    two = tmp_path / 'two.yaml'
    two.write_text('/**:\n  ros__parameters: {t: 1}\n')
    values = {k: o.value for k, o in composable_overrides(
        [_file_source(one, 'global'), _values_source({'t': 0}), _file_source(two)], 'n', '/ns').items()}
    assert values == {'x': 5, 'w': 'y', 'u': '1e5', 't': 1}
    unnamed = composable_overrides([_file_source(one)], None, '/ns')
    assert {k: o.value for k, o in unnamed.items()} == {'x': 2, 'w': 'y'}


def test_a_composable_record_uses_launch_ros_rules(tmp_path: Path) -> None:
    params = tmp_path / 'p.yaml'
    params.write_text('/**/cam:\n  ros__parameters: {x: 1}\n/rig/cam:\n  ros__parameters: {y: 2}\n')
    main = tmp_path / 'm.launch.xml'
    main.write_text(f'<launch><node_container pkg="rclcpp_components" exec="component_container" '
                    f'name="c" namespace="rig"><composable_node pkg="p" plugin="p::Cam" name="cam" '
                    f'namespace="rig"><param from="{params}"/></composable_node></node_container></launch>')
    container, cam = load_launch(main, {}).nodes
    assert {k: o.value for k, o in parameter_overrides(cam).items()} == {'y': 2}
    assert parameter_overrides(container) == {}


def test_a_long_text_is_typed_as_its_yaml_dump_is_read_without_dumping_it() -> None:
    """A text past 1,024 characters that rcl reads as a string skips yaml.dump and the
    re-read (pure Python: 20 s for 16 MiB); the result is what that round trip gives."""
    import random
    import time

    from nodl.launch.parameter_values import as_rcl_reads_dump
    from nodl.launch.rcl_yaml import rcl_yaml_value

    rng = random.Random(15)
    alphabet = 'ab01 .:-#\'"\n\té\\[]{}xXeE+_'
    texts = [''.join(rng.choice(alphabet) for _ in range(rng.randint(1025, 3000))) for _ in range(300)]
    texts += ['1' * 1100, '0x' + 'f' * 1100, '1' * 1100 + 'e5', 'y' * 1100, ' ' * 1100 + '5', '0' * 1100 + '7']
    for text in texts:
        assert as_rcl_reads_dump(text) == rcl_yaml_value(yaml.dump(text)), text[:40]
    description = '<robot name="r">' + '<link name="l"/>\n' * 300_000 + '</robot>'  # 5 MB
    start = time.perf_counter()
    assert as_rcl_reads_dump(description) is description
    assert time.perf_counter() - start < 1.0  # was ~6 s
