"""The analysis report (nodl_schema.analysis.report): a value known only at run time is
never reported as a value."""

from __future__ import annotations

import json
from pathlib import Path

from nodl_schema.analysis import analyse_launch, report
from nodl_schema.analysis.log import format_log

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
