"""Can a publisher and a subscription with these QoS profiles talk? The middleware's answer.

:func:`check_qos_compatible` applies the rules the DDS middlewares of ROS 2
share (``rmw_dds_common``'s ``qos_profile_check_compatible``, which
``rclpy.qos.qos_check_compatible`` reaches through rmw), verdict for verdict:

errors (the two endpoints will not be matched)
  * a ``BEST_EFFORT`` publisher and a ``RELIABLE`` subscription;
  * a ``VOLATILE`` publisher and a ``TRANSIENT_LOCAL`` subscription;
  * a subscription with a deadline and a publisher without one, or a
    subscription deadline shorter than the publisher's;
  * an ``AUTOMATIC`` publisher and a ``MANUAL_BY_TOPIC`` subscription;
  * a subscription with a liveliness lease duration and a publisher without
    one, or a subscription lease shorter than the publisher's;

warnings (only when there is no error: the outcome depends on what the
middleware picks for a ``SYSTEM_DEFAULT`` or ``UNKNOWN`` policy)
  * reliability, durability or liveliness unknown on both sides, or unknown
    on the publisher while the subscription asks for the stronger value
    (``RELIABLE``, ``TRANSIENT_LOCAL``, ``MANUAL_BY_TOPIC``), or unknown on
    the subscription while the publisher offers the weaker one.

``BEST_AVAILABLE`` is neither: the middleware resolves it (for a
subscription, from the publishers it finds) before matching, and the check
takes it as a value that causes no error and no warning.  A duration of 0 (or
an absent one) is rmw's "default", i.e. no deadline / no lease; every other
value is a duration, compared in nanoseconds.  History, depth and lifespan
play no part.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple

from nodl.model.qos import QoSProfile
from nodl.vocabulary import QOS_DURATIONS, QOS_ENUMS, QOS_KEYS

__all__ = ['QoSCompatibility', 'check_qos_compatible', 'VERDICTS']

#: The verdicts, from best to worst.
VERDICTS = ('ok', 'warning', 'error')

#: Values a profile read from the graph may hold besides the NoDL ones.
_EXTRA_VALUES = ('UNKNOWN',)
#: Values that say the policy is not known until the middleware picks it.
_UNKNOWN = ('SYSTEM_DEFAULT', 'UNKNOWN')
#: Per enumerated policy: (the weaker value a publisher may offer, the stronger one a
#: subscription may ask for, the words for the policy); the weaker offer cannot serve the
#: stronger request.
_ENUM_RULES = (
    ('reliability', 'BEST_EFFORT', 'RELIABLE', 'reliability'),
    ('durability', 'VOLATILE', 'TRANSIENT_LOCAL', 'durability'),
    ('liveliness', 'AUTOMATIC', 'MANUAL_BY_TOPIC', 'liveliness'),
)
_DURATION_RULES = (
    ('deadline_ns', 'deadline'),
    ('liveliness_lease_duration_ns', 'liveliness lease duration'),
)


class QoSCompatibility(NamedTuple):
    """The verdict (``ok``, ``warning`` or ``error``) and, unless ``ok``, why."""

    verdict: str
    reason: str


def _policies(qos: QoSProfile | Mapping[str, Any] | None, role: str) -> dict[str, Any]:
    """The policies that matter, as NoDL names them, with absent ones filled in."""
    if qos is None:
        data: Mapping[str, Any] = {}
    elif isinstance(qos, QoSProfile):
        data = qos.to_dict()
    elif isinstance(qos, Mapping):
        data = qos
        unknown = sorted(str(k) for k in data if k not in QOS_KEYS)
        if unknown:
            raise ValueError(f'{role} QoS: unknown polic{"ies" if len(unknown) > 1 else "y"} '
                             f'{", ".join(map(repr, unknown))}; expected some of {", ".join(QOS_KEYS)}')
    else:
        raise TypeError(f'{role} QoS must be a QoSProfile or a mapping, not {type(qos).__name__}')
    out: dict[str, Any] = {}
    for policy, _, _, _ in _ENUM_RULES:
        value = data.get(policy)
        value = 'SYSTEM_DEFAULT' if value is None else str(value).upper()
        allowed = QOS_ENUMS[policy] + _EXTRA_VALUES
        if value not in allowed:
            raise ValueError(f'{role} QoS: invalid {policy} {data.get(policy)!r}; expected one of '
                             f'{", ".join(allowed)}')
        out[policy] = value
    for key, _ in _DURATION_RULES:
        assert key in QOS_DURATIONS
        value = data.get(key)
        if value is None:
            value = 0
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            raise ValueError(f'{role} QoS: invalid {key} {value!r}; expected a whole number of '
                             'nanoseconds, 0 or more (0: none)')
        out[key] = value
    return out


def _words(value: str) -> str:
    return value.lower().replace('_', ' ')


def check_qos_compatible(publisher_qos: QoSProfile | Mapping[str, Any] | None,
                         subscription_qos: QoSProfile | Mapping[str, Any] | None
                         ) -> QoSCompatibility:
    """Whether a publisher and a subscription with these profiles can communicate.

    Each profile is a :class:`~nodl.model.QoSProfile`, a mapping in
    NoDL form (``reliability``, ``durability``, ``liveliness``,
    ``deadline_ns``, ``liveliness_lease_duration_ns``, ...; an absent policy
    is ``SYSTEM_DEFAULT``, an absent duration is none) or ``None`` (all
    absent).  Returns ``(verdict, reason)``: ``ok`` with an empty reason,
    ``warning`` or ``error`` with one sentence per problem naming the policy.
    Raises ``ValueError`` for a value that is not a QoS policy value.
    """
    pub = _policies(publisher_qos, 'publisher')
    sub = _policies(subscription_qos, 'subscription')
    reliability, durability, liveliness = (_enum_error(pub, sub, rule) for rule in _ENUM_RULES)
    # in rmw's order: reliability, durability, deadline, liveliness, lease duration
    errors = [e for e in (reliability, durability, _duration_error(pub, sub, *_DURATION_RULES[0]),
                          liveliness, _duration_error(pub, sub, *_DURATION_RULES[1])) if e]
    if errors:
        return QoSCompatibility('error', '; '.join(errors))
    warnings: list[str] = []
    for policy, weak, strong, words in _ENUM_RULES:
        pub_unknown, sub_unknown = pub[policy] in _UNKNOWN, sub[policy] in _UNKNOWN
        if pub_unknown and sub_unknown:
            warnings.append(f'{words}: the publisher\'s is {pub[policy]} and the subscription\'s '
                            f'is {sub[policy]}, so the middleware decides whether they match')
        elif pub_unknown and sub[policy] == strong:
            warnings.append(f'{words}: the subscription requests {_words(strong)} but the '
                            f'publisher\'s is {pub[policy]}, which may be {_words(weak)}')
        elif pub[policy] == weak and sub_unknown:
            warnings.append(f'{words}: the publisher offers {_words(weak)} but the subscription\'s '
                            f'is {sub[policy]}, which may be {_words(strong)}')
    if warnings:
        return QoSCompatibility('warning', '; '.join(warnings))
    return QoSCompatibility('ok', '')


def _enum_error(pub: dict[str, Any], sub: dict[str, Any], rule: tuple[str, str, str, str]
                ) -> str | None:
    policy, weak, strong, words = rule
    if pub[policy] == weak and sub[policy] == strong:
        return (f'{words}: the publisher offers {_words(weak)} but the subscription requests '
                f'{_words(strong)}')
    return None


def _duration_error(pub: dict[str, Any], sub: dict[str, Any], key: str, words: str) -> str | None:
    offered, requested = pub[key], sub[key]
    if not offered and requested:
        return f'{words}: the subscription requests {requested} ns but the publisher offers none'
    if offered and requested and requested < offered:
        return (f'{words}: the subscription requests {requested} ns, shorter than the '
                f'{offered} ns the publisher offers')
    return None
