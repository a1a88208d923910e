"""A converted legacy node carries its source map (nodl.legacy.converted)."""

from __future__ import annotations

from conftest import FIXTURES
from nodl.frontends.legacy_xml import parse_legacy_xml
from nodl.legacy import Converted, convert_legacy
from nodl.legacy.converted import origin_of

LEGACY_PKG = FIXTURES / 'index' / 'legacy' / 'share' / 'legacy_pkg' / 'legacy_pkg.nodl.xml'


def talker() -> Converted:
    converted = convert_legacy(parse_legacy_xml(LEGACY_PKG))
    return next(c for c in converted if c.node.executable == 'talker')


def line_of(text: str) -> int:
    """The 1-based line of the fixture holding ``text`` (once)."""
    lines = LEGACY_PKG.read_text(encoding='utf-8').splitlines()
    found = [n for n, line in enumerate(lines, 1) if text in line]
    assert len(found) == 1, text
    return found[0]


def test_each_entry_maps_to_the_element_it_came_from() -> None:
    converted = talker()
    assert converted.position(('main', 'parameters', 'rate')) == (line_of('name="rate"'), 5)
    assert converted.position(('main', 'publishers', 0)) == (line_of('name="chatter"'), 5)
    assert converted.position(('main', 'publishers', 0, 'qos')) == (line_of('depth="10"'), 7)
    assert converted.position(('main', 'service_servers', 0)) == (line_of('name="reset"'), 5)
    assert converted.position(('main', 'action_servers', 0)) == (line_of('name="fibonacci"'), 5)


def test_a_topic_with_both_roles_maps_both_entries_to_its_element() -> None:
    converted = talker()
    echo = (line_of('name="echo"'), 5)
    assert converted.position(('main', 'publishers', 1)) == echo
    assert converted.position(('main', 'subscriptions', 0)) == echo


def test_attributes_map_to_their_own_positions() -> None:
    converted = talker()
    line = line_of('name="rate"')
    assert converted.position(('main', 'parameters', 'rate', 'name')) == (line, 16)
    assert converted.position(('main', 'parameters', 'rate', 'type')) == (line, 28)
    assert converted.position(('main', 'publishers', 0, 'qos', 'reliability')) == (
        line_of('depth="10"'), 23)


def test_a_path_without_a_position_falls_back_to_the_enclosing_entry() -> None:
    converted = talker()
    node = (converted.node.line, converted.node.column)
    assert node == (line_of('executable="talker"'), 3)
    # made up by the converter: the QoS history of a <qos> that only sets a depth
    assert converted.position(('main', 'publishers', 0, 'qos', 'history')) == (
        line_of('depth="10"'), 7)
    assert converted.position(('main', 'publishers', 0, 'description')) == (
        line_of('name="chatter"'), 5)
    assert converted.position(('nodl_version',)) == node
    assert converted.position(('main', 'publishers')) == node
    assert converted.position(()) == node


def test_origin_of_is_line_one_when_nothing_is_known() -> None:
    assert origin_of({}, ('main', 'publishers', 0)) == (1, 1)
    assert origin_of({(): (4, 3)}, ('main', 'publishers', 0)) == (4, 3)


def test_a_converted_made_by_hand_maps_everything_to_its_node() -> None:
    node = talker().node
    made = Converted('talker.nodl.yaml', {}, [], str(LEGACY_PKG), node)
    assert made.origins == {(): (node.line, node.column)}
    assert made.position(('main', 'publishers', 0)) == (node.line, node.column)
