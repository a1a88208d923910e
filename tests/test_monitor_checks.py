"""The monitor's checks as coded findings (without ROS: fed what the graph would report)."""

from __future__ import annotations

from nodl.composition.entities import Location
from nodl.live.conformance import Difference
from nodl.monitor.checks import connection_findings, endpoint_findings, rate_finding
from nodl.monitor.expected import DeadlineTopic
from nodl.monitor.graph import TopicEndpoint

DEADLINE = DeadlineTopic('/s/data', 'std_msgs/msg/String', 100_000_000, Location('s.nodl.yaml', 9, 7))


def endpoint(node: str, kind: str, type_: str = 'std_msgs/msg/String', hash_: str = 'RIHS01_aa',
             **qos: object) -> TopicEndpoint:
    policies = {'reliability': 'RELIABLE', 'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC', **qos}
    return TopicEndpoint('/t', node, kind, type_, tuple(sorted(policies.items())), (), hash_, node)


def test_rate_nothing_is_error_slow_is_warning_within_tolerance_is_none() -> None:
    none = rate_finding(DEADLINE, 0, 2.0, 0.2)
    assert none is not None and (none.code, none.severity) == ('NODL435', 'error')
    assert none.location == DEADLINE.location
    slow = rate_finding(DEADLINE, 8, 2.0, 0.2)
    assert slow is not None and (slow.code, slow.severity) == ('NODL436', 'warning')
    assert "'/s/data' is published at 4 Hz, slower than the 10 Hz" in slow.message
    assert rate_finding(DEADLINE, 17, 2.0, 0.2) is None


def test_qos_incompatible_pairs_are_given_to_both_nodes() -> None:
    found = connection_findings({'/t': [endpoint('/pub', 'publisher', reliability='BEST_EFFORT'),
                                        endpoint('/sub', 'subscription', reliability='RELIABLE')]})
    assert [f.code for f in found['/pub']] == ['NODL553'] and found['/pub'] == found['/sub']
    assert found['/sub'][0].subject == 'topic /t /pub -> /sub'


def test_type_mismatch_and_hash_skew() -> None:
    mismatch = connection_findings({'/t': [endpoint('/a', 'publisher'),
                                           endpoint('/b', 'subscription', 'std_msgs/msg/Int32')]})
    assert [f.code for f in mismatch['/b']] == ['NODL552']
    skew = connection_findings({'/t': [endpoint('/a', 'publisher', hash_='RIHS01_aa'),
                                       endpoint('/b', 'subscription', hash_='RIHS01_bb')]})
    assert [f.code for f in skew['/a']] == ['NODL437'] and skew['/a'] == skew['/b']
    assert connection_findings({'/t': [endpoint('/a', 'publisher'),
                                       endpoint('/b', 'subscription')]}) == {}


def test_unverifiable_is_stated_once() -> None:
    differences = [Difference('unverifiable', 'service_servers', f'/s{i}', f'cannot {i}')
                   for i in range(3)] + [Difference('missing', 'publishers', '/x', 'gone')]
    found = endpoint_findings(differences)
    assert [f.code for f in found] == ['NODL401', 'NODL408']
    assert found[1].message == 'cannot be verified: cannot 0 (and 2 more)'
