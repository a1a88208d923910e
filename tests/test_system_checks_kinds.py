"""Every check kind of nodl.system.checks, run by nodl analyse: each fails on a planted
problem, and stays quiet without it."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl.analysis import KINDS, AnalysisSettings, analyse_launch
from nodl.model.parameter_types import parse_type
from nodl.system.checks import load_checks
from nodl.system.checks.parameters import launch_value_fits, launch_value_verdict

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]
LAUNCH = FIXTURES / 'launch'


@pytest.fixture(scope='module')
def checks_analysis():  # type: ignore[no-untyped-def]
    return analyse_launch(LAUNCH / 'checks.launch.xml', prefixes=PREFIX)


def _of(analysis, kind: str):  # type: ignore[no-untyped-def]
    return [f for f in analysis.findings if f.kind == kind]


def test_the_builtin_checks_are_registered_extensions() -> None:
    checks, broken = load_checks()
    assert not broken
    kinds = {kind for check in checks.values() for kind in check.kinds}  # type: ignore[attr-defined]
    assert kinds == set(KINDS) - {'unnamed-node', 'not-analysable', 'broken-check'}


@pytest.mark.parametrize(('kind', 'line', 'nodes', 'where', 'words'), [
    ('duplicate-node', 10, ['/planner', '/planner'][:1], None, 'launched twice'),
    ('multiple-publishers', 4, ['/lidar', '/lidar2'], '/scan', 'published by 2 nodes'),
    ('type-mismatch', 10, ['/planner'], '/cmd_vel', 'geometry_msgs/msg/TwistStamped'),
    ('qos-incompatible', 5, ['/lidar', '/planner'], '/scan', 'best effort'),
    ('qos-warning', 5, ['/imu_filter', '/planner'], '/imu/data', 'SYSTEM_DEFAULT'),
    ('orphan-subscription', 11, ['/imu_filter'], '/imu/raw', 'no node publishes it'),
    ('orphan-service-client', 5, ['/planner'], '/get_map', 'no node serves it'),
    ('orphan-action-client', 5, ['/planner'], '/dock', 'no node serves it'),
    ('orphan-publisher', 14, ['/camera'], '/camera/image', 'no node subscribes'),
    ('unused-remap', 8, ['/planner'], '/odm', "'odm:=odom' is never used"),  # the <remap>
    ('unknown-parameter', 7, ['/planner'], 'sped', "did you mean 'speed'"),  # the <param>
    ('parameter-type', 6, ['/planner'], 'speed', 'declared double but is set to 1 (int)'),
    ('parameter-invalid', 15, ['/camera'], 'fps', 'outside [1.0, 120.0]'),
    ('missing-parameter', 14, ['/camera'], 'device', 'has no default'),
    ('no-definition', 12, ['/ghost'], None, "registers no node definition for 'ghost'"),
    ('unnamed-node', 11, [], None, "called 'imu_filter'"),
])
def test_each_kind_is_found_at_its_launch_entry(checks_analysis, kind, line, nodes, where,  # type: ignore[no-untyped-def]
                                                words) -> None:
    found = [f for f in _of(checks_analysis, kind) if where is None
             or where in (f.to_dict().get('endpoint'), f.to_dict().get('parameter'))]
    assert found, f'no {kind} finding about {where}'
    first = found[0]
    assert first.code == KINDS[kind]
    assert first.diagnostic.line == line and first.diagnostic.file.endswith('checks.launch.xml')
    assert words in first.message
    for node in nodes:
        assert node in first.nodes


def test_severities_are_the_catalogue_defaults(checks_analysis) -> None:  # type: ignore[no-untyped-def]
    from nodl.codes import default_severity

    for finding in checks_analysis.findings:
        assert finding.severity.value == default_severity(finding.code)


def test_a_clean_system_has_no_error(tmp_path: Path) -> None:
    analysis = analyse_launch(LAUNCH / 'system.launch.xml', prefixes=PREFIX)
    assert not analysis.errors
    assert {f.kind for f in analysis.findings} <= {'qos-warning', 'orphan-subscription',
                                                   'orphan-service-client', 'orphan-action-client',
                                                   'orphan-publisher'}


def test_the_allow_list_silences_multiple_publishers() -> None:
    analysis = analyse_launch(LAUNCH / 'checks.launch.xml', prefixes=PREFIX,
                              settings=AnalysisSettings(('/sc*',)))
    assert not _of(analysis, 'multiple-publishers')


def test_a_recorded_node_name_names_an_unnamed_node(checks_analysis) -> None:  # type: ignore[no-untyped-def]
    lidar = next(n for n in checks_analysis.nodes if n.entry.executable == 'lidar_node'
                 and n.entry.name is None)
    assert lidar.fqn == '/lidar'   # node_name=lidar in nodl_node_info/sensors__lidar_node
    assert not [f for f in _of(checks_analysis, 'unnamed-node') if '/lidar' in f.message]


def test_a_composable_node_is_matched_by_its_recorded_plugin(checks_analysis) -> None:  # type: ignore[no-untyped-def]
    camera = next(n for n in checks_analysis.nodes if n.entry.plugin)
    assert camera.match.how == 'plugin' and camera.match.file.endswith('camera.nodl.yaml')


def test_orphans_are_not_derived_from_a_node_without_definition(checks_analysis) -> None:  # type: ignore[no-untyped-def]
    for finding in _of(checks_analysis, 'orphan-subscription'):
        assert '/ghost' in finding.message   # says the unknown node may serve it


@pytest.mark.parametrize(('value', 'type_name', 'ok'), [
    (1, 'double', False), (1.0, 'double', True), (True, 'int', False), (True, 'string', False),
    ('x', 'string', True), ([1, 2], 'double_array', False), ([1.0], 'double_array', True),
    ([], 'string_array', True), (300, 'byte_array', False), ([1, 300], 'byte_array', False),
    ('anything', 'none', True), ('abcdef', 'string_fixed_3', False),
])
def test_parameter_types_are_as_strict_as_a_node(value, type_name: str, ok: bool) -> None:  # type: ignore[no-untyped-def]
    spec = parse_type(type_name)
    assert spec is not None
    assert launch_value_fits(value, spec) is ok


#: (NoDL type, the value as written in a parameter file): rclpy decides, the analysis must agree.
RCLPY_TYPE_CASES = [
    ('double', '1'), ('double', '1.0'), ('double', '1e5'), ('double', '.5'), ('int', '1.0'),
    ('int', '0x10'), ('int', 'true'), ('string', 'true'), ('string', '5'), ('string', "'5'"),
    ('string', '!!str 5'), ('string', '~'), ('bool', 'on'), ('bool', 'yes'), ('bool', '1'),
    ('double_array', '[1, 2]'), ('double_array', '[1.0, 2.5]'), ('int_array', '[1.0]'),
    ('int_array', '[1, 2]'), ('string_array', '[a, b]'), ('bool_array', '[true, off]'),
    ('byte_array', '[1, 2]'), ('none', 'hello'), ('none', '[1.5]'), ('string_array', '[]'),
    ('double_array', '[]'), ('int', '[]'),
]
_RCLPY_TYPES = {'bool': 'BOOL', 'int': 'INTEGER', 'double': 'DOUBLE', 'string': 'STRING',
                'byte_array': 'BYTE_ARRAY', 'bool_array': 'BOOL_ARRAY', 'int_array': 'INTEGER_ARRAY',
                'double_array': 'DOUBLE_ARRAY', 'string_array': 'STRING_ARRAY'}


def _rclpy_verdict(type_name: str, params_file: Path) -> str:
    """What a real rclpy node does when it declares ``x`` of ``type_name`` with that file."""
    import rclpy
    from rcl_interfaces.msg import ParameterDescriptor
    from rclpy.exceptions import (
        InvalidParameterTypeException,
        ParameterUninitializedException,
    )
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    context = rclpy.Context()
    rclpy.init(context=context, args=[])
    try:
        node = Node('typing_oracle', context=context,
                    cli_args=['--ros-args', '--params-file', str(params_file)])
        try:
            if type_name == 'none':
                node.declare_parameter('x', 0, ParameterDescriptor(dynamic_typing=True))
            else:
                node.declare_parameter('x', getattr(Parameter.Type, _RCLPY_TYPES[type_name]))
            _ = node.get_parameter('x').value
            return 'accepted'
        except InvalidParameterTypeException:
            return 'refused'
        except ParameterUninitializedException:
            return 'unset'
        finally:
            node.destroy_node()
    finally:
        rclpy.shutdown(context=context)


@pytest.mark.parametrize(('type_name', 'written'), RCLPY_TYPE_CASES,
                         ids=[f'{t}={w}' for t, w in RCLPY_TYPE_CASES])
def test_parameter_type_verdicts_agree_with_rclpy(type_name: str, written: str, tmp_path: Path) -> None:
    """parameter-type against the oracle: the value as rcl reads the file, then the check's verdict
    must be rclpy's (refused by declare_parameter: parameter-type; an empty list leaves the
    parameter unset, reading it raises: parameter-invalid; accepted: no finding)."""
    from nodl.launch import load_parameter_file

    params_file = tmp_path / 'params.yaml'
    params_file.write_text(f'/**:\n  ros__parameters:\n    x: {written}\n', encoding='utf-8')
    oracle = _rclpy_verdict(type_name, params_file)
    (entry,) = load_parameter_file(params_file).nodes
    spec = parse_type(type_name)
    assert spec is not None
    assert launch_value_verdict(entry.rcl_parameters['x'], spec) == oracle, (entry.rcl_parameters['x'], oracle)


def test_unused_remap_follows_rcl(tmp_path: Path) -> None:
    """Base entities (/rosout, /parameter_events, ~/get_parameters) are remappable (real rclpy
    remaps them), so rules for them are used; a node-scoped rule for another launched node (a
    set_remap gives it to every node in scope) is that node's; one for no launched node is a typo."""
    launch = tmp_path / 'remaps.launch.xml'
    launch.write_text(
        '<launch>\n'
        '  <set_remap from="second:cmd_vel" to="/x"/>\n'
        '  <node pkg="nav" exec="planner" name="first">\n'
        '    <remap from="/rosout" to="/log"/><remap from="/parameter_events" to="/events"/>\n'
        '    <remap from="~/get_parameters" to="/gp"/>\n'
        '  </node>\n'
        '  <node pkg="nav" exec="planner" name="second"/>\n'
        '  <node pkg="nav" exec="planner" name="third">\n'
        '    <remap from="thrid:cmd_vel" to="/y"/>\n'
        '  </node>\n'
        '</launch>\n', encoding='utf-8')
    (finding,) = _of(analyse_launch(launch, prefixes=PREFIX), 'unused-remap')
    assert (finding.nodes, finding.diagnostic.line) == (('/third',), 9)
    assert "'thrid'" in finding.message and 'no launched node has that name' in finding.message


#: The same unused rules written in each format: (file name, text, {rule: (line, column)}).
#: A finding about a rule points at the rule (the <remap>, the set_remap, the args with -r),
#: its related places at the entries of the nodes given it (the set_remap, given to the three
#: nodes, is one finding for all).
REMAP_PLACES = [
    ('r.launch.xml',
     '<launch>\n'
     '  <set_remap from="scna" to="/a"/>\n'
     '  <node pkg="nav" exec="planner" name="planner"\n'
     '        ros_args="--log-level info -r gte_map:=/m">\n'
     '    <remap from="scan" to="/scan2"/>\n'
     '    <remap from="odm" to="/odom"/>\n'
     '  </node>\n'
     '  <node_container pkg="rclcpp_components" exec="component_container" name="box" namespace="/">\n'
     '    <composable_node pkg="sensors" plugin="sensors::CameraDriver" name="camera">\n'
     '      <remap from="imgae" to="/i"/>\n'
     '    </composable_node>\n'
     '  </node_container>\n'
     '</launch>\n',
     {'/planner': (3, 3), '/box': (8, 3), '/camera': (9, 5)},
     {(('/planner', '/box', '/camera'), 'scna:=/a'): (2, 3), ('/planner', 'gte_map:=/m'): (4, 9),
      ('/planner', 'odm:=/odom'): (6, 5), ('/camera', 'imgae:=/i'): (10, 7)}),
    ('r.launch.yaml',
     'launch:\n'
     '  - set_remap: {from: scna, to: /a}\n'
     '  - node:\n'
     '      pkg: nav\n'
     '      exec: planner\n'
     '      name: planner\n'
     '      ros_args: --log-level info -r gte_map:=/m\n'
     '      remap:\n'
     '        - {from: scan, to: /scan2}\n'
     '        - {from: odm, to: /odom}\n'
     '  - node_container:\n'
     '      pkg: rclcpp_components\n'
     '      exec: component_container\n'
     '      name: box\n'
     '      namespace: /\n'
     '      composable_node:\n'
     '        - pkg: sensors\n'
     '          plugin: sensors::CameraDriver\n'
     '          name: camera\n'
     '          remap:\n'
     '            - {from: imgae, to: /i}\n',
     {'/planner': (3, 5), '/box': (11, 5), '/camera': (17, 11)},
     {(('/planner', '/box', '/camera'), 'scna:=/a'): (2, 5), ('/planner', 'gte_map:=/m'): (7, 7),
      ('/planner', 'odm:=/odom'): (10, 11), ('/camera', 'imgae:=/i'): (21, 15)}),
    ('r.launch.py',
     'from launch import LaunchDescription\n'
     'from launch_ros.actions import ComposableNodeContainer, Node, SetRemap\n'
     'from launch_ros.descriptions import ComposableNode\n'
     '\n'
     '\n'
     'def generate_launch_description():\n'
     '    return LaunchDescription([\n'
     "        SetRemap(src='scna', dst='/a'),\n"
     "        Node(package='nav', executable='planner', name='planner',\n"
     "             ros_arguments=['--log-level', 'info', '-r', 'gte_map:=/m'],\n"
     "             remappings=[('scan', '/scan2'),\n"
     "                         ('odm', '/odom')]),\n"
     "        ComposableNodeContainer(package='rclcpp_components', executable='component_container',\n"
     "                                name='box', namespace='/', composable_node_descriptions=[\n"
     "            ComposableNode(package='sensors', plugin='sensors::CameraDriver', name='camera',\n"
     "                           remappings=[('imgae', '/i')])]),\n"
     '    ])\n',
     {'/planner': (9, 9), '/box': (13, 9), '/camera': (15, 13)},
     {(('/planner', '/box', '/camera'), 'scna:=/a'): (8, 9), ('/planner', 'gte_map:=/m'): (10, 58),
      ('/planner', 'odm:=/odom'): (12, 26), ('/camera', 'imgae:=/i'): (16, 40)}),
]


@pytest.mark.parametrize(('name', 'text', 'entries', 'expected'), REMAP_PLACES,
                         ids=[p[0] for p in REMAP_PLACES])
def test_a_finding_about_a_remap_points_at_the_rule(tmp_path: Path, name: str, text: str,
                                                    entries: dict[str, tuple[int, int]],
                                                    expected: dict[tuple[str, str], tuple[int, int]]) -> None:
    launch = tmp_path / name
    launch.write_text(text, encoding='utf-8')
    analysis = analyse_launch(launch, prefixes=PREFIX)
    found = {}
    for finding in _of(analysis, 'unused-remap'):
        nodes = finding.nodes
        rule = finding.message.split("'")[1]
        d = finding.diagnostic
        assert d.file == str(launch)
        found[nodes if len(nodes) > 1 else nodes[0], rule] = (d.line, d.column)
        # the entries of the nodes given the rule are the related places
        assert [(r[1], r[2]) for r in d.related] == [entries[n] for n in nodes], d.related
    assert found == expected


def test_a_rule_given_to_many_nodes_is_one_finding_at_the_rule() -> None:
    """A set_remap given to 14 nodes is one finding at the set_remap (not one per node), and
    none when a node in its scope uses it or may use it (a node without a definition); a
    node-scoped rule whose node is launched outside its scope says so."""
    launch = LAUNCH / 'shared_remaps.launch.xml'
    analysis = analyse_launch(launch, prefixes=PREFIX)
    planners = tuple(f'/planner_{i}' for i in range(14))
    found = {f.diagnostic.line: f for f in _of(analysis, 'unused-remap')}
    assert sorted(found) == [4, 6, 7]  # scna, lidar:cmd_vel, planner_0:dokc; not scan, odm
    for finding in found.values():
        assert finding.nodes == planners and finding.diagnostic.file == str(launch)
        assert len(finding.diagnostic.related) == 14  # each node's entry
    assert "'scna:=/scan_filtered', given to 14 nodes, is never used" in found[4].message
    assert "has a topic, service or action '/scna'" in found[4].message
    assert found[4].endpoint == '/scna'
    assert "/lidar, launched at" in found[6].message and 'outside its scope' in found[6].message
    assert 'it applies only to /planner_0, which has no' in found[7].message


def test_a_duplicate_on_an_assumed_name_is_a_warning_that_says_so() -> None:
    """Two spawners (no name=, no recorded NODE_NAME) share only the name the analysis
    assumed: a NODL530 warning naming the assumption; recorded names and __node rules are
    known, so their duplicates stay NODL550 errors."""
    analysis = analyse_launch(LAUNCH / 'assumed_names.launch.xml', prefixes=PREFIX)
    assumed = [(f.diagnostic.line, f.nodes, f.code, f.severity.value)
               for f in _of(analysis, 'assumed-duplicate-node')]
    assert assumed == [(4, ('/spawner',), 'NODL530', 'warning'),
                       (7, ('/imu_filter',), 'NODL530', 'warning')]
    spawner = _of(analysis, 'assumed-duplicate-node')[0]
    assert "assumed the name 'spawner'" in spawner.message and 'name=' in spawner.message
    errors = [(f.diagnostic.line, f.nodes, f.severity.value) for f in _of(analysis, 'duplicate-node')]
    assert errors == [(10, ('/lidar',), 'error'), (13, ('/driver',), 'error')]
    assert not analysis.errors or all(f.kind != 'assumed-duplicate-node' for f in analysis.errors)


def test_a_fixed_size_array_with_too_many_elements_says_how_many_fit() -> None:
    """As nodl params check says it: 'holds 3 elements; at most 2 fit', not 'declared double
    array but is set to ... (double array)'."""
    fixed = Path(__file__).parent / 'fixtures' / 'params' / 'fixed_size'
    analysis = analyse_launch(fixed / 'arm.launch.xml', prefixes=[str(fixed / 'prefix')])
    (finding,) = _of(analysis, 'parameter-type')
    assert 'holds 3 elements; at most 2 fit double_array_fixed_2' in finding.message
    assert 'declared double array' not in finding.message
    assert (finding.diagnostic.file, finding.diagnostic.line) == (str(fixed / 'gains.yaml'), 3)


def test_a_container_s_command_line_rules_reach_only_forwarding_composable_nodes() -> None:
    """rclcpp_components loads a composable node with use_global_arguments false: the rules on
    its container's command line (ros_args/args -r) reach it only with the extra argument
    forward_global_arguments: true.  A rule used by such a node is not reported; an unused one
    is one finding at the ros_args attribute for the container and the forwarding nodes; a
    rule a non-forwarding composable node would use says why it does not reach it."""
    launch = LAUNCH / 'container_rules.launch.xml'
    analysis = analyse_launch(launch, prefixes=PREFIX)
    nodes = {n.fqn: n for n in analysis.nodes}
    assert set(nodes) == {'/cams/box', '/cams/front', '/cams/side', '/back'}  # the container's
    # __ns reaches the forwarding nodes (given no namespace), not /back
    front = nodes['/cams/front'].instance
    assert front is not None and '/front_image' in [b.name for b in front.endpoints]
    back = nodes['/back'].instance
    assert back is not None and '/back/image' in [b.name for b in back.endpoints]
    found = sorted((f.diagnostic.line, f.diagnostic.column, f.message, f.nodes)
                   for f in _of(analysis, 'unused-remap'))
    assert [(line, column, fqns) for line, column, _, fqns in found] == [
        (5, 19, ('/cams/box', '/cams/front', '/cams/side'))] * 2
    back_rule, typo = sorted((m for _, _, m, _ in found), key=lambda m: 'side/imag' in m)
    assert "'back/image:=/back_image', given to 3 nodes, is never used" in back_rule
    assert '/back, loaded into the container, would use it' in back_rule
    assert 'forward_global_arguments: true' in back_rule
    assert "'side/imag:=/side_image'" in typo and 'loaded into the container' not in typo


def test_a_rule_given_through_a_python_variable_is_one_finding_where_it_is_written() -> None:
    """remappings=common given to 6 Node(...) calls: an unused rule of common is one finding
    at its item in common = [...], not one per node; a Python container's ros_arguments reach
    the composable node loaded with forward_global_arguments only."""
    launch = LAUNCH / 'shared_remaps.launch.py'
    analysis = analyse_launch(launch, prefixes=PREFIX)
    found = [(f.diagnostic.line, f.diagnostic.column, f.nodes) for f in _of(analysis, 'unused-remap')]
    planners = tuple(f'/planner_{i}' for i in range(6))
    assert found == [(10, 15, planners), (16, 65, ('/box', '/front'))]
    (typo,) = [f for f in _of(analysis, 'unused-remap') if f.diagnostic.line == 10]
    assert "'scna:=/scan_filtered', given to 6 nodes, is never used" in typo.message
    (missed,) = [f for f in _of(analysis, 'unused-remap') if f.diagnostic.line == 16]
    assert '/back, loaded into the container, would use it' in missed.message
