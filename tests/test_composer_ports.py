"""nodl.composer.ports: whether two endpoints can be joined (kinds, types, QoS)."""

from __future__ import annotations

from nodl.composer.ports import Port, find_port, verdict

RELIABLE = {'reliability': 'RELIABLE', 'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}


def _port(kind: str, name: str, type_: str = 'std_msgs/msg/String', qos=RELIABLE,  # type: ignore[no-untyped-def]
          final: str | None = None) -> Port:
    return Port('n1', kind, name, final or '/' + name.lstrip('~/'), type_, qos)


def test_kinds_must_pair() -> None:
    assert verdict(_port('publisher', 'a'), _port('subscription', 'b')).ok
    assert verdict(_port('subscription', 'b'), _port('publisher', 'a')).ok
    assert verdict(_port('service_client', 'a', 'std_srvs/srv/Trigger', None),
                   _port('service_server', 'b', 'std_srvs/srv/Trigger', None)).ok
    assert verdict(_port('action_server', 'a', 'x/action/Y', None),
                   _port('action_client', 'b', 'x/action/Y', None)).ok
    for first, second in (('publisher', 'publisher'), ('publisher', 'service_client'),
                          ('action_server', 'service_client')):
        judged = verdict(_port(first, 'a'), _port(second, 'b'))
        assert (judged.verdict, judged.code) == ('error', 'NODL972')


def test_types_must_be_the_same_short_forms_included() -> None:
    assert verdict(_port('publisher', 'a', 'std_msgs/String'), _port('subscription', 'b')).ok
    judged = verdict(_port('publisher', 'a', 'std_msgs/msg/Int32'), _port('subscription', 'b'))
    assert judged.code == 'NODL973' and 'std_msgs/msg/Int32' in judged.reason


def test_qos_verdicts_are_the_middlewares() -> None:
    best_effort = {**RELIABLE, 'reliability': 'BEST_EFFORT'}
    refused = verdict(_port('publisher', 'a', qos=best_effort), _port('subscription', 'b'))
    assert refused.code == 'NODL974' and 'reliability' in refused.reason
    unknown = verdict(_port('publisher', 'a', qos=best_effort),
                      _port('subscription', 'b', qos={}))
    assert (unknown.verdict, unknown.code) == ('warning', 'NODL975')
    fine = verdict(_port('publisher', 'a'), _port('subscription', 'b', qos=best_effort))
    assert fine.verdict == 'ok' and not fine.connected
    assert verdict(_port('publisher', 'a'), _port('subscription', 'a')).connected


def test_find_port_by_declared_final_or_kind() -> None:
    ports = [_port('publisher', 'scan', final='/robot/scan'),
             _port('subscription', 'scan', final='/robot/scan'),
             _port('service_server', '~/reset', 'std_srvs/srv/Trigger', None, '/robot/n/reset')]
    assert len(find_port(ports, 'scan')) == 2
    assert [p.kind for p in find_port(ports, 'subscription/scan')] == ['subscription']
    assert find_port(ports, 'reset') == [ports[2]] == find_port(ports, '/robot/n/reset')
    assert find_port(ports, 'nothing') == []
