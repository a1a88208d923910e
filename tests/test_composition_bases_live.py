"""The built-in bases tell the truth: compared, both ways, with real rclpy nodes.

A default rclpy Node and LifecycleNode are started in processes of their
own and observed through the ROS graph; every entity the base declares must
be observed, and every observed entity must be in the base.
"""

from __future__ import annotations

import pytest

from nodl.composition.bases import base_layer
from nodl.live.observe import observe_node
from nodl.naming import expand


def _declared(base: str, name: str, namespace: str) -> dict[str, set[tuple[str, str]]]:
    iface = base_layer(base).interface
    return {section: {(expand(e.name, name, namespace), e.type) for e in iface.endpoints(section)}
            for section in ('publishers', 'subscriptions', 'service_servers', 'service_clients',
                            'action_servers', 'action_clients')}


def _observed(observed) -> dict[str, set[tuple[str, str]]]:  # type: ignore[no-untyped-def]
    return {section: {(e.name, e.type) for e in getattr(observed, section)}
            for section in ('publishers', 'subscriptions', 'service_servers', 'service_clients',
                            'action_servers', 'action_clients')}


@pytest.mark.parametrize('base, script', [('node', 'plain_node.py'),
                                          ('lifecycle_node', 'lifecycle_node.py')])
def test_base_matches_a_real_node_both_ways(ros_node, base: str, script: str) -> None:
    node = ros_node(script, f'default_{base}', '/bases')
    observed = observe_node(node.fqn, timeout=15)
    declared = _declared(base, node.name, node.namespace)
    seen = _observed(observed)
    for section in declared:
        assert declared[section] - seen[section] == set(), f'{section}: declared but not observed'
        assert seen[section] - declared[section] == set(), f'{section}: observed but not in the base'

    params = base_layer(base).interface.parameters or {}
    assert observed.parameters is not None
    assert set(params) == set(observed.parameters)
    for name, param in params.items():
        real = observed.parameters[name]
        assert (param.type, param.default_value, param.read_only) == \
            (real.type, real.value, real.read_only), name


def test_observed_topic_qos_agrees_with_the_base(ros_node) -> None:
    node = ros_node('lifecycle_node.py', 'qos_probe', '/bases')
    observed = observe_node(node.fqn, timeout=15, parameters=False)
    declared = {expand(e.name, node.name, node.namespace): e.qos
                for e in base_layer('lifecycle_node').interface.endpoints('publishers')}
    for endpoint in observed.publishers:
        qos = declared[endpoint.name]
        for field, value in (endpoint.qos or {}).items():
            assert getattr(qos, field) == value, (endpoint.name, field)


@pytest.mark.parametrize('base, script', [('node', 'plain_node.py'),
                                          ('lifecycle_node', 'lifecycle_node.py')])
def test_the_rclcpp_base_is_the_observed_rclpy_node_plus_rclcpp_documented_additions(
        ros_node, base: str, script: str) -> None:
    # rclcpp cannot run here: its base is derived from rclcpp's documented behaviour. What can be
    # checked is that it differs from a real rclpy node by exactly those additions.
    node = ros_node(script, f'cpp_{base}', '/bases')
    observed = _observed(observe_node(node.fqn, timeout=15, parameters=False))
    iface = base_layer(base, 'rclcpp').interface
    declared = {section: {(expand(e.name, node.name, node.namespace), e.type)
                          for e in iface.endpoints(section)} for section in observed}
    extra = {(section, name) for section in declared for name, _ in declared[section] - observed[section]}
    assert extra == {('subscriptions', '/parameter_events')}
    for section in observed:
        assert observed[section] - declared[section] == set(), section
