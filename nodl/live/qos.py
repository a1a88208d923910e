"""rclpy QoS profiles as NoDL QoS mappings, saying what the middleware did not report."""

from __future__ import annotations

from typing import Any

from nodl.vocabulary import QOS_DURATIONS, QOS_ENUMS

__all__ = ['qos_from_rclpy', 'INFINITE_NS']

#: Durations at or above this are "infinite" (rmw's INT64_MAX-ish values).
INFINITE_NS = 9223372036854775807 - 10**9
_UNKNOWN = 'UNKNOWN'


def _policy(value: Any) -> str:
    name = getattr(value, 'name', str(value))
    for prefix in ('RMW_QOS_POLICY_HISTORY_', 'RMW_QOS_POLICY_RELIABILITY_',
                   'RMW_QOS_POLICY_DURABILITY_', 'RMW_QOS_POLICY_LIVELINESS_'):
        if name.startswith(prefix):
            name = name[len(prefix):]
    return name


def _duration_ns(value: Any) -> int | None:
    ns = getattr(value, 'nanoseconds', None)
    if ns is None:
        return None
    return None if ns <= 0 or ns >= INFINITE_NS else int(ns)


def qos_from_rclpy(profile: Any) -> tuple[dict[str, Any], list[str]]:
    """The NoDL QoS fields an observed profile reports, and the fields it could not report."""
    qos: dict[str, Any] = {}
    unobserved: list[str] = []
    history = _policy(profile.history)
    if history == _UNKNOWN:
        unobserved += ['history', 'depth']
    else:
        qos['history'] = history
        if history == 'KEEP_LAST' and profile.depth > 0:
            qos['depth'] = int(profile.depth)
    for field in (policy for policy in QOS_ENUMS if policy != 'history'):
        value = _policy(getattr(profile, field))
        if value == _UNKNOWN:
            unobserved.append(field)
        else:
            qos[field] = value
    for field, attribute in QOS_DURATIONS.items():
        ns = _duration_ns(getattr(profile, attribute))
        if ns is not None:
            qos[field] = ns
    return qos, unobserved
