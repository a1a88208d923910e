"""The analysis report (nodl.analysis.report): a value known only at run time is
never reported as a value."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nodl.analysis import analyse_launch, report
from nodl.analysis.log import format_log

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]


def test_a_run_time_value_is_null_and_listed_never_a_placeholder() -> None:
    """<param value="$(var robot)"> where robot is set from $(command): in JSON the value is
    null, parameters_complete is false and run_time lists the parameter with its place; no
    report (JSON, text, SARIF, JUnit, log) holds a stand-in text for the value."""
    launch = FIXTURES / 'launch' / 'param_places.launch.xml'
    analysis = analyse_launch(launch, prefixes=PREFIX)
    (node,) = json.loads(report.format_json(analysis))['nodes']
    assert node['parameters'] == {'speed': 1, 'robot_name': None}
    assert node['parameters_complete'] is False
    assert node['run_time'] == [{'part': 'parameter', 'parameter': 'robot_name',
                                 'file': str(launch), 'line': 5, 'column': 5}]
    log = format_log(analysis)
    assert 'robot_name, known only at run time' in log
    for text in (report.format_json(analysis), report.format_text(analysis, True),
                 report.format_sarif(analysis), report.format_junit(analysis), log):
        assert 'known at run time>' not in text and 'RuntimeValue' not in text


def test_a_node_with_every_value_known_is_complete() -> None:
    analysis = analyse_launch(FIXTURES / 'launch' / 'checks.launch.xml', prefixes=PREFIX)
    nodes = json.loads(report.format_json(analysis))['nodes']
    assert all(n['parameters_complete'] and n['run_time'] == [] for n in nodes)


RUN_TIME = FIXTURES / 'run_time'
#: The stand-ins the launch reader uses for values only the running launch knows
#: (python_missing's marker text, in any case, and the names of its classes).
_MARKERS = ('known at run time>', 'KNOWN AT RUN TIME>', 'RunTimeText', 'RuntimeValue', 'Placeholder',
            'Deferred', '\u2039')


def _every_output(launch: Path, limits: object = None) -> tuple[object, dict[str, str]]:
    from nodl.graph import render_graph
    from nodl.params.check import check_launch_parameters
    from nodl.policy.launched import launch_policy
    from nodl.policy.writer import write_policy

    kwargs = {} if limits is None else {'limits': limits}
    analysis = analyse_launch(launch, prefixes=PREFIX, **kwargs)  # type: ignore[arg-type]
    outputs = {'text': report.format_text(analysis, True), 'log': format_log(analysis),
               'json': report.format_json(analysis), 'sarif': report.format_sarif(analysis),
               'junit': report.format_junit(analysis), 'dot': render_graph(analysis, 'dot')}
    policy = launch_policy(launch, prefixes=PREFIX, allow_missing=True, **kwargs)  # type: ignore[arg-type]
    outputs['policy'] = write_policy(policy.policy) + '\n'.join(map(str, policy.diagnostics))
    outputs['params'] = '\n'.join(str(d) for d in check_launch_parameters(
        str(launch), prefixes=PREFIX, **kwargs))  # type: ignore[arg-type]
    return analysis, outputs


@pytest.mark.parametrize('name,execute', [('missing_modules.launch.py', True),
                                          ('commands.launch.xml', True),
                                          ('commands.launch.xml', False)])
def test_no_output_shows_a_stand_in_for_a_run_time_value(name: str, execute: bool) -> None:
    """Python launch files importing modules not installed here (xacro, nav2_common: values
    made into f-strings, .upper(), os.path.join, PathJoinSubstitution), $(command) and $(eval)
    (run, and not run: --no-exec): no output of the analysis (text, log, JSON, SARIF, JUnit,
    graph, policy, params check) holds the reader's marker text for such a value."""
    from nodl.launch.sandbox import LaunchLimits

    _, outputs = _every_output(RUN_TIME / name, None if execute else LaunchLimits(execute=False))
    for kind, text in outputs.items():
        for marker in _MARKERS:
            assert marker not in text, f'{kind} output shows {marker!r}'


def test_names_rules_and_files_from_run_time_values_are_unknown_not_made_up() -> None:
    """A node named from a run-time value is left out (said so), not named by a stand-in; a
    remapping rule with a run-time side is left out of the node's rules (remaps_complete
    false, NODL513 at the rule); a parameter file whose path is run-time (os.path.join of a
    missing module's folder, PathJoinSubstitution, RewrittenYaml) leaves parameters_complete
    false; a run-time value is null in JSON; the let of a run-time value is one finding."""
    launch = RUN_TIME / 'missing_modules.launch.py'
    analysis, outputs = _every_output(launch)
    nodes = {n['name']: n for n in json.loads(outputs['json'])['nodes']}
    assert set(nodes) == {'/planner', '/remapped', '/controller', '/joined', '/path_joined'}
    assert nodes['/planner']['parameters'] == {'robot_name': None, 'speed': 1.0}
    assert nodes['/remapped']['remaps'] == [] and nodes['/remapped']['remaps_complete'] is False
    for name in ('/controller', '/joined', '/path_joined'):
        assert nodes[name]['parameters_complete'] is False
    unknown = [(f.diagnostic.line, f.message) for f in analysis.findings if f.code == 'NODL513']  # type: ignore[attr-defined]
    assert [line for line, m in unknown if 'this node is missing' in m] == [24, 32]
    assert [line for line, m in unknown if m.startswith('remapping rule')] == [26, 26]
    assert not [f for f in analysis.findings if f.code == 'NODL519']  # type: ignore[attr-defined]
