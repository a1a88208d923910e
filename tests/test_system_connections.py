"""Systems (nodl.system.connections): connections per topic, service and action; peers."""

from __future__ import annotations

import pytest

from conftest import FIXTURES
from nodl.system import EntityKind, NodeInstance, Provider, System, resolve_node
from nodl.system.connections import Connection

SYSTEM = FIXTURES / 'system'


@pytest.fixture(scope='module')
def system() -> System:
    talker = resolve_node(SYSTEM / 'talker.nodl.yaml')
    listener = resolve_node(SYSTEM / 'listener.nodl.yaml', client_library='rclcpp')
    return System([NodeInstance(talker, 'talker', '/'),
                   NodeInstance(listener, 'listener', '/', ['chatter:=/talker/chatter']),
                   NodeInstance(listener, 'listener', '/spare')])


def test_topic_connections(system: System) -> None:
    chatter = system.connection('topic', '/talker/chatter')
    assert chatter is not None and chatter.connected
    assert [p.instance.fqn for p in chatter.publishers] == ['/talker']
    assert [s.instance.fqn for s in chatter.subscriptions] == ['/listener']
    assert chatter.servers == chatter.clients == ()
    assert chatter.types == ['std_msgs/msg/String']
    assert str(chatter) == 'topic /talker/chatter: 1 publishers, 1 subscriptions'
    spare = system.connection('topic', '/spare/chatter')
    assert spare is not None and not spare.connected and spare.publishers == ()


def test_services_and_actions(system: System) -> None:
    reset = system.connection('service', '/talker/reset')
    assert reset is not None
    assert [s.instance.fqn for s in reset.servers] == ['/talker']
    assert sorted(c.instance.fqn for c in reset.clients) == ['/listener']
    navigate = system.connection('action', '/navigate')
    assert navigate is not None
    assert sorted(s.instance.fqn for s in navigate.servers) == ['/listener', '/spare/listener']
    assert [c.instance.fqn for c in navigate.clients] == ['/talker']
    assert {c.communication for c in system.services} == {'service'}
    assert [c.name for c in system.actions] == ['/navigate']


def test_peers(system: System) -> None:
    talker = system.instance('/talker')
    assert [p.instance.fqn for p in system.peers(talker, ('publisher', '~/chatter'))] == ['/listener']
    assert sorted(p.instance.fqn for p in system.peers('/talker', ('action_client', '/navigate'))) == [
        '/listener', '/spare/listener']
    listener = system.instance('/listener')
    entity = listener.resolved.entity(EntityKind.SUBSCRIPTION, 'chatter')
    [peer] = system.peers(listener, entity)
    assert (peer.instance.fqn, peer.name, peer.entity.name) == ('/talker', '/talker/chatter', '~/chatter')
    assert system.peers(talker, ('parameter', 'rate')) == []
    with pytest.raises(KeyError):
        system.instance('/nobody')


def test_base_entities_are_included_and_flagged(system: System) -> None:
    events = system.connection('topic', '/parameter_events')
    assert events is not None
    assert len(events.publishers) == 3
    # only the rclcpp listeners subscribe (their time source)
    assert sorted(s.instance.fqn for s in events.subscriptions) == ['/listener', '/spare/listener']
    assert events.only_client_library()
    names = {c.name for c in system.connections(include_client_library=False)}
    assert '/rosout' not in names and '/parameter_events' not in names
    assert '/talker/chatter' in names and '/talker/get_parameters' not in names
    rosout = system.connection('topic', '/rosout')
    assert rosout is not None and {p.provider for p in rosout.publishers} == {Provider.CLIENT_LIBRARY}


def test_connections_are_sorted_and_name_clashes_found() -> None:
    listener = resolve_node(SYSTEM / 'listener.nodl.yaml')
    twice = System([NodeInstance(listener, 'listener', '/'), NodeInstance(listener, 'listener', '/')])
    assert list(twice.name_clashes()) == ['/listener']
    keys = [(c.communication, c.name) for c in twice.connections()]
    assert keys == sorted(keys)
    with pytest.raises(KeyError):
        twice.instance('/listener')  # ambiguous


def _lone(connection: Connection) -> bool:
    return connection.communication != 'topic' and len(connection.offering) == 1 \
        and not connection.using


@pytest.mark.parametrize('lone_first', [True, False])
def test_lone_servers_left_out_on_request(lone_first: bool) -> None:
    talker = resolve_node(SYSTEM / 'talker.nodl.yaml')
    listener = resolve_node(SYSTEM / 'listener.nodl.yaml', client_library='rclcpp')

    instances = [NodeInstance(talker, 'talker', '/'),
                 NodeInstance(listener, 'listener', '/', ['chatter:=/talker/chatter']),
                 NodeInstance(listener, 'listener', '/spare')]

    def made() -> System:
        return System(instances)

    every = made().connections()
    assert any(_lone(c) for c in every) and not all(_lone(c) for c in every)
    system = made()
    # the count does not make the lone servers; asked before or after they are made, the
    # connections without them are every connection's others, in the same order
    assert repr(system) == f'System(3 instances, {len(every)} connections)'
    if not lone_first:
        assert system.connections() == every
    for communication in (None, 'topic', 'service', 'action'):
        whole = [c for c in every if communication in (None, c.communication)]
        assert system.connections(communication, lone_servers=False) == \
            [c for c in whole if not _lone(c)]
        assert system.connections(communication, include_client_library=False,
                                  lone_servers=False) == \
            [c for c in system.connections(communication, include_client_library=False)
             if not _lone(c)]
    lone = next(c for c in every if _lone(c))
    assert system.connection(lone.communication, lone.name) == lone
    assert system.connections() == every
    assert repr(system) == f'System(3 instances, {len(every)} connections)'
