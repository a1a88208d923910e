"""The XML and YAML launch frontends (nodl.launch.markup_actions, xml_frontend,
yaml_frontend): strictness with "did you mean" at FILE:LINE:COL, and parameters typed as
launch types them (YAML rules, value-sep, type)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from nodl.launch import load_launch


def _diagnostics(tmp_path: Path, name: str, text: str) -> list[Any]:
    main = tmp_path / name
    main.write_text(text, encoding='utf-8')
    return [(d.code, d.line, d.column, d.message) for d in load_launch(main, {}).diagnostics]


@pytest.mark.parametrize('name, text, expected', [
    ('a.launch.xml', '<launch>\n  <nod pkg="p" exec="e"/>\n</launch>\n',
     ('NODL501', 2, 3, "did you mean 'node'?")),
    ('a.launch.xml', '<launch>\n  <node pkg="p" exec="e"\n        nmae="x"/>\n</launch>\n',
     ('NODL502', 3, 9, "did you mean 'name'?")),
    ('a.launch.xml', '<launch>\n  <node pkg="p" exec="e">\n    <remap form="a" to="b"/>\n  </node>\n</launch>\n',
     ('NODL502', 3, 12, "did you mean 'from'?")),
    ('a.launch.xml', '<launch>\n  <node pkg="p" exec="e">\n    <parm name="a" value="1"/>\n  </node>\n</launch>\n',
     ('NODL501', 3, 5, "did you mean 'param'?")),
    ('a.launch.yaml', 'launch:\n  - nod: {pkg: p, exec: e}\n', ('NODL501', 2, 5, "did you mean 'node'?")),
    ('a.launch.yaml', 'launch:\n  - node:\n      pkg: p\n      exec: e\n      nmae: x\n',
     ('NODL502', 5, 7, "did you mean 'name'?")),
    ('a.launch.yaml', 'launch:\n  - node: {pkg: p}\n', ('NODL503', 2, 5, "'exec'")),
    ('a.launch.xml', '<launch>\n  <node pkg="p" exec="e" if="1" unless="0"/>\n</launch>\n',
     ('NODL504', 2, 3, "both 'if' and 'unless'")),
    ('a.launch.xml', '<launch>\n  <group scoped="maybe"/>\n</launch>\n', ('NODL504', 2, 10, 'true or false')),
    ('a.launch.xml', '<lunch/>\n', ('NODL501', 1, 1, '<launch>')),
    # launch_xml splits a list only with NAME-sep: 'sep' alone is an unexpected attribute there.
    ('a.launch.xml', '<launch>\n  <node pkg="p" exec="e">\n    <param name="l" value="1,2" sep=","/>\n'
     '  </node>\n</launch>\n', ('NODL502', 3, 33, "did you mean 'value-sep'?")),
    # launch_yaml reads no NAME-sep (a list is a YAML list) and rejects every key it did not read
    ('a.launch.yaml', 'launch:\n  - node:\n      pkg: p\n      exec: e\n      param:\n'
     '        - {name: l, value: "1,2", value-sep: ","}\n',
     ('NODL502', 6, 35, "unknown attribute 'value-sep' of <param>; did you mean 'value'? ('value-sep' is "
      "launch_xml's: in a YAML launch file a list value is a YAML list")),
    ('a.launch.yaml', 'launch:\n  - node_container:\n      pkg: p\n      exec: e\n      name: c\n'
     '      composable_node:\n        - pkg: q\n          plugin: q::C\n          name: n\n'
     '          param:\n            - {name: l, value: "a;b", value-sep: ";"}\n',
     ('NODL502', 11, 39, "unknown attribute 'value-sep' of <param>")),
    ('a.launch.yaml', 'launch:\n  - node:\n      pkg: p\n      exec: e\n      xmlns: x\n',
     ('NODL502', 5, 7, "unknown attribute 'xmlns' of <node>")),
    # launch_yaml checks a YAML value against 'type' (no conversion): 1 is not a float there
    ('a.launch.yaml', 'launch:\n  - node:\n      pkg: p\n      exec: e\n      param:\n'
     '        - {name: f, value: 1, type: float}\n', ('NODL518', 6, 21, "is not of type 'float'")),
    ('a.launch.yaml', 'launch:\n  - node:\n      pkg: p\n      exec: e\n      param:\n'
     '        - {name: f, value: [1, 2], type: list_of_str}\n', ('NODL518', 6, 21, "type 'list_of_str'")),
    ('a.launch.yaml', 'launch:\n  - node:\n      pkg: p\n      exec: e\n      param:\n'
     '        - {name: f, value: {a: 1}}\n', ('NODL518', 6, 21, 'is not a parameter value')),
    ('a.launch.yaml', 'launch:\n  - node:\n      pkg: p\n      exec: e\n      param:\n'
     '        - {name: f, value: ~}\n', ('NODL503', 6, 21, "needs a 'value'")),
])
def test_unknown_or_wrong_entities_are_placed(tmp_path: Path, name: str, text: str,
                                             expected: tuple[str, int, int, str]) -> None:
    found = _diagnostics(tmp_path, name, text)
    assert any(f[:3] == expected[:3] and expected[3] in f[3] for f in found), found


def _values(tmp_path: Path, name: str, text: str) -> dict[str, Any]:
    main = tmp_path / name
    main.write_text(text, encoding='utf-8')
    result = load_launch(main, {})
    assert result.ok, [str(d) for d in result.diagnostics]
    return {k: v for p in result.nodes[0].parameters for k, v in p.values.items()}


def test_xml_parameters_are_typed_as_launch_types_them(tmp_path: Path) -> None:
    values = _values(tmp_path, 'p.launch.xml', '''<launch><node pkg="p" exec="e" name="n">
      <param name="a" value="true"/><param name="b" value="1"/><param name="c" value="1.0"/>
      <param name="d" value="[1, 2]"/><param name="e" value="'1'"/>
      <param name="f" value="1,2,3" value-sep=","/><param name="g" value="7" type="str"/>
      <param name="h" value="a;b" value-sep=";"/><param name="i" value="1e5"/>
      <param name="j"><param name="k" value="2"/></param></node></launch>''')
    assert values == {'a': True, 'b': 1, 'c': 1.0, 'd': [1, 2], 'e': '1', 'f': [1, 2, 3], 'g': '7',
                      'h': ['a', 'b'], 'i': '1e5', 'j.k': 2}
    assert [type(values[k]) for k in 'abcegi'] == [bool, int, float, str, str, str]


def test_yaml_parameters_are_typed_as_launch_types_them(tmp_path: Path) -> None:
    # the YAML frontend hands launch the text of scalars: a quoted '1' is read again as YAML
    values = _values(tmp_path, 'p.launch.yaml', '''launch:
  - node:
      pkg: p
      exec: e
      name: n
      param:
        - {name: a, value: true}
        - {name: b, value: 1}
        - {name: c, value: 1.0}
        - {name: d, value: [1, 2]}
        - {name: e, value: '1'}
        - {name: g, value: "true"}
        - {name: h, value: [a, b]}
        - {name: i, value: '7', type: str}
        - {name: j, value: '7', type: float}
        - {name: k, value: [a, b], type: list_of_str}
''')
    assert values == {'a': True, 'b': 1, 'c': 1.0, 'd': [1, 2], 'e': 1, 'g': True, 'h': ['a', 'b'], 'i': '7',
                      'j': 7.0, 'k': ['a', 'b']}


@pytest.mark.parametrize('param, code', [
    ('<param name="a" value="x" type="integer"/>', 'NODL504'),
    ('<param name="a" value="{b: 1}"/>', 'NODL518'),
    ('<param name="a" value="1" from="f.yaml"/>', 'NODL504'),
    ('<param name="a"/>', 'NODL503'),
])
def test_bad_parameters_are_coded(tmp_path: Path, param: str, code: str) -> None:
    found = _diagnostics(tmp_path, 'b.launch.xml', f'<launch><node pkg="p" exec="e">{param}</node></launch>')
    assert code in [f[0] for f in found], found


def test_scoped_and_unscoped_groups(tmp_path: Path) -> None:
    main = tmp_path / 's.launch.xml'
    main.write_text('''<launch>
  <group><push-ros-namespace namespace="in"/><let name="x" value="1"/></group>
  <node pkg="p" exec="a" name="a$(var x 0)"/>
  <group scoped="false"><push-ros-namespace namespace="out"/><let name="x" value="2"/></group>
  <node pkg="p" exec="b" name="n$(var x)"/>
</launch>''')
    result = load_launch(main, {})
    assert result.ok, [str(d) for d in result.diagnostics]
    assert [(n.name, n.namespace) for n in result.nodes] == [('a0', '/'), ('n2', '/out')]


def test_ros_timer_actions_and_plain_processes(tmp_path: Path) -> None:
    """<ros_timer> (launch_ros) runs its actions; <executable> is said at its line: a warning
    when the command starts ROS nodes, a note otherwise."""
    main = tmp_path / 'a.launch.xml'
    main.write_text('<launch>\n'
                    '  <ros_timer period="2.0">\n    <node pkg="p" exec="late" name="late"/>\n  </ros_timer>\n'
                    '  <executable cmd="ros2 run p helper --ros-args -r a:=b" respawn_max_retries="2"/>\n'
                    '  <executable cmd="$(find-exec true)" on_exit="shutdown"/>\n'
                    '</launch>\n', encoding='utf-8')
    result = load_launch(main, {})
    assert [n.name for n in result.nodes] == ['late']
    assert [(d.code, d.severity.value, d.line) for d in result.diagnostics] == [
        ('NODL512', 'warning', 5), ('NODL512', 'info', 6)]
    assert 'ROS nodes it starts are missing from the analysis' in result.diagnostics[0].message
