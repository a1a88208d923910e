"""One launched node from launch record to instance (nodl.system.launched): the launch
reader's record is the system node's entry, and every place is the record's own, carried,
not rebuilt."""

from __future__ import annotations

from pathlib import Path

from nodl.composition.entities import Location as EntityLocation
from nodl.launch import load_launch
from nodl.launch.model import LaunchedNode, LaunchRemap
from nodl.location import Location
from nodl.system.findings import Finding
from nodl.system.launched import ParameterSetting, SystemNode, build_node
from nodl.system.matching import DefinitionMatcher, Match
from nodl.system.run import analyse_entries

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]
LAUNCH = FIXTURES / 'launch'


def _records(name: str) -> list[LaunchedNode]:
    return load_launch(str(LAUNCH / name), {}, prefixes=PREFIX).nodes


def test_one_location_type_from_the_launch_reader_to_the_model() -> None:
    from nodl.launch.model import SourceLocation

    assert SourceLocation is Location is EntityLocation
    assert str(Location('a.launch.xml', 3, 5)) == 'a.launch.xml:3:5'
    assert str(Location('a.launch.xml', 0, 0)) == 'a.launch.xml'


def test_the_record_is_the_node_s_entry_and_its_places_are_carried() -> None:
    records = _records('renames.launch.xml')
    matcher = DefinitionMatcher(None, PREFIX)
    findings: list[Finding] = []
    nodes = [build_node(record, matcher.match(record), findings) for record in records]
    planner = next(n for n in nodes if n.entry.executable == 'planner')
    record = next(r for r in records if r.executable == 'planner')
    assert planner.entry is record                       # no copy of the launch record
    assert planner.location is record.source             # the node's place, once
    assert planner.instance is not None and planner.instance.location is record.source
    remap = record.remaps[-1]
    assert isinstance(remap, LaunchRemap) and tuple(remap) == ('cmd_vel', '/cmd')
    assert planner.rule_locations[-1] is remap.source    # each rule where it is written
    assert planner.rule_location(planner.rules[-1]) is remap.source
    speed = planner.parameters['speed']
    assert isinstance(speed, ParameterSetting) and speed.value == 0.8 and speed.origin == 'inline'
    assert speed.location.file == record.source.file and speed.location.line > record.source.line
    sim = planner.parameters['use_sim_time']
    assert sim.origin == 'global' and sim.value is True
    lidar = next(n for n in nodes if n.entry.executable == 'lidar_node')
    assert lidar.fqn == '/robot/front_lidar' and lidar.created_name == 'lidar'  # recorded at registration


def test_a_node_without_a_package_or_definition_is_still_a_system_node() -> None:
    here = Location('hand.launch.py', 7, 3)
    record = LaunchedNode('node', None, 'talker', None, '/', here,
                          remaps=[LaunchRemap('a', 'b', Location('hand.launch.py', 8, 9))])
    findings: list[Finding] = []
    node = build_node(record, Match('', 'talker', None, None), findings)
    assert isinstance(node, SystemNode) and node.instance is None
    assert node.package == '' and node.fqn == '/talker' and node.location is here
    assert node.to_dict()['package'] == '' and node.to_dict()['remaps'] == [['a', 'b']]
    assert node.provenance().source == 'none'
    assert not findings  # no definition: the no-definition check says so, not the build


def test_records_made_by_hand_are_analysed_like_read_ones() -> None:
    """What a front end other than the launch reader builds (records) runs the same path."""
    here = Location('system.launch.py', 4, 5)
    analysis = analyse_entries([LaunchedNode('node', 'demo', 'talker', 'a', '/', here)],
                               prefixes=[], checks={})
    assert [n.fqn for n in analysis.nodes] == ['/a']
    assert analysis.nodes[0].location is here and analysis.findings == []
