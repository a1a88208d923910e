"""A node's view from a graph snapshot: QoS from the topic infos, actions folded."""

from __future__ import annotations

from nodl_schema.monitor.graph import Snapshot, TopicEndpoint, observed_node


def test_observed_node_from_a_snapshot() -> None:
    snapshot = Snapshot(0.0, {'/n': 1}, {'/n': {
        'publishers': [('/n/out', ['std_msgs/msg/String']),
                       ('/f/_action/status', ['action_msgs/msg/GoalStatusArray'])],
        'subscriptions': [],
        'service_servers': [('/f/_action/send_goal', ['test_msgs/action/Fibonacci_SendGoal'])],
        'service_clients': []}},
        {'/n/out': [TopicEndpoint('/n/out', '/n', 'publisher', 'std_msgs/msg/String',
                                  (('reliability', 'RELIABLE'),), ('history',), '', '00')]})
    observed = observed_node('/n', snapshot)
    assert observed is not None
    assert [(e.name, e.qos, e.unobserved) for e in observed.publishers] == [
        ('/n/out', {'reliability': 'RELIABLE'}, ['history'])]
    assert [(e.name, e.type) for e in observed.action_servers] == [('/f', 'test_msgs/action/Fibonacci')]
    assert observed.service_servers == []
    assert observed_node('/absent', snapshot) is None
