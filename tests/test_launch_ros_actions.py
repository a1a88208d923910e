"""The launch_ros actions (nodl.launch.ros_actions): parameter files read with
allow_substs, and findings about a node's parameters placed where they are written."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nodl.analysis import analyse_launch, report
from nodl.launch import load_launch

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]
LAUNCH = FIXTURES / 'launch'
SUBSTITUTED = FIXTURES / 'params' / 'substituted.yaml'


@pytest.mark.parametrize('name', ['allow_substs.launch.xml', 'allow_substs.launch.py'])
def test_allow_substs_substitutes_the_file_s_text(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """ParameterFile(..., allow_substs=True) and <param from=... allow_substs="true">: the node
    reads the file's text after $(var) and $(env) are performed, as launch_ros gives it;
    without allow_substs the text is read as written (and '$(var speed)' is no double)."""
    monkeypatch.setenv('NODL_TEST_SUFFIX', 'one')
    analysis = analyse_launch(LAUNCH / name, {'robot': 'bot'}, prefixes=PREFIX)
    values = {n.fqn: n.parameter_values() for n in analysis.nodes}
    assert values['/planner'] == {'speed': 0.75, 'robot_name': 'bot_one'}
    assert not [f for f in analysis.findings if f.kind.startswith('parameter')
                and '/planner' in f.nodes]
    if name.endswith('.xml'):
        assert values['/verbatim/planner'] == {'speed': '$(var speed)',
                                               'robot_name': '$(var robot)_$(env NODL_TEST_SUFFIX unset)'}
        (wrong,) = [f for f in analysis.findings if f.kind == 'parameter-type']
        assert wrong.nodes == ('/verbatim/planner',) and wrong.diagnostic.file == str(SUBSTITUTED)


def test_allow_substs_problems_are_at_the_param() -> None:
    """A substitution of the file that fails is an error at the <param from=...>; one only
    the running launch knows leaves the node analysed without the file (NODL513 there,
    parameters_complete false, the part listed)."""
    launch = LAUNCH / 'allow_substs_problems.launch.xml'
    result = load_launch(launch, {})
    found = [(d.code, d.line, d.column) for d in result.diagnostics]
    assert found == [('NODL510', 4, 5), ('NODL513', 7, 5)]
    assert "'no_such_argument' does not exist" in result.diagnostics[0].message
    assert 'substituted_unknown.yaml' in result.diagnostics[0].message
    analysis = analyse_launch(launch, prefixes=PREFIX)
    (node,) = json.loads(report.format_json(analysis))['nodes']
    assert node['name'] == '/run_time' and node['parameters'] == {}
    assert node['parameters_complete'] is False
    assert node['run_time'] == [{'part': 'parameters', 'file': str(launch), 'line': 7, 'column': 5}]


def test_findings_about_a_param_sit_at_the_param() -> None:
    """An XML <param>'s findings (a value of the wrong type, a parameter file that is not a
    file) sit at the <param> line, not at the node's; a value known only at run time that a
    let sets is said at the let, the <param> using it a related location."""
    launch = LAUNCH / 'param_places.launch.xml'
    analysis = analyse_launch(launch, prefixes=PREFIX)
    placed = {(f.code, f.diagnostic.line, f.diagnostic.column) for f in analysis.findings
              if f.code in ('NODL561', 'NODL513', 'NODL517')}
    assert placed == {('NODL561', 4, 5), ('NODL513', 2, 3), ('NODL517', 6, 5)}
    (run_time,) = [f for f in analysis.findings if f.code == 'NODL513']
    assert [r[:3] for r in run_time.diagnostic.related] == [(str(launch), 5, 5)]
    assert "parameter 'robot_name'" in run_time.diagnostic.related[0][3]


def test_a_run_time_let_is_one_finding_at_the_let() -> None:
    """<let value="$(command ...)"> used by three nodes (two <param> values, a <param from>):
    one NODL513 at the let naming where it is used (in the message, for the text report, and
    as related locations), not one per use; each node still knows what it lacks (null value
    or an incomplete parameter set)."""
    launch = LAUNCH / 'let_places.launch.xml'
    analysis = analyse_launch(launch, prefixes=PREFIX)
    (run_time,) = [f for f in analysis.findings if f.code == 'NODL513']
    assert (run_time.diagnostic.line, run_time.diagnostic.column) == (2, 3)
    assert "launch configuration 'robot'" in run_time.message and 'used at 4:5, 7:5, 10:5' in run_time.message
    assert [r[:3] for r in run_time.diagnostic.related] == [(str(launch), 4, 5), (str(launch), 7, 5),
                                                            (str(launch), 10, 5)]
    sarif = json.loads(report.format_sarif(analysis))
    (result,) = [r for r in sarif['runs'][0]['results'] if r['ruleId'] == 'NODL513']
    assert [loc['physicalLocation']['region']['startLine'] for loc in result['relatedLocations']] == [4, 7, 10]
    nodes = {n['name']: n for n in json.loads(report.format_json(analysis))['nodes']}
    assert nodes['/planner']['parameters']['robot_name'] is None
    assert nodes['/planner_2']['parameters']['robot_name'] is None
    assert nodes['/controller']['parameters_complete'] is False
    (finding,) = [f for f in json.loads(report.format_json(analysis))['findings'] if f['code'] == 'NODL513']
    assert [(r['line'], r['column']) for r in finding['related']] == [(4, 5), (7, 5), (10, 5)]


def test_the_container_s_global_arguments_reach_a_node_only_with_forward_global_arguments() -> None:
    """rclcpp_components loads a node with use_global_arguments false; forward_global_arguments
    true (the last given wins) gives it the container's command-line rules after its own, and
    the container's __node/__ns where the load gives no name/namespace (so an unnamed one takes
    the container's name, as rcl does); a load option that is not a bool is NODL533 (the load
    is refused: no node); one known only at run time leaves the node's rules incomplete."""
    launch = LAUNCH / 'load_options.launch.py'
    result = load_launch(launch, {})
    nodes = {(n.kind, n.name): n for n in result.nodes}
    assert set(nodes) == {('container', 'box'), ('composable', None), ('composable', 'named'),
                          ('composable', 'maybe'), ('composable', 'off')}
    assert nodes['composable', None].remaps == [('chatter', 'shout'), ('__node', 'box'),
                                                ('__ns', '/robot')]
    assert nodes['composable', 'named'].remaps == [('chatter', 'shout')]
    assert nodes['composable', 'off'].remaps == []
    maybe = nodes['composable', 'maybe']
    assert maybe.remaps == [] and [s.part for s in maybe.run_time] == ['remaps']
    found = [(d.code, d.line) for d in result.diagnostics]
    assert found == [('NODL533', 19), ('NODL513', 21)]
    assert "'use_intra_process_comms' is 'yes', not a bool" in result.diagnostics[0].message
    analysis = analyse_launch(launch, prefixes=PREFIX)
    (twice,) = [f for f in analysis.findings if f.kind == 'duplicate-node']
    assert twice.nodes == ('/robot/box',)
    (json_node,) = [n for n in json.loads(report.format_json(analysis))['nodes'] if n['name'] == '/maybe']
    assert json_node['remaps_complete'] is False


def test_a_parameter_file_given_to_many_nodes_is_evaluated_once(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """launch_ros's ParameterFile keeps its first evaluation: one object given to several
    nodes is performed once (nav2's bringup gives one ParameterFile(RewrittenYaml(...)) to
    twenty nodes), and a node in another scope gets the file the first node's scope made;
    a ParameterFile of its own is evaluated in its node's scope."""
    counter = tmp_path / 'count'
    monkeypatch.setenv('NODL_TEST_COUNT_FILE', str(counter))
    analysis = analyse_launch(LAUNCH / 'shared_parameter_file.launch.py', {}, prefixes=PREFIX)
    values = {n.fqn: n.parameter_values() for n in analysis.nodes}
    assert values == {'/one': {'robot': 'first', 'written': 1},
                      '/two': {'robot': 'first', 'written': 1},
                      '/three': {'robot': 'second', 'written': 2}}
    assert counter.read_text().splitlines() == ['performed', 'performed']


NAV2 = Path(__file__).parent / 'fixtures' / 'launch' / 'nav2_bringup'


def test_nav2_bringup_without_nav2_common(monkeypatch: pytest.MonkeyPatch,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    """nodl analyse of nav2's bringup_launch.py (navigation2 1.4.2, nav2_common not installed
    here): its 21 nodes (the container and 20 composable nodes of four included files), each
    with the parameters known here and the RewrittenYaml entry said to be known only at run
    time, as analysed before a shared ParameterFile was evaluated once."""
    from nodl.cli.main import main

    prefix = NAV2 / 'prefix'
    launch = prefix / 'share' / 'nav2_bringup' / 'launch'
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    assert main(['analyse', str(launch / 'bringup_launch.py'), '--format', 'json']) == 0
    nodes = json.loads(capsys.readouterr().out)['nodes']
    root = f'{launch}/'
    found = [{'name': n['name'], 'package': n['package'], 'executable': n['executable'],
              'source': [n['source']['file'].replace(root, ''), n['source']['line']],
              'remaps': n['remaps'], 'parameters': n['parameters'],
              'parameters_complete': n['parameters_complete'],
              'run_time': [[r['part'], r['file'].replace(root, ''), r['line'], r['column']]
                           for r in n['run_time']]} for n in nodes]
    expected = json.loads((NAV2 / 'expected_nodes.json').read_text(encoding='utf-8'))
    assert found == expected
    assert len(found) == 21
    # every node given the RewrittenYaml file (all but the four lifecycle managers) says so
    assert [n['name'] for n in found if not n['run_time']] == [
        '/lifecycle_manager_localization', '/lifecycle_manager_keepout_zone',
        '/lifecycle_manager_speed_zone', '/lifecycle_manager_navigation']
