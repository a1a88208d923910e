"""``rclcpp::QoS`` expressions built from every policy a definition declares.

A policy the definition does not give keeps rclcpp's default (the rmw
default profile), exactly as an undeclared policy claims nothing.  The
tables below map the vocabulary's values (:data:`nodl.vocabulary.QOS_ENUMS`)
to rclcpp's enumerators; a test keeps them complete.
"""

from __future__ import annotations

from nodl.model import QoSProfile
from nodl.vocabulary import QOS_DURATIONS

__all__ = ['CPP_POLICY_VALUES', 'qos_expression', 'DEFAULT_SERVICE_QOS']

#: Enumerated policy -> (rclcpp enum, NoDL value -> enumerator).
CPP_POLICY_VALUES: dict[str, tuple[str, dict[str, str]]] = {
    'history': ('rclcpp::HistoryPolicy', {
        'KEEP_LAST': 'KeepLast', 'KEEP_ALL': 'KeepAll', 'SYSTEM_DEFAULT': 'SystemDefault'}),
    'reliability': ('rclcpp::ReliabilityPolicy', {
        'RELIABLE': 'Reliable', 'BEST_EFFORT': 'BestEffort', 'SYSTEM_DEFAULT': 'SystemDefault',
        'BEST_AVAILABLE': 'BestAvailable'}),
    'durability': ('rclcpp::DurabilityPolicy', {
        'TRANSIENT_LOCAL': 'TransientLocal', 'VOLATILE': 'Volatile',
        'SYSTEM_DEFAULT': 'SystemDefault', 'BEST_AVAILABLE': 'BestAvailable'}),
    'liveliness': ('rclcpp::LivelinessPolicy', {
        'AUTOMATIC': 'Automatic', 'MANUAL_BY_TOPIC': 'ManualByTopic',
        'SYSTEM_DEFAULT': 'SystemDefault', 'BEST_AVAILABLE': 'BestAvailable'}),
}

#: What a service without declared QoS gets (rclcpp's default for services).
DEFAULT_SERVICE_QOS = 'rclcpp::ServicesQoS()'


def _enum(policy: str, value: str) -> str:
    enum, values = CPP_POLICY_VALUES[policy]
    return f'{enum}::{values[value]}'


def qos_expression(qos: QoSProfile | None, default: str = DEFAULT_SERVICE_QOS) -> str:
    """A C++ expression of type ``rclcpp::QoS`` with every declared policy of ``qos``."""
    if qos is None:
        return default
    if qos.history == 'KEEP_ALL':
        expr = 'rclcpp::QoS(rclcpp::KeepAll())'
    elif qos.history == 'KEEP_LAST':
        expr = f'rclcpp::QoS(rclcpp::KeepLast({int(qos.depth or 0)}))'
    else:  # SYSTEM_DEFAULT: the middleware's history, with the depth as written
        expr = ('rclcpp::QoS(rclcpp::QoSInitialization(RMW_QOS_POLICY_HISTORY_SYSTEM_DEFAULT, '
                f'{int(qos.depth or 0)}))')
    for policy in ('reliability', 'durability', 'liveliness'):
        value = getattr(qos, policy)
        if value is not None:
            expr += f'.{policy}({_enum(policy, value)})'
    for key, policy in QOS_DURATIONS.items():
        value = getattr(qos, key)
        if value is not None:
            expr += f'.{policy}(rclcpp::Duration::from_nanoseconds({int(value)}))'
    return expr
