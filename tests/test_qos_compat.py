"""check_qos_compatible against rclpy.qos.qos_check_compatible, verdict for verdict.

The cross products cover every value of reliability, durability and
liveliness on both sides (with the durations that decide errors), and a set
of deadlines and lease durations on both sides (with the values that decide
warnings): tens of thousands of pairs, each asked of the middleware itself.
"""

from __future__ import annotations

import itertools
from typing import Any

import pytest

from nodl.model import QoSProfile
from nodl.qos_compat import VERDICTS, check_qos_compatible
from nodl.vocabulary import QOS_ENUMS

ENUM_POLICIES = ('reliability', 'durability', 'liveliness')
#: Every value NoDL allows, and what rmw reports for a policy it cannot name.
ENUM_VALUES = {policy: (*QOS_ENUMS[policy], 'UNKNOWN') for policy in ENUM_POLICIES}
#: Durations in nanoseconds: none, tiny, around a second, rmw's "best available" and "infinite".
DURATIONS = (0, 1, 999_999_999, 1_000_000_000, 1_000_000_001, 5_500_000_000,
             2**63 - 2, 2**63 - 1)
#: (deadline, lease) of a publisher and a subscription, for the enum cross product: none, an
#: error from the deadline, an error from the lease (errors silence warnings), and durations
#: that agree (the duration cross product below has the rest).
DURATION_PAIRS = (((0, 0), (0, 0)), ((0, 7), (5, 3)), ((3, 9), (4, 9)))


def _rclpy_profile(policies: dict[str, Any]) -> Any:
    from rclpy.duration import Duration
    from rclpy.qos import DurabilityPolicy, LivelinessPolicy, ReliabilityPolicy
    from rclpy.qos import QoSProfile as RclpyProfile

    return RclpyProfile(
        depth=10,
        reliability=ReliabilityPolicy[policies['reliability']],
        durability=DurabilityPolicy[policies['durability']],
        liveliness=LivelinessPolicy[policies['liveliness']],
        deadline=Duration(nanoseconds=policies.get('deadline_ns', 0)),
        liveliness_lease_duration=Duration(
            nanoseconds=policies.get('liveliness_lease_duration_ns', 0)))


def _verdict_of_rclpy(pub: Any, sub: Any) -> str:
    from rclpy.qos import qos_check_compatible

    return qos_check_compatible(pub, sub)[0].name.lower()


def _compare(profiles: list[dict[str, Any]], pairs: Any) -> tuple[int, list[str]]:
    rclpy_profiles = [_rclpy_profile(p) for p in profiles]
    count, wrong = 0, []
    for i, j in pairs:
        count += 1
        expected = _verdict_of_rclpy(rclpy_profiles[i], rclpy_profiles[j])
        verdict, reason = check_qos_compatible(profiles[i], profiles[j])
        if verdict != expected:
            wrong.append(f'{profiles[i]} -> {profiles[j]}: rclpy {expected}, we {verdict} ({reason})')
    return count, wrong


def test_every_policy_value_on_both_sides() -> None:
    enums = [dict(zip(ENUM_POLICIES, values, strict=True))
             for values in itertools.product(*(ENUM_VALUES[p] for p in ENUM_POLICIES))]
    profiles, pairs = [], []
    for (pub_deadline, pub_lease), (sub_deadline, sub_lease) in DURATION_PAIRS:
        base = len(profiles)
        for e in enums:
            profiles.append({**e, 'deadline_ns': pub_deadline, 'liveliness_lease_duration_ns': pub_lease})
        for e in enums:
            profiles.append({**e, 'deadline_ns': sub_deadline, 'liveliness_lease_duration_ns': sub_lease})
        n = len(enums)
        pairs += [(base + i, base + n + j) for i in range(n) for j in range(n)]
    count, wrong = _compare(profiles, pairs)
    assert count == len(DURATION_PAIRS) * len(enums) ** 2 == 3 * 125 ** 2  # 46875 pairs
    assert not wrong, f'{len(wrong)} of {count} differ, e.g.\n' + '\n'.join(wrong[:10])


@pytest.mark.parametrize('enums', [
    {'reliability': 'RELIABLE', 'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'},
    {'reliability': 'SYSTEM_DEFAULT', 'durability': 'SYSTEM_DEFAULT', 'liveliness': 'SYSTEM_DEFAULT'},
    {'reliability': 'BEST_AVAILABLE', 'durability': 'BEST_AVAILABLE', 'liveliness': 'BEST_AVAILABLE'},
], ids=['known', 'system-default', 'best-available'])
def test_every_deadline_and_lease_on_both_sides(enums: dict[str, str]) -> None:
    profiles = [{**enums, 'deadline_ns': d, 'liveliness_lease_duration_ns': lease}
                for d, lease in itertools.product(DURATIONS, DURATIONS)]
    pairs = itertools.product(range(len(profiles)), repeat=2)
    count, wrong = _compare(profiles, pairs)
    assert count == len(DURATIONS) ** 4  # 4096 pairs
    assert not wrong, f'{len(wrong)} of {count} differ, e.g.\n' + '\n'.join(wrong[:10])


def test_the_oracle_gives_every_verdict() -> None:
    """The cross products above are not trivially agreeing: rclpy says each verdict."""
    ok = {'reliability': 'RELIABLE', 'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}
    cases = {'ok': (ok, ok),
             'warning': ({**ok, 'reliability': 'SYSTEM_DEFAULT'}, ok),
             'error': ({**ok, 'reliability': 'BEST_EFFORT'}, ok)}
    for verdict, (pub, sub) in cases.items():
        assert _verdict_of_rclpy(_rclpy_profile(pub), _rclpy_profile(sub)) == verdict
        assert check_qos_compatible(pub, sub)[0] == verdict
    assert VERDICTS == ('ok', 'warning', 'error')


# -- the toolkit's own forms and the reasons -------------------------------------------------


def test_takes_the_model_and_nodl_dicts_alike() -> None:
    pub = QoSProfile(history='KEEP_LAST', depth=5, reliability='BEST_EFFORT', durability='VOLATILE',
                     liveliness='AUTOMATIC')
    sub = {'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'RELIABLE', 'durability': 'VOLATILE',
           'liveliness': 'AUTOMATIC'}
    verdict, reason = check_qos_compatible(pub, sub)
    assert verdict == 'error'
    assert reason.startswith('reliability: ') and 'best effort' in reason and 'reliable' in reason
    assert check_qos_compatible(pub.to_dict(), QoSProfile.from_dict(sub)) == (verdict, reason)


def test_ok_has_no_reason_and_the_result_is_a_named_pair() -> None:
    result = check_qos_compatible({'reliability': 'RELIABLE', 'durability': 'VOLATILE',
                                   'liveliness': 'AUTOMATIC'},
                                  {'reliability': 'BEST_EFFORT', 'durability': 'VOLATILE',
                                   'liveliness': 'AUTOMATIC'})
    assert result == ('ok', '') and result.verdict == 'ok' and result.reason == ''


def test_every_error_is_named_in_rmw_order() -> None:
    pub = {'reliability': 'BEST_EFFORT', 'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC',
           'deadline_ns': 0, 'liveliness_lease_duration_ns': 10}
    sub = {'reliability': 'RELIABLE', 'durability': 'TRANSIENT_LOCAL',
           'liveliness': 'MANUAL_BY_TOPIC', 'deadline_ns': 5, 'liveliness_lease_duration_ns': 3}
    verdict, reason = check_qos_compatible(pub, sub)
    assert verdict == 'error'
    assert [part.split(':')[0] for part in reason.split('; ')] == [
        'reliability', 'durability', 'deadline', 'liveliness', 'liveliness lease duration']
    assert 'shorter than the 10 ns' in reason and 'offers none' in reason


def test_warnings_only_without_errors() -> None:
    pub = {'reliability': 'SYSTEM_DEFAULT', 'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}
    sub = {'reliability': 'RELIABLE', 'durability': 'TRANSIENT_LOCAL', 'liveliness': 'AUTOMATIC'}
    assert check_qos_compatible(pub, sub)[0] == 'error'
    verdict, reason = check_qos_compatible(pub, {**sub, 'durability': 'VOLATILE'})
    assert verdict == 'warning'
    assert reason.startswith('reliability: ') and 'SYSTEM_DEFAULT' in reason


def test_absent_policies_are_system_default_and_absent_durations_none() -> None:
    assert check_qos_compatible({}, None)[0] == 'warning'
    assert check_qos_compatible(None, {'deadline_ns': 0})[0] == 'warning'
    known = {'reliability': 'RELIABLE', 'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}
    assert check_qos_compatible(known, {**known, 'deadline_ns': 1})[0] == 'error'


@pytest.mark.parametrize('qos, message', [
    ({'reliability': 'SOMETIMES'}, "invalid reliability 'SOMETIMES'; expected one of"),
    ({'deadline_ns': -1}, 'invalid deadline_ns -1'),
    ({'deadline_ns': 1.5}, 'invalid deadline_ns 1.5'),
    ({'deadline': 5}, "unknown policy 'deadline'; expected some of"),
])
def test_bad_profiles_are_refused_with_what_was_expected(qos: dict[str, Any], message: str) -> None:
    with pytest.raises(ValueError, match=message.replace('(', r'\(')):
        check_qos_compatible(qos, {})


def test_other_types_are_refused() -> None:
    with pytest.raises(TypeError, match='publisher QoS must be a QoSProfile or a mapping'):
        check_qos_compatible('RELIABLE', {})  # type: ignore[arg-type]
