"""Checks on each topic, service and action: ``multiple-publishers``, ``type-mismatch``,
``qos-incompatible`` / ``qos-warning``."""

from __future__ import annotations

import operator
from collections.abc import Iterator
from typing import Any

from nodl.composition.entities import Provider
from nodl.composition.instance import InstanceEntity
from nodl.model.qos import QOS_POLICIES
from nodl.qos_compat import check_qos_compatible
from nodl.system.checks import CheckExtension
from nodl.system.context import AnalysisContext
from nodl.system.findings import Finding, make_finding

__all__ = ['MultiplePublishersCheck', 'QoSCheck', 'TypeMismatchCheck']


def _own(endpoints: tuple[InstanceEntity, ...]) -> list[InstanceEntity]:
    """The endpoints the nodes bring themselves (not the client library's)."""
    return [e for e in endpoints if e.entity.provider is not Provider.CLIENT_LIBRARY]


def _related(bound: InstanceEntity, what: str) -> tuple[str, int, int, str]:
    where = bound.entity.location
    return (where.file, where.line, where.column, what)


class MultiplePublishersCheck(CheckExtension):
    """More than one node publishes a topic (the client library's ``/rosout`` and
    ``/parameter_events`` excluded; topics on the configured allow list too)."""

    kinds = ('multiple-publishers',)

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per topic published by several nodes."""
        for connection in context.system.connections('topic'):
            if len(connection.offering) < 2:
                continue  # fewer than two publishers
            publishers = _own(connection.offering)
            nodes = list(dict.fromkeys(p.instance.fqn for p in publishers))
            if len(nodes) < 2 or context.settings.publishers_allowed(connection.name):
                continue
            second = next(p for p in publishers if p.instance.fqn == nodes[1])
            yield make_finding(
                'multiple-publishers',
                f'topic {connection.name} is published by {len(nodes)} nodes: {", ".join(nodes)} '
                '(if that is intended, add it to multiple_publishers_allow in nodl.toml)',
                context.node_of(second.instance).location, nodes, endpoint=connection.name,
                related=[_related(p, f'{p.instance.fqn} publishes it') for p in publishers])


_SIDE_WORDS = {'publisher': 'published', 'subscription': 'subscribed', 'service_server': 'served',
               'service_client': 'called', 'action_server': 'served', 'action_client': 'called'}


class TypeMismatchCheck(CheckExtension):
    """The endpoints of a topic (or the servers and clients of a service or action)
    disagree on its type: the middleware never connects them."""

    kinds = ('type-mismatch',)

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per connection whose endpoints use more than one type."""
        # (a service or action one server offers and no client uses has one type: those,
        # most connections of a system, are not even made)
        for connection in context.system.connections(lone_servers=False):
            offering, using = connection.offering, connection.using
            if len(offering) + len(using) < 2:
                continue  # one endpoint, one type
            endpoints = offering + using
            first_type = endpoints[0].entity.type_name
            for e in endpoints:
                if e.entity.type_name != first_type:
                    break
            else:
                continue
            by_type: dict[str, list[InstanceEntity]] = {}
            for e in endpoints:
                by_type.setdefault(e.entity.type_name, []).append(e)
            parts = []
            for type_name, group in by_type.items():
                who = ', '.join(f'{_SIDE_WORDS[e.entity.kind.value]} by {e.instance.fqn}'
                                for e in group)
                parts.append(f'{type_name} ({who})')
            odd = next(e for e in endpoints if e.entity.type_name != first_type)
            yield make_finding(
                'type-mismatch', f'{connection.communication} {connection.name} has '
                f'{len(by_type)} types: {"; ".join(parts)}',
                context.node_of(odd.instance).location,
                [e.instance.fqn for e in endpoints], endpoint=connection.name,
                related=[_related(e, f'{e.instance.fqn}: {e.entity.kind.word} of '
                                     f'{e.entity.type_name}') for e in endpoints])


#: Every policy of a profile, in a fixed order: two profiles with the same policies have the
#: same key (as their ``to_dict()`` items would, without making a dict per endpoint).
_QOS_POLICIES = operator.attrgetter(*QOS_POLICIES)


def _qos_key(qos: Any) -> tuple[Any, ...]:
    return _QOS_POLICIES(qos) if qos is not None else ()


#: Not yet asked (a verdict may be None).
_UNKNOWN = object()


def _any_flagged(verdict_of: Any, publishers: Any, own_subs: Any, own_pubs: Any,
                 library_subs: Any) -> bool:
    """True if a pair QoSCheck looks at has a verdict other than ``ok``, asked once per pair
    of distinct profiles (not per pair of endpoints: quadratic in the nodes on one topic)."""
    def profiles(endpoints: Any) -> list[Any]:
        return list({_qos_key(e.entity.qos): e.entity.qos for e in endpoints}.values())

    for pubs, subs in ((publishers, own_subs), (own_pubs, library_subs)):
        for pub_qos in profiles(pubs):
            for sub_qos in profiles(subs):
                verdict = verdict_of(pub_qos, sub_qos)
                if verdict is not None and verdict.verdict != 'ok':
                    return True
    return False


def _qos_finding(context: AnalysisContext, topic: str, pub: InstanceEntity, sub: InstanceEntity,
                 verdict: Any) -> Finding:
    kind = 'qos-incompatible' if verdict.verdict == 'error' else 'qos-warning'
    outcome = 'will not connect' if verdict.verdict == 'error' else 'may not connect'
    return make_finding(
        kind, f'topic {topic}: the publisher of {pub.instance.fqn} and '
        f'the subscription of {sub.instance.fqn} {outcome}: {verdict.reason}',
        context.node_of(sub.instance).location,
        [pub.instance.fqn, sub.instance.fqn], endpoint=topic,
        related=[_related(pub, f'the publisher of {pub.instance.fqn}'),
                 _related(sub, f'the subscription of {sub.instance.fqn}')])


class QoSCheck(CheckExtension):
    """A publisher and a subscription on one topic that the middleware would not connect
    (``qos-incompatible``), or would connect with a warning (``qos-warning``): exactly
    :func:`nodl.qos_compat.check_qos_compatible`."""

    kinds = ('qos-incompatible', 'qos-warning')

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per incompatible (or doubtful) publisher/subscription pair."""
        verdicts: dict[tuple[Any, Any], Any] = {}

        def verdict_of(pub_qos: Any, sub_qos: Any) -> Any:
            """check_qos_compatible's verdict, once per pair of profiles (None if it raises:
            a definition that passed validation has valid QoS)."""
            # (_qos_key of both, written out: once per pair of endpoints)
            key = (_QOS_POLICIES(pub_qos) if pub_qos is not None else (),
                   _QOS_POLICIES(sub_qos) if sub_qos is not None else ())
            verdict = verdicts.get(key, _UNKNOWN)
            if verdict is _UNKNOWN:
                try:
                    verdict = check_qos_compatible(pub_qos, sub_qos)
                except ValueError:
                    verdict = None
                verdicts[key] = verdict
            return verdict

        library = Provider.CLIENT_LIBRARY
        for connection in context.system.connections('topic'):
            publishers, subscriptions = connection.offering, connection.using
            if not publishers or not subscriptions:
                continue
            # client library to client library pairs (/parameter_events) are never checked:
            # pair every publisher with the nodes' own subscriptions, and the nodes' own
            # publishers with the client library's subscriptions (linear when none are own).
            # (Loops rather than comprehensions: most topics have one publisher and one
            # subscription, and there are as many topics as nodes.)
            own_subs: list[InstanceEntity] = []
            library_subs: list[InstanceEntity] = []
            for s in subscriptions:
                (library_subs if s.entity.provider is library else own_subs).append(s)
            own_pubs = _own(publishers) if library_subs else []
            if len(publishers) * len(own_subs) + len(own_pubs) * len(library_subs) > \
                    len(publishers) + len(subscriptions) and \
                    not _any_flagged(verdict_of, publishers, own_subs, own_pubs, library_subs):
                continue  # many pairs (a topic most nodes publish and subscribe), none flagged
            for pubs, subs in ((publishers, own_subs), (own_pubs, library_subs)):
                for pub in pubs:
                    for sub in subs:
                        verdict = verdict_of(pub.entity.qos, sub.entity.qos)
                        if verdict is not None and verdict.verdict != 'ok':
                            yield _qos_finding(context, connection.name, pub, sub, verdict)
