"""qos_from_rclpy: real rclpy QoS profiles as NoDL QoS mappings."""

from __future__ import annotations

import pytest
from rclpy.duration import Duration, Infinite
from rclpy.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
    qos_profile_sensor_data,
    qos_profile_system_default,
)

from nodl.live.qos import INFINITE_NS, qos_from_rclpy
from nodl.model import QOS_POLICIES


def test_keep_last_reports_history_and_depth() -> None:
    qos, unobserved = qos_from_rclpy(QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=7))
    assert unobserved == []
    assert qos['history'] == 'KEEP_LAST'
    assert qos['depth'] == 7
    assert qos['reliability'] == 'RELIABLE'
    assert qos['durability'] == 'VOLATILE'


def test_keep_all_has_no_depth() -> None:
    qos, unobserved = qos_from_rclpy(QoSProfile(history=HistoryPolicy.KEEP_ALL, depth=5))
    assert unobserved == []
    assert qos['history'] == 'KEEP_ALL'
    assert 'depth' not in qos


def test_unknown_history_is_unobserved_with_its_depth() -> None:
    # What Fast DDS reports for every remote endpoint: history UNKNOWN, depth 0.
    profile = QoSProfile(history=HistoryPolicy.UNKNOWN, depth=0,
                         reliability=ReliabilityPolicy.BEST_EFFORT)
    qos, unobserved = qos_from_rclpy(profile)
    assert unobserved == ['history', 'depth']
    assert 'history' not in qos and 'depth' not in qos
    assert qos['reliability'] == 'BEST_EFFORT'


@pytest.mark.parametrize('field, policy', [
    ('reliability', ReliabilityPolicy.UNKNOWN),
    ('durability', DurabilityPolicy.UNKNOWN),
    ('liveliness', LivelinessPolicy.UNKNOWN),
])
def test_unknown_policies_are_unobserved(field: str, policy: object) -> None:
    profile = QoSProfile(depth=3)
    setattr(profile, field, policy)
    qos, unobserved = qos_from_rclpy(profile)
    assert unobserved == [field]
    assert field not in qos
    assert qos['depth'] == 3


def test_policy_names_are_the_rmw_names_without_prefix() -> None:
    profile = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT,
                         durability=DurabilityPolicy.TRANSIENT_LOCAL,
                         liveliness=LivelinessPolicy.MANUAL_BY_TOPIC)
    qos, _ = qos_from_rclpy(profile)
    assert (qos['reliability'], qos['durability'], qos['liveliness']) == \
        ('BEST_EFFORT', 'TRANSIENT_LOCAL', 'MANUAL_BY_TOPIC')
    qos, _ = qos_from_rclpy(QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_AVAILABLE,
                                       durability=DurabilityPolicy.SYSTEM_DEFAULT))
    assert (qos['reliability'], qos['durability']) == ('BEST_AVAILABLE', 'SYSTEM_DEFAULT')


def test_finite_durations_in_nanoseconds() -> None:
    profile = QoSProfile(depth=10, deadline=Duration(seconds=1), lifespan=Duration(nanoseconds=5),
                         liveliness=LivelinessPolicy.AUTOMATIC,
                         liveliness_lease_duration=Duration(seconds=2, nanoseconds=3))
    qos, unobserved = qos_from_rclpy(profile)
    assert unobserved == []
    assert qos['deadline_ns'] == 1_000_000_000
    assert qos['lifespan_ns'] == 5
    assert qos['liveliness_lease_duration_ns'] == 2_000_000_003
    assert all(isinstance(qos[k], int) for k in ('deadline_ns', 'lifespan_ns',
                                                  'liveliness_lease_duration_ns'))


def test_infinite_and_default_durations_are_left_out() -> None:
    # Infinite is what the graph reports for "no deadline"; 0 is rclpy's default.
    profile = QoSProfile(depth=10, deadline=Infinite, lifespan=Duration(),
                         liveliness_lease_duration=Duration(nanoseconds=INFINITE_NS + 1))
    qos, unobserved = qos_from_rclpy(profile)
    assert unobserved == []
    assert not {'deadline_ns', 'lifespan_ns', 'liveliness_lease_duration_ns'} & set(qos)


def test_every_reported_key_is_a_nodl_policy() -> None:
    for profile in (qos_profile_sensor_data, qos_profile_system_default,
                    QoSProfile(history=HistoryPolicy.UNKNOWN, depth=0, deadline=Duration(seconds=4))):
        qos, unobserved = qos_from_rclpy(profile)
        assert set(qos) <= set(QOS_POLICIES)
        assert set(unobserved) <= set(QOS_POLICIES)
        assert not set(qos) & set(unobserved)


def test_sensor_data_profile() -> None:
    qos, unobserved = qos_from_rclpy(qos_profile_sensor_data)
    assert unobserved == []
    assert qos == {'history': 'KEEP_LAST', 'depth': 5, 'reliability': 'BEST_EFFORT',
                   'durability': 'VOLATILE', 'liveliness': 'SYSTEM_DEFAULT'}


def test_profile_read_back_from_the_graph() -> None:
    """A profile as the graph API returns it (a real publisher in a private context)."""
    import rclpy
    from std_msgs.msg import String

    context = rclpy.Context()
    rclpy.init(context=context, args=['--ros-args', '--disable-rosout-logs'])
    try:
        node = rclpy.create_node('qos_probe', context=context, start_parameter_services=False,
                                 enable_rosout=False)
        try:
            node.create_publisher(String, 'qos_probe_topic', QoSProfile(
                history=HistoryPolicy.KEEP_LAST, depth=4, reliability=ReliabilityPolicy.BEST_EFFORT,
                durability=DurabilityPolicy.TRANSIENT_LOCAL, deadline=Duration(seconds=1)))
            infos = node.get_publishers_info_by_topic('/qos_probe_topic')
            assert len(infos) == 1
            qos, unobserved = qos_from_rclpy(infos[0].qos_profile)
        finally:
            node.destroy_node()
    finally:
        rclpy.shutdown(context=context)
    assert qos['reliability'] == 'BEST_EFFORT'
    assert qos['durability'] == 'TRANSIENT_LOCAL'
    assert qos['deadline_ns'] == 1_000_000_000
    assert 'lifespan_ns' not in qos  # reported as infinite
    if 'history' in unobserved:  # Fast DDS does not report history and depth
        assert unobserved[:2] == ['history', 'depth'] and 'depth' not in qos
    else:
        assert (qos['history'], qos['depth']) == ('KEEP_LAST', 4)
