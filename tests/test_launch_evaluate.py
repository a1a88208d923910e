"""The launch walk (nodl.launch.evaluate): launch files read as ros2 launch would, a
table of semantics cases, one system in three formats, includes (chains, cycles, required
arguments) and hostile input (bounded, coded, no traceback)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import pytest
import yaml

from conftest import FIXTURES, REPO
from nodl.launch import load_launch

CASES = sorted((FIXTURES / 'launch' / 'cases').glob('*.yaml'))
SAME = FIXTURES / 'launch' / 'same_system'


def _write(tmp_path: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding='utf-8')
    return tmp_path / next(iter(files))


def _node_view(node: Any, base: Path) -> dict[str, Any]:
    view = node.to_dict()
    view['parameters'] = [
        {**p, **({'path': os.path.relpath(p['path'], base)} if p.get('path') else {})}
        for p in view['parameters']]
    return view


def _matches(actual: Any, expected: Any) -> bool:
    if isinstance(expected, dict):
        return isinstance(actual, dict) and all(_matches(actual.get(k), v) for k, v in expected.items())
    if isinstance(expected, list):
        return (isinstance(actual, list) and len(actual) == len(expected)
                and all(_matches(a, e) for a, e in zip(actual, expected, strict=True)))
    return bool(actual == expected)


@pytest.mark.parametrize('case', CASES, ids=[c.stem for c in CASES])
def test_launch_semantics_case(case: Path, tmp_path: Path) -> None:
    spec = yaml.safe_load(case.read_text(encoding='utf-8'))
    main = _write(tmp_path, spec['files'])
    result = load_launch(main, spec.get('arguments', {}))
    assert result.ok, [str(d) for d in result.diagnostics]
    nodes = [_node_view(n, tmp_path) for n in result.nodes]
    assert _matches(nodes, spec['expected']), json.dumps(nodes, indent=1)


def _normalized(path: Path) -> list[dict[str, Any]]:
    result = load_launch(path, {})
    assert result.ok, [str(d) for d in result.diagnostics]
    out = []
    for node in result.nodes:
        view = node.to_dict()
        view.pop('source')
        view.pop('remap_sources')  # lines differ between the formats
        for p in view['parameters']:
            p.pop('source')
        out.append(view)
    return out


def test_the_same_system_in_xml_yaml_and_python_resolves_alike() -> None:
    xml = _normalized(SAME / 'system.launch.xml')
    assert xml == _normalized(SAME / 'system.launch.yaml')
    assert xml == _normalized(SAME / 'system.launch.py')
    assert [n['namespace'] for n in xml] == ['/rover/sensors', '/rover/nav']
    assert xml[1]['remaps'] == [['odom', '/odom']]
    assert xml[0]['parameters'][0] == {'kind': 'values', 'origin': 'global',
                                       'values': {'use_sim_time': False}, 'node_key': '/**'}


def test_sources_and_include_chain(tmp_path: Path) -> None:
    main = _write(tmp_path, {
        'main.launch.xml': '<launch>\n  <include file="$(dirname)/sub.launch.py"/>\n</launch>\n',
        'sub.launch.py': textwrap.dedent('''\
            from launch import LaunchDescription
            from launch_ros.actions import Node
            def generate_launch_description():
                return LaunchDescription([
                    Node(package='p', executable='e')])
            ''')})
    result = load_launch(main, {})
    (node,) = result.nodes
    assert (node.source.line, node.source.file) == (5, str(tmp_path / 'sub.launch.py'))
    assert [(s.file, s.line) for s in node.include_chain] == [(str(main), 2)]


@pytest.mark.parametrize('text, arguments, code, words', [
    ('<launch><nod pkg="p" exec="e"/></launch>', {}, 'NODL501', "did you mean 'node'"),
    ('<launch><node pkg="p" exec="e" nmae="x"/></launch>', {}, 'NODL502', "did you mean 'name'"),
    ('<launch><node pkg="p"/></launch>', {}, 'NODL503', "'exec'"),
    ('<launch><arg name="m"><choice value="a"/></arg></launch>', {'m': 'b'}, 'NODL505', 'choices'),
    ('<launch><arg name="m"/></launch>', {}, 'NODL506', "'m'"),
    ('<launch><node pkg="p" exec="$(vra x)"/></launch>', {}, 'NODL509', "did you mean 'var'"),
    ('<launch><node pkg="p" exec="$(var nope)"/></launch>', {}, 'NODL510', "'nope'"),
    ('<launch><include file="$(find-pkg-share no_such_pkg)/x.launch.xml"/></launch>', {}, 'NODL511',
     'no_such_pkg'),
    ('<launch><node pkg="p" exec="e" if="maybe"/></launch>', {}, 'NODL514', 'maybe'),
    ('<launch><include file="/nonexistent/x.launch.xml"/></launch>', {}, 'NODL515', 'does not exist'),
    ('<launch><node pkg="p" exec="e" name="bad name"/></launch>', {}, 'NODL519', 'bad name'),
    ('<launch/>', {'typo': '1'}, 'NODL520', 'typo'),
])
def test_problems_are_coded_and_placed(tmp_path: Path, text: str, arguments: dict[str, str], code: str,
                                       words: str) -> None:
    main = _write(tmp_path, {'main.launch.xml': text})
    result = load_launch(main, arguments, environment={'AMENT_PREFIX_PATH': ''})
    found = [d for d in result.diagnostics if d.code == code]
    assert found, [str(d) for d in result.diagnostics]
    assert words in found[0].message and found[0].file == str(main)


def test_include_cycle_shows_the_chain(tmp_path: Path) -> None:
    main = _write(tmp_path, {
        'a.launch.xml': '<launch>\n  <include file="$(dirname)/b.launch.yaml"/>\n</launch>\n',
        'b.launch.yaml': 'launch:\n  - include: {file: $(dirname)/a.launch.xml}\n'})
    result = load_launch(main, {})
    (cycle,) = [d for d in result.diagnostics if d.code == 'NODL507']
    assert 'a.launch.xml -> ' in cycle.message and 'b.launch.yaml -> ' in cycle.message
    assert (cycle.file, cycle.line) == (str(tmp_path / 'b.launch.yaml'), 2)


_HOSTILE_RUNNER = '''
import json, sys, time
from nodl.launch import load_launch
start = time.perf_counter()
result = load_launch(sys.argv[1], {})
# VmHWM, not ru_maxrss: Linux keeps ru_maxrss across exec (the pytest worker's size)
peak = next(int(line.split()[1]) for line in open('/proc/self/status') if line.startswith('VmHWM:'))
print(json.dumps({"codes": sorted({d.code for d in result.diagnostics}),
                  "seconds": time.perf_counter() - start, "rss_mb": peak / 1024}))
'''


def _hostile(path: Path) -> dict[str, Any]:
    done = subprocess.run([sys.executable, '-c', _HOSTILE_RUNNER, str(path)], cwd=REPO, text=True,
                          capture_output=True, timeout=60)
    assert done.returncode == 0 and 'Traceback' not in done.stderr, done.stderr
    out: dict[str, Any] = json.loads(done.stdout)
    assert out['seconds'] < 5 and out['rss_mb'] < 400, out
    return out


def test_hostile_launch_input(tmp_path: Path) -> None:
    bomb = tmp_path / 'bomb.launch.xml'
    bomb.write_text('<?xml version="1.0"?>\n<!DOCTYPE l [<!ENTITY a "aaaaaaaaaa">'
                    + ''.join(f'<!ENTITY a{i} "{"&a;" * 10}">' for i in range(8))
                    + ']>\n<launch><node pkg="p" exec="&a7;"/></launch>\n')
    assert _hostile(bomb)['codes'] == ['NODL013']
    deep = tmp_path / 'deep.launch.xml'
    deep.write_text('<launch>' + '<group>' * 5000 + '</group>' * 5000 + '</launch>')
    assert _hostile(deep)['codes'] == ['NODL009']
    huge = tmp_path / 'huge.launch.xml'
    huge.write_text('<launch>' + ' ' * (11 * 1024 * 1024) + '</launch>')
    assert _hostile(huge)['codes'] == ['NODL001']
    chain = tmp_path / 'c0.launch.xml'
    for i in range(60):
        (tmp_path / f'c{i}.launch.xml').write_text(
            f'<launch><include file="$(dirname)/c{i + 1}.launch.xml"/></launch>')
    (tmp_path / 'c60.launch.xml').write_text('<launch/>')
    assert _hostile(chain)['codes'] == ['NODL508']
    loop = tmp_path / 'loop.launch.yaml'
    loop.write_text('launch:\n  - include: {file: $(dirname)/loop.launch.yaml}\n')
    assert _hostile(loop)['codes'] == ['NODL507']
    laughs = tmp_path / 'laughs.launch.yaml'
    laughs.write_text('a: &a ["x","x","x","x","x","x","x","x","x"]\n'
                      + ''.join(f'{c}: &{c} [*{p},*{p},*{p},*{p},*{p},*{p},*{p},*{p},*{p}]\n'
                                for p, c in zip('abcdefg', 'bcdefgh', strict=True)))
    assert _hostile(laughs)['codes'] == ['NODL008']


def test_required_arguments_of_nested_includes_are_checked_as_launch_does(tmp_path: Path) -> None:
    # launch checks, before an include, the arguments declared without default in the file AND
    # in the files it includes (when their path is known without a context): an argument the
    # inner include does not pass must come from the outer include.
    inner = _write(tmp_path, {'inner.launch.xml': '<launch>\n  <arg name="rate"/>\n'
                                                  '  <node pkg="p" exec="e"/>\n</launch>\n'})
    middle = tmp_path / 'middle.launch.xml'
    middle.write_text(f'<launch>\n  <include file="{inner}"/>\n  <node pkg="p" exec="m"/>\n</launch>\n')
    main = tmp_path / 'main.launch.xml'
    main.write_text(f'<launch>\n  <include file="{middle}"/>\n</launch>\n')
    result = load_launch(main, {})
    (missing,) = [d for d in result.diagnostics if d.code == 'NODL506']
    assert (missing.file, missing.line) == (str(inner), 2) and "'rate'" in missing.message
    assert f'{middle}:2:' in missing.message and result.nodes == []
    main.write_text(f'<launch>\n  <include file="{middle}">\n    <arg name="rate" value="5"/>\n'
                    '  </include>\n</launch>\n')
    result = load_launch(main, {})  # given to middle, but middle's include of inner does not pass it
    assert [d.line for d in result.diagnostics if d.code == 'NODL506'] == [2]
    assert [n.executable for n in result.nodes] == ['m']
    middle.write_text(f'<launch>\n  <include file="{inner}">\n    <arg name="rate" value="$(var rate)"/>\n'
                      '  </include>\n  <node pkg="p" exec="m"/>\n</launch>\n')
    result = load_launch(main, {})
    assert result.ok and [n.executable for n in result.nodes] == ['e', 'm']
    # a path that needs the context ($(dirname)) is not followed by the outer check (as in
    # launch); the inner include itself then finds the argument missing
    middle.write_text('<launch>\n  <node pkg="p" exec="m"/>\n  <include file="$(dirname)/inner.launch.xml"/>\n'
                      '</launch>\n')
    main.write_text(f'<launch>\n  <include file="{middle}"/>\n</launch>\n')
    result = load_launch(main, {})
    (missing,) = [d for d in result.diagnostics if d.code == 'NODL506']
    assert 'declared in a file it includes' not in missing.message
    assert (missing.file, missing.line) == (str(inner), 2) and [n.executable for n in result.nodes] == ['m']


def test_a_configuration_known_only_at_run_time_keeps_the_nodes_that_use_it(tmp_path: Path) -> None:
    """<let value="$(command ...)"> (the xacro idiom), an argument default and an include
    argument from $(command): the nodes that use them stay, the value is unchecked; the
    let's warning is at the let (its use a related place), the others' at the use; a
    condition on such a value says what may be missing."""
    from nodl.launch.params import RuntimeValue

    main = _write(tmp_path, {
        'main.launch.xml': textwrap.dedent('''\
            <launch>
              <let name="description" value="$(command 'xacro robot.xacro')"/>
              <arg name="mode" default="$(command 'cat mode.txt')"/>
              <node pkg="p" exec="publisher" name="publisher">
                <param name="robot_description" value="$(var description)"/>
              </node>
              <include file="$(dirname)/inner.launch.xml">
                <arg name="model" value="$(command 'xacro robot.xacro')"/>
              </include>
              <node pkg="p" exec="maybe" name="maybe" if="$(var mode)"/>
            </launch>'''),
        'inner.launch.xml': textwrap.dedent('''\
            <launch>
              <arg name="model"/>
              <node pkg="p" exec="viewer" name="viewer">
                <param name="model" value="$(var model)"/>
              </node>
            </launch>''')})
    result = load_launch(main, {})
    assert [n.name for n in result.nodes] == ['publisher', 'viewer']
    for node in result.nodes:
        (values,) = [p.values for p in node.parameters]
        assert all(isinstance(v, RuntimeValue) for v in values.values())
    assert [(d.code, d.severity.value, os.path.basename(d.file), d.line) for d in result.diagnostics] == [
        ('NODL513', 'warning', 'main.launch.xml', 2), ('NODL513', 'warning', 'inner.launch.xml', 4),
        ('NODL513', 'warning', 'main.launch.xml', 10)]
    assert "launch configuration 'description'" in result.diagnostics[0].message
    assert [r[1:3] for r in result.diagnostics[0].related] == [(5, 5)]
    assert result.diagnostics[2].message.endswith('this node is missing from the analysis')


def test_a_parameter_file_known_only_at_run_time_keeps_its_node(tmp_path: Path) -> None:
    """<param from="$(command ...)"> (a node's, a composable node's) and a
    set_parameters_from_file of such a path: the nodes stay, with their known parameters, one
    warning per entry, and their records say what only the running launch gives."""
    main = _write(tmp_path, {
        'main.launch.xml': textwrap.dedent('''\
            <launch>
              <node pkg="p" exec="e" name="a">
                <param from="$(command 'cat a.yaml')"/>
                <param name="rate" value="2.0"/>
              </node>
              <group>
                <set_parameters_from_file filename="$(command 'cat all.yaml')"/>
                <node pkg="p" exec="e" name="b"/>
              </group>
              <node pkg="p" exec="e" name="c"/>
              <node_container pkg="rclcpp_components" exec="component_container" name="box" namespace="/">
                <composable_node pkg="p" plugin="p::C" name="d">
                  <param from="$(command 'cat d.yaml')"/>
                </composable_node>
              </node_container>
            </launch>''')})
    result = load_launch(main, {})
    assert [n.name for n in result.nodes] == ['a', 'b', 'c', 'box', 'd']
    assert [(d.code, d.severity.value, d.line) for d in result.diagnostics] == [
        ('NODL513', 'warning', 3), ('NODL513', 'warning', 7), ('NODL513', 'warning', 13)]
    first, scope, composable = (d.message for d in result.diagnostics)
    assert first.startswith("parameters entry: the value comes from running 'cat a.yaml' ($(command))")
    assert first.endswith('the node is analysed without the parameters this entry gives (the known ones '
                          'are checked; no parameter is reported missing for it)')
    assert scope.endswith('the nodes in its scope are analysed without the parameters it gives')
    assert 'the composable node is analysed without the parameters' in composable
    assert not any('missing from the analysis' in d.message for d in result.diagnostics)
    a, b, c, box, d = result.nodes
    assert [p.values for p in a.parameters] == [{'rate': 2.0}]
    assert [(s.part, s.source.line) for s in a.run_time] == [('parameters', 3)]  # its <param>
    assert [(s.part, s.source.line) for s in b.run_time] == [('parameters', 7)]
    assert [(s.part, s.source.line) for s in d.run_time] == [('parameters', 13)]
    assert c.run_time == () and box.run_time == () and c.parameters_complete
    assert not a.parameters_complete and a.remaps_complete
    assert a.to_dict()['run_time'] == [{'part': 'parameters', 'file': str(main), 'line': 3, 'column': 5}]


def test_included_and_parameter_file_paths_are_tidy(tmp_path: Path) -> None:
    """'$(dirname)/../config/x.yaml' is reported as '<dir>/config/x.yaml' (the file a user would
    name), across formats; sources, include chains and parameter files alike."""
    (tmp_path / 'launch').mkdir()
    (tmp_path / 'config').mkdir()
    (tmp_path / 'config' / 'p.yaml').write_text('/**:\n  ros__parameters:\n    a: 1\n')
    main = _write(tmp_path / 'launch', {
        'main.launch.xml': textwrap.dedent('''\
            <launch>
              <node pkg="p" exec="x" name="x"><param from="$(dirname)/../config/./p.yaml"/></node>
              <include file="$(dirname)/../launch/./sub.launch.yaml"/>
            </launch>
            '''),
        'sub.launch.yaml': textwrap.dedent('''\
            launch:
              - node: {pkg: p, exec: y, name: y, param: [{from: $(dirname)/../config/p.yaml}]}
              - include: {file: $(dirname)//../launch/sub.launch.py}
            '''),
        'sub.launch.py': textwrap.dedent('''\
            import os
            from launch import LaunchDescription
            from launch_ros.actions import Node
            def generate_launch_description():
                here = os.path.dirname(__file__)
                return LaunchDescription([Node(
                    package='p', executable='z', name='z',
                    parameters=[os.path.join(here, '..', 'config', 'p.yaml')],
                    ros_arguments=['--params-file', os.path.join(here, '..', 'config', 'p.yaml')])])
            ''')})
    result = load_launch(main, {})
    assert result.ok, [str(d) for d in result.diagnostics]
    params = str(tmp_path / 'config' / 'p.yaml')
    launch = tmp_path / 'launch'
    assert result.files == [str(launch / n) for n in ('main.launch.xml', 'sub.launch.yaml',
                                                      'sub.launch.py')]
    x, y, z = result.nodes
    assert [n.source.file for n in (x, y, z)] == [
        str(launch / 'main.launch.xml'), str(launch / 'sub.launch.yaml'), str(launch / 'sub.launch.py')]
    assert [s.file for s in z.include_chain] == [str(launch / 'main.launch.xml'),
                                                 str(launch / 'sub.launch.yaml')]
    for node in (x, y, z):
        assert [p.path for p in node.parameters if p.kind == 'file'] == [params] * (1 + (node is z))


def test_a_required_argument_of_the_file_run_says_name_value() -> None:
    """The file the user ran needs an argument: given as NAME:=VALUE on the command line
    (not "add <arg> to the include", which it has none of); an included file's missing
    argument still says to add it to the include."""
    folder = Path(__file__).parent / 'fixtures' / 'launch' / 'required_arguments'
    (top,) = load_launch(folder / 'top.launch.xml', {}).diagnostics
    assert (top.code, top.line) == ('NODL506', 3)
    assert top.message.endswith('give it on the command line: robot:=VALUE')
    assert 'include' not in top.message
    assert [n.name for n in load_launch(folder / 'top.launch.xml', {'robot': 'r2'}).nodes] == ['r2']
    (included,) = load_launch(folder / 'includes.launch.xml', {}).diagnostics
    assert included.message.endswith('add <arg name="robot" value="..."/> to the include')


def _time_load(tmp_path: Path, count: int) -> float:
    import time

    path = tmp_path / f'nodes{count}.launch.xml'
    path.write_text('<launch>\n' + ''.join(f'<node pkg="p{i % 100}" exec="e" name="n{i}" namespace="/g{i // 1000}"/>\n'
                                            for i in range(count)) + '</launch>\n')
    start = time.perf_counter()
    result = load_launch(path)
    elapsed = time.perf_counter() - start
    assert len(result.nodes) == count and not result.diagnostics
    return elapsed


def test_a_launch_of_many_nodes_is_read_in_linear_time(tmp_path: Path) -> None:
    """10 times the nodes take about 10 times as long (a quadratic step: 100 times); best of
    two each, a generous bound.  100,000 nodes through nodl analyse: bench/bench_hostile.py."""
    small = min(_time_load(tmp_path, 2_000) for _ in range(2))
    large = min(_time_load(tmp_path, 20_000) for _ in range(2))
    assert large < 30 * small, (small, large)
