"""A node's view from a graph snapshot: QoS from the topic infos, actions folded."""

from __future__ import annotations

import time

import pytest

from nodl.monitor.graph import LiveTopicEndpoint, Snapshot, observed_node


def test_observed_node_from_a_snapshot() -> None:
    snapshot = Snapshot(0.0, {'/n': 1}, {'/n': {
        'publishers': [('/n/out', ['std_msgs/msg/String']),
                       ('/f/_action/status', ['action_msgs/msg/GoalStatusArray'])],
        'subscriptions': [],
        'service_servers': [('/f/_action/send_goal', ['test_msgs/action/Fibonacci_SendGoal'])],
        'service_clients': []}},
        {'/n/out': [LiveTopicEndpoint('/n/out', '/n', 'publisher', 'std_msgs/msg/String',
                                      (('reliability', 'RELIABLE'),), ('history',), '', '00')]})
    observed = observed_node('/n', snapshot)
    assert observed is not None
    assert [(e.name, e.qos, e.unobserved) for e in observed.publishers] == [
        ('/n/out', {'reliability': 'RELIABLE'}, ['history'])]
    assert [(e.name, e.type) for e in observed.action_servers] == [('/f', 'test_msgs/action/Fibonacci')]
    assert observed.service_servers == []
    assert observed_node('/absent', snapshot) is None


class _Graph:
    """What rcl reports, for GraphView.scan: one publisher on '/t', whose node rcl names
    once its node's announcement has arrived (before that: rmw's unknown node)."""

    def __init__(self) -> None:
        self.node_name, self.node_namespace = '_NODE_NAME_UNKNOWN_', '_NODE_NAMESPACE_UNKNOWN_'

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        return [('n', '/')]

    def get_topic_names_and_types(self) -> list[tuple[str, list[str]]]:
        return [('/t', ['std_msgs/msg/String'])]

    def get_publisher_names_and_types_by_node(self, name: str, namespace: str) -> list[object]:
        return [('/t', ['std_msgs/msg/String'])]

    get_subscriber_names_and_types_by_node = get_service_names_and_types_by_node = \
        get_client_names_and_types_by_node = lambda self, name, namespace: []  # noqa: E731

    def publishers(self, topic: str) -> list[dict[str, object]]:
        from rclpy.duration import Duration

        forever = Duration(nanoseconds=2**63 - 1)
        return [{'node_name': self.node_name, 'node_namespace': self.node_namespace,
                 'topic_type': 'std_msgs/msg/String', 'topic_type_hash': {'version': 0, 'value': b''},
                 'endpoint_type': 1, 'endpoint_gid': list(range(16)),
                 'qos_profile': {'depth': 0, 'history': 3, 'reliability': 1, 'durability': 2,
                                 'lifespan': forever, 'deadline': forever, 'liveliness': 1,
                                 'liveliness_lease_duration': forever,
                                 'avoid_ros_namespace_conventions': False}}]


def test_an_endpoint_is_converted_again_once_its_node_is_known() -> None:
    from nodl.monitor.graph import GraphView

    graph = _Graph()
    view = GraphView(graph)
    view._info_functions = lambda: (graph.publishers, lambda topic: [])  # type: ignore[method-assign]
    first = view.scan({'/n': 1}, ['/n'])
    assert [e.node for e in first.topics['/t']] == ['/_NODE_NAMESPACE_UNKNOWN_/_NODE_NAME_UNKNOWN_']
    assert first.of_node('/n') == ()
    graph.node_name, graph.node_namespace = 'n', '/'  # same endpoint (GID), its node now known
    second = view.scan({'/n': 1}, ['/n'])
    assert [(e.node, e.qos_dict['reliability']) for e in second.of_node('/n')] == [('/n', 'RELIABLE')]
    observed = observed_node('/n', second)
    assert observed is not None and observed.publishers[0].unobserved == ['history', 'depth']


def test_the_raw_infos_and_rclpy_s_own_methods_give_one_snapshot(
        monkeypatch: pytest.MonkeyPatch) -> None:
    import rclpy
    import std_msgs.msg
    from rclpy.qos import QoSProfile, ReliabilityPolicy

    from nodl.monitor.graph import GraphView

    context = rclpy.Context()
    rclpy.init(context=context)
    try:
        talker = rclpy.create_node('graph_talker', namespace='/g', context=context)
        talker.create_publisher(std_msgs.msg.String, 'out', QoSProfile(
            depth=5, reliability=ReliabilityPolicy.BEST_EFFORT))
        me = rclpy.create_node('_nodl_monitor_me', context=context)
        end = time.monotonic() + 10
        while time.monotonic() < end and not me.get_publishers_info_by_topic('/g/out'):
            time.sleep(0.05)
        present = {'/g/graph_talker': 1}
        raw = GraphView(me).scan(present, ['/g/graph_talker'])
        # an rclpy whose extension lacks the raw calls (rclpy's own module keeps its own)
        from rclpy.impl import implementation_singleton
        with monkeypatch.context() as patch:
            patch.setattr(implementation_singleton, 'rclpy_implementation', object())
            wrapped = GraphView(me).scan(present, ['/g/graph_talker'])
        assert raw.topics == wrapped.topics
        assert [(e.node, e.kind, e.qos_dict['reliability']) for e in raw.topics['/g/out']] == [
            ('/g/graph_talker', 'publisher', 'BEST_EFFORT')]
        assert ('/g/out', ['std_msgs/msg/String']) in raw.endpoints['/g/graph_talker']['publishers']
        # the toolkit's own nodes (the monitor's) are never the user's
        assert '/_nodl_monitor_me' not in {e.node for infos in raw.topics.values() for e in infos}
    finally:
        rclpy.shutdown(context=context)


def test_discovered_waits_for_every_announced_endpoint_s_qos() -> None:
    from nodl.monitor.graph import discovered

    raw = {'publishers': [('/n/out', ['std_msgs/msg/String'])],
           'subscriptions': [('/n/in', ['std_msgs/msg/String'])],
           'service_servers': [], 'service_clients': []}
    out = LiveTopicEndpoint('/n/out', '/n', 'publisher', 'std_msgs/msg/String', (), (), '', '01')
    into = LiveTopicEndpoint('/n/in', '/n', 'subscription', 'std_msgs/msg/String', (), (), '', '02')
    assert not discovered(Snapshot(0.0, {'/n': 1}, {'/n': raw}, {'/n/out': [out]}))
    assert discovered(Snapshot(0.0, {'/n': 1}, {'/n': raw}, {'/n/out': [out], '/n/in': [into]}))


def test_a_long_scan_lets_what_cannot_wait_run_and_does_not_count_it() -> None:
    """GraphView.scan calls ``meanwhile`` every SCAN_CHUNK topics (nodl monitor publishes
    then, if due); the processor time it takes is not the scan's cost."""
    from nodl.monitor.graph import SCAN_CHUNK, GraphView

    class Crowded(_Graph):
        def get_topic_names_and_types(self) -> list[tuple[str, list[str]]]:
            return [(f'/t{i}', ['std_msgs/msg/String']) for i in range(2 * SCAN_CHUNK + 50)]

    graph = Crowded()
    view = GraphView(graph)
    view._info_functions = lambda: (lambda topic: [], lambda topic: [])  # type: ignore[method-assign]
    calls: list[float] = []

    def busy() -> None:
        end = time.process_time() + 0.05
        while time.process_time() < end:
            pass
        calls.append(time.monotonic())

    snapshot = view.scan({'/n': 1}, ['/n'], meanwhile=busy)
    assert len(calls) == 2
    assert snapshot.cost < 0.05
    assert view.scan({'/n': 1}, ['/n']).endpoints == snapshot.endpoints  # none: never called
