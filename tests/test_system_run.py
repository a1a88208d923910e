"""The same system written in XML, YAML and Python resolves to identical nodes; the JSON
shape of a report; the log file."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nodl.analysis import analyse_launch
from nodl.analysis.log import format_log
from nodl.analysis.report import analysis_to_dict, format_junit, format_sarif

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]
MIXIN_PREFIX = [str(FIXTURES / 'mixin_prefix')]
LAUNCH = FIXTURES / 'launch'


def _nodes(name: str) -> list[dict[str, object]]:
    report = analysis_to_dict(analyse_launch(LAUNCH / name, prefixes=PREFIX))
    for node in report['nodes']:
        node.pop('source')  # the line differs between the three files
    return report['nodes']


def test_three_formats_resolve_to_identical_nodes() -> None:
    xml = _nodes('system.launch.xml')
    assert xml == _nodes('system.launch.yaml') == _nodes('system.launch.py')
    imu = next(n for n in xml if n['name'] == '/rover/imu')
    assert imu['parameters'] == {'gain': 0.2}
    assert ['imu/data', '/imu/data'] in imu['endpoints']['publishers']
    assert imu['remaps'] == [['imu/data', '/imu/data']]


def test_json_shape() -> None:
    report = analysis_to_dict(analyse_launch(LAUNCH / 'checks.launch.xml', prefixes=PREFIX))
    assert set(report) == {'nodes', 'findings'}
    for node in report['nodes']:
        assert set(node) == {'name', 'package', 'executable', 'definition', 'definition_source',
                             'definition_folder', 'definition_provenance', 'source', 'remaps',
                             'remaps_complete', 'parameters', 'parameters_complete', 'run_time',
                             'endpoints'}
        assert node['parameters_complete'] is True and node['remaps_complete'] is True
        # every definition here comes from the ament index of the fixture prefix (or none)
        assert node['definition_source'] in ('index', None), node
        assert node['definition_folder'] is None
        assert set(node['source']) == {'file', 'line'}
    planner = next(n for n in report['nodes'] if n['executable'] == 'planner')
    assert planner['remaps'] == [['odm', 'odom']]
    assert planner['parameters'] == {'speed': 1, 'sped': 1.0}
    assert ['~/get_parameters', '/planner/get_parameters'] in planner['endpoints']['service_servers']
    for finding in report['findings']:
        assert {'code', 'kind', 'severity', 'message', 'file', 'line', 'column', 'nodes'} <= set(finding)
    assert any(f.get('endpoint') == '/scan' for f in report['findings'])
    assert any(f.get('parameter') == 'speed' for f in report['findings'])
    json.dumps(report)


def test_sarif_and_junit() -> None:
    analysis = analyse_launch(LAUNCH / 'checks.launch.xml', prefixes=PREFIX)
    sarif = json.loads(format_sarif(analysis))
    rules = {r['id'] for r in sarif['runs'][0]['tool']['driver']['rules']}
    assert 'NODL550' in rules and len(sarif['runs'][0]['results']) == len(analysis.findings)
    import xml.etree.ElementTree as ET

    suite = ET.fromstring(format_junit(analysis))
    failed = {case.get('name') for case in suite if case.find('failure') is not None}
    assert {'duplicate-node', 'type-mismatch', 'parameter-type'} <= failed
    assert 'multiple-publishers' not in failed   # a warning


def test_log_has_the_system_then_every_finding() -> None:
    analysis = analyse_launch(LAUNCH / 'checks.launch.xml', prefixes=PREFIX)
    log = format_log(analysis)
    system, findings = log.split('== Findings')
    assert 'node /planner' in system and '/planner/get_parameters' in system
    assert 'definition      none' in system          # /ghost
    for finding in analysis.findings:
        assert finding.message in findings


@pytest.mark.parametrize('name', ['system.launch.xml', 'checks.launch.xml'])
def test_analysis_is_deterministic(name: str) -> None:
    one = analysis_to_dict(analyse_launch(LAUNCH / name, prefixes=PREFIX))
    two = analysis_to_dict(analyse_launch(LAUNCH / name, prefixes=PREFIX))
    assert one == two


def test_an_unknown_client_library_is_refused_before_anything_is_read() -> None:
    with pytest.raises(ValueError, match="unknown client library 'rclcp'; expected one of: rclpy, rclcpp"):
        analyse_launch(LAUNCH / 'system.launch.xml', prefixes=PREFIX, client_library='rclcp')


def test_the_prefixes_given_serve_every_look_up_mixins_included(monkeypatch: pytest.MonkeyPatch) -> None:
    # $(find-pkg-share mixed), the registered definition and its nodl://mixed/chatter mixin
    # are all in MIXIN_PREFIX; AMENT_PREFIX_PATH points elsewhere (no package 'mixed')
    monkeypatch.setenv('AMENT_PREFIX_PATH', PREFIX[0])
    analysis = analyse_launch(LAUNCH / 'mixin.launch.xml', prefixes=MIXIN_PREFIX)
    assert [f.code for f in analysis.findings] == ['NODL558']   # orphan-publisher, nothing else
    [talker] = analysis_to_dict(analysis)['nodes']
    assert talker['name'] == '/demo/talker'
    assert ['chatter', '/demo/chatter'] in talker['endpoints']['publishers']
    # without prefixes=, AMENT_PREFIX_PATH is searched, as before
    monkeypatch.setenv('AMENT_PREFIX_PATH', MIXIN_PREFIX[0])
    assert analysis_to_dict(analyse_launch(LAUNCH / 'mixin.launch.xml'))['nodes'] == [talker]


@pytest.mark.parametrize('name', ['run_time_params.launch.py', 'run_time_params.launch.xml'])
def test_a_node_with_a_parameter_file_known_only_at_run_time_is_analysed(name: str) -> None:
    """nav2's ParameterFile(RewrittenYaml(...)) (nav2_common not installed here) and XML's
    <param from="$(command ...)">: the nodes stay, one NODL513 per such entry, the known values
    are checked; missing-parameter is not reported for them; JSON and log say more come."""
    analysis = analyse_launch(LAUNCH / name, prefixes=PREFIX)
    assert [n.fqn for n in analysis.nodes] == ['/planner', '/lidar', '/box', '/camera', '/camera_known']
    run_time = [f for f in analysis.findings
                if f.code == 'NODL513' and 'analysed without the parameters' in f.message]
    assert len(run_time) == 2 and all('missing from the analysis' not in f.message for f in run_time)
    assert 'the composable node is analysed' in run_time[1].message
    found = {(f.kind, f.nodes[0], f.parameter) for f in analysis.findings if f.parameter}
    assert found == {('parameter-type', '/planner', 'speed'), ('unknown-parameter', '/planner', 'sped'),
                     ('parameter-invalid', '/camera', 'fps'),
                     ('missing-parameter', '/camera_known', 'device')}   # not /camera's device
    nodes = {n['name']: n for n in analysis_to_dict(analysis)['nodes']}
    assert nodes['/planner']['parameters'] == {'speed': 2, 'sped': 1.0}
    assert [n['parameters_complete'] for n in nodes.values()] == [False, True, True, False, True]
    log = format_log(analysis)
    planner = log.split('node /planner\n')[1].split('\n\n')[0]
    assert '  run time        more parameters, known only when the launch runs' in planner
    assert '(declared default unless set at run time, ' in planner
    known = log.split('node /camera_known\n')[1].split('\n\n')[0]
    assert 'run time' not in known and '(declared default, ' in known


def test_remappings_given_whole_as_a_run_time_value_keep_the_node() -> None:
    analysis = analyse_launch(LAUNCH / 'run_time_params.launch.py', prefixes=PREFIX)
    (remaps,) = [f for f in analysis.findings if f.code == 'NODL513' and f.message.startswith('remappings')]
    assert remaps.message.endswith('the node is analysed without its remapping rules')
    assert remaps.diagnostic.line == 21
    nodes = {n['name']: n for n in analysis_to_dict(analysis)['nodes']}
    assert nodes['/lidar']['remaps'] == [] and nodes['/lidar']['remaps_complete'] is False
    assert nodes['/lidar']['parameters_complete'] is True
    assert '  run time        more remapping rules, known only when the launch runs' in format_log(analysis)


def test_yaml_rules_per_reader_rcl_refuses_aliases_launch_ros_reads_with_pyyaml() -> None:
    # One file given to a node started as a process (rcl reads it: aliases refused, anchors
    # ignored, no merge keys) and to a composable node (launch_ros reads it with PyYAML).
    import yaml

    params = FIXTURES / 'params' / 'aliased.params.yaml'
    analysis = analyse_launch(LAUNCH / 'aliased_params.launch.xml', prefixes=PREFIX)
    found = [f.diagnostic for f in analysis.findings if f.diagnostic.file == str(params)]
    assert [(d.code, d.severity.value, d.line, d.column) for d in found] == [
        ('NODL712', 'error', 7, 5), ('NODL711', 'warning', 7, 10),
        ('NODL711', 'warning', 7, 29), ('NODL711', 'warning', 11, 17),
        ('NODL710', 'error', 14, 17)]
    # each once, related to the process it is given to (line 3), not the composable node's
    assert all([r[1] for r in d.related] == [3] for d in found)
    nodes = {n['name']: n for n in analysis_to_dict(analysis)['nodes']}
    assert nodes['/robot/planner']['parameters'] == {}  # rcl refuses the file: defaults only
    # the composable node gets what launch_ros's yaml.safe_load reads (the installed PyYAML's
    # merge order: here PyYAML is the behaviour to match)
    read = yaml.safe_load(params.read_text(encoding='utf-8'))['/robot/camera']['ros__parameters']
    assert nodes['/robot/camera']['parameters'] == read
    assert read['device'] == '/dev/video0' and read['fps'] in (30.0, 60.0)


def test_a_parameter_file_rcl_cannot_parse_is_an_error_once_at_its_line() -> None:
    # A node given such a file fails to start: the file's problem is said once (however many
    # nodes are given it), where it is, related to where the launch file gives it, and before
    # the checks' findings.
    analysis = analyse_launch(LAUNCH / 'broken_params.launch.xml', prefixes=PREFIX)
    broken = [f for f in analysis.findings if f.diagnostic.file.endswith('broken.params.yaml')]
    assert len(broken) == 1
    finding = broken[0]
    assert finding.severity.value == 'error' and finding.code == 'NODL003'
    assert finding.diagnostic.line == 5
    assert ('the parameter file is given here' in [r[3] for r in finding.diagnostic.related])
    assert analysis.findings[0] is finding  # launch-file problems first
    assert len(analysis.nodes) == 2


def test_a_remap_rule_given_on_the_command_line_is_one_finding() -> None:
    """analyse_definitions(remaps=[...]) (nodl analyse DEFINITION... --remap) gives the rule to
    every node at once: an unused one is one finding at the command line (each node's
    definition a related place), not one per definition."""
    from nodl.system.run import analyse_definitions
    from nodl.targets.placement import Definition

    share = FIXTURES / 'prefix' / 'share' / 'nav' / 'nodl'
    analysis = analyse_definitions([Definition(str(share / 'planner.nodl.yaml')),
                                    Definition(str(share / 'controller.nodl.yaml'))],
                                   remaps=['scna:=/x', 'scan:=/y'], prefixes=PREFIX)
    (unused,) = [f for f in analysis.findings if f.kind == 'unused-remap']
    assert unused.diagnostic.file == '<command line>' and unused.nodes == ('/planner', '/controller')
    assert "'scna:=/x', given to 2 nodes, is never used" in unused.message
    assert [r[0] for r in unused.diagnostic.related] == [str(share / 'planner.nodl.yaml'),
                                                       str(share / 'controller.nodl.yaml')]


def test_files_are_everything_the_analysis_read(tmp_path: Path) -> None:
    """Launch files and what they include, the nodes' parameter files, each definition found
    and its mixins: what nodl analyse -o/--log/--graph must never overwrite."""
    import os
    import shutil

    from conftest import REPO
    from nodl.targets.resolve import gather_definitions

    system = REPO / 'examples' / 'system'
    folder = tmp_path / 'defs' / 'rover_base'
    folder.mkdir(parents=True)
    for name in ('battery_monitor', 'diagnostics'):
        shutil.copy(system / 'rover_base' / 'nodl' / f'{name}.nodl.yaml', folder)
    monitor = folder / 'battery_monitor.nodl.yaml'
    monitor.write_text(monitor.read_text().replace('nodl://rover_base/diagnostics',
                                                   'diagnostics.nodl.yaml'))
    analysis = analyse_launch(str(system / 'launch' / 'rover.launch.xml'), prefixes=[],
                              definitions=gather_definitions([str(tmp_path / 'defs')],
                                                             use_config=False))
    read = {os.path.relpath(os.path.realpath(f), system) if f.startswith(str(system)) else
            os.path.relpath(os.path.realpath(f), tmp_path) for f in analysis.files()}
    assert read == {'launch/rover.launch.xml', 'launch/sensors.launch.yaml',
                    'launch/navigation.launch.py', 'config/base.yaml', 'config/sensors.yaml',
                    'config/navigation.yaml', 'defs/rover_base/battery_monitor.nodl.yaml',
                    'defs/rover_base/diagnostics.nodl.yaml'}
    assert len(analysis.files()) == len(read)  # each once
