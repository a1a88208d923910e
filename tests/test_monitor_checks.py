"""The monitor's checks as coded findings (without ROS: fed what the graph would report)."""

from __future__ import annotations

from nodl.composition.entities import Location
from nodl.live.conformance import LiveDiagnostic
from nodl.monitor.checks import connection_findings, endpoint_findings, rate_finding
from nodl.monitor.expected import DeadlineTopic
from nodl.monitor.graph import LiveTopicEndpoint

DEADLINE = DeadlineTopic('/s/data', 'std_msgs/msg/String', 100_000_000, Location('s.nodl.yaml', 9, 7))


def endpoint(node: str, kind: str, type_: str = 'std_msgs/msg/String', hash_: str = 'RIHS01_aa',
             **qos: object) -> LiveTopicEndpoint:
    policies = {'reliability': 'RELIABLE', 'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC', **qos}
    return LiveTopicEndpoint('/t', node, kind, type_, tuple(sorted(policies.items())), (), hash_, node)


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
    differences = [LiveDiagnostic('unverifiable', 'service_servers', f'/s{i}', f'cannot {i}')
                   for i in range(3)] + [LiveDiagnostic('missing', 'publishers', '/x', 'gone')]
    found = endpoint_findings(differences)
    assert [f.code for f in found] == ['NODL401', 'NODL408']
    assert found[1].message == 'cannot be verified: cannot 0 (and 2 more)'


def test_a_difference_keeps_its_severity_and_its_place_in_the_definition() -> None:
    declared = LiveDiagnostic('missing', 'publishers', '/x', 'gone', location=Location('s.nodl.yaml', 4, 7))
    # observed but not declared: no declaration, but it points at the section it belongs in
    extra = LiveDiagnostic('extra', 'publishers', '/y', 'not declared', at=Location('s.nodl.yaml', 3, 3))
    unplaced = LiveDiagnostic('extra', 'publishers', '/z', 'not declared')
    missing, undeclared, nowhere = endpoint_findings([declared, extra, unplaced])
    assert (missing.severity, missing.location) == ('error', Location('s.nodl.yaml', 4, 7))
    assert (undeclared.severity, undeclared.location) == ('error', Location('s.nodl.yaml', 3, 3))
    assert str(undeclared.diagnostic(Location('launch.py', 9, 1))).startswith('s.nodl.yaml:3:3: error: ')
    assert nowhere.location is None  # not placed: the status's own place is used
    assert str(nowhere.diagnostic(Location('launch.py', 9, 1))).startswith('launch.py:9:1: error: ')
