"""nodl.studio.palette: every definition found, with its ports (the client library's left out),
and the search the page does."""

from __future__ import annotations

from conftest import FIXTURES
from nodl.registry.overlay import using
from nodl.studio.palette import build_palette, matches
from nodl.targets.resolve import gather_definitions


def test_the_palette_of_a_definitions_folder() -> None:
    definitions = gather_definitions([str(FIXTURES / 'studio' / 'example_definitions')],
                                     use_config=False)
    with using(definitions):
        palette = build_palette()
    assert [(e['package'], e['executable']) for e in palette][:3] == [
        ('rover_base', 'battery_monitor'), ('rover_base', 'diagnostic_aggregator'),
        ('rover_base', 'motor_controller')]
    mission = next(e for e in palette if e['executable'] == 'mission_executive')
    assert mission['node_name'] == 'mission'  # from nodes.yaml
    assert {p['kind'] for p in mission['ports']} == {'publisher', 'subscription', 'service_client',
                                                      'action_client'}
    assert not any(p['name'] in ('/rosout', '/parameter_events') for e in palette
                   for p in e['ports'])
    assert mission['parameters'] == ['low_battery'] and mission['problems'] == []
    assert matches(mission, 'fibonacci tools') and not matches(mission, 'LaserScan')
