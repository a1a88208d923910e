"""Entity kinds, providers, interface types and locations (nodl.composition.entities)."""

from __future__ import annotations

import pytest

from nodl.composition.entities import (
    PROVIDER_OF_ROLE,
    EntityKind,
    InterfaceType,
    Location,
    Provider,
    parse_entity_type,
)
from nodl.model.parameter_types import TypeSpec
from nodl.vocabulary import SECTIONS


def test_every_section_has_a_kind_and_back() -> None:
    assert [EntityKind.of_section(s.key) for s in SECTIONS] == [
        EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION, EntityKind.SERVICE_SERVER,
        EntityKind.SERVICE_CLIENT, EntityKind.ACTION_SERVER, EntityKind.ACTION_CLIENT]
    for kind in EntityKind:
        assert EntityKind.of_section(kind.section) is kind
    assert EntityKind.of_section('parameters') is EntityKind.PARAMETER


@pytest.mark.parametrize('kind, communication, offers, word', [
    (EntityKind.PARAMETER, None, False, 'parameter'),
    (EntityKind.PUBLISHER, 'topic', True, 'publisher'),
    (EntityKind.SUBSCRIPTION, 'topic', False, 'subscription'),
    (EntityKind.SERVICE_SERVER, 'service', True, 'service server'),
    (EntityKind.SERVICE_CLIENT, 'service', False, 'service client'),
    (EntityKind.ACTION_SERVER, 'action', True, 'action server'),
    (EntityKind.ACTION_CLIENT, 'action', False, 'action client'),
])
def test_kind_properties(kind: EntityKind, communication: str | None, offers: bool, word: str) -> None:
    assert (kind.communication, kind.offers, kind.word) == (communication, offers, word)
    assert str(kind) == kind.value


def test_providers_follow_the_layer_that_declares_first() -> None:
    assert PROVIDER_OF_ROLE == {'base': Provider.CLIENT_LIBRARY, 'mixin': Provider.OTHER_CODE,
                                'main': Provider.IMPLEMENTATION}


def test_interface_types_parse_and_print() -> None:
    parsed = InterfaceType.parse('std_msgs/msg/String')
    assert parsed == ('std_msgs', 'msg', 'String')
    assert (parsed.package, parsed.namespace, parsed.name) == ('std_msgs', 'msg', 'String')
    assert str(parsed) == 'std_msgs/msg/String'
    # the short form takes the namespace of the communication
    assert str(InterfaceType.parse('std_srvs/Trigger', 'service')) == 'std_srvs/srv/Trigger'
    assert str(InterfaceType.parse('nav2_msgs/NavigateToPose', 'action')) == \
        'nav2_msgs/action/NavigateToPose'
    for bad in ('String', 'a//b', 'a/b/c/d', ''):
        with pytest.raises(ValueError, match='is not an interface type'):
            InterfaceType.parse(bad, 'topic')
    with pytest.raises(ValueError):
        InterfaceType.parse('std_msgs/String')  # short, and no communication to complete it


def test_entity_types_are_parsed_by_kind() -> None:
    assert parse_entity_type(EntityKind.PARAMETER, 'double_array') == TypeSpec('double_array',
                                                                                'double_array')
    assert parse_entity_type(EntityKind.SUBSCRIPTION, 'std_msgs/msg/Bool') == \
        InterfaceType('std_msgs', 'msg', 'Bool')
    assert parse_entity_type(EntityKind.PUBLISHER, 'nonsense') is None


def test_location_text() -> None:
    assert str(Location('a.yaml', 3, 5)) == 'a.yaml:3:5'
    assert str(Location('a.yaml', 0, 0)) == 'a.yaml'
