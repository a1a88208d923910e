"""The expected system from placed definitions (the analysis nodl analyse runs)."""

from __future__ import annotations

from conftest import FIXTURES
from nodl.monitor.expected import expected_from_definitions
from nodl.targets.placement import Definition

SENSOR = str(FIXTURES / 'monitor' / 'sensor.nodl.yaml')


def test_placed_definitions_with_their_deadline_topics() -> None:
    expected = expected_from_definitions([Definition(file=SENSOR), Definition(file=SENSOR)],
                                         ['/robot/sensor', 'other'])
    assert sorted(expected.nodes) == ['/other', '/robot/sensor']
    node = expected.nodes['/robot/sensor']
    assert node.hardware_id == 'sensor.nodl.yaml' and node.resolved is not None
    assert [(d.topic, d.expected_rate) for d in node.deadlines] == [('/robot/sensor/data', 10.0)]
    assert node.deadlines[0].location.line > 1


def test_a_definition_that_does_not_resolve_is_a_diagnostic() -> None:
    expected = expected_from_definitions([Definition(package='no_such_pkg', executable='x')])
    assert not expected.nodes and expected.diagnostics
