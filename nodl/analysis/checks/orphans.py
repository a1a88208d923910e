"""Orphans: ``orphan-subscription``, ``orphan-service-client``, ``orphan-action-client``
(nothing in the system serves them) and ``orphan-publisher`` (nobody subscribes)."""

from __future__ import annotations

from typing import Iterator

from nodl.analysis.checks import CheckExtension
from nodl.analysis.context import AnalysisContext
from nodl.analysis.findings import Finding, make_finding
from nodl.system.entities import EntityKind, Provider

__all__ = ['OrphanCheck']

#: The kind of an endpoint that has no peer -> (finding kind, what is missing).
_ORPHANS = {
    EntityKind.SUBSCRIPTION: ('orphan-subscription', 'no node publishes it'),
    EntityKind.SERVICE_CLIENT: ('orphan-service-client', 'no node serves it'),
    EntityKind.ACTION_CLIENT: ('orphan-action-client', 'no node serves it'),
    EntityKind.PUBLISHER: ('orphan-publisher', 'no node subscribes to it'),
}


class OrphanCheck(CheckExtension):
    """Endpoints without a peer in the system.

    Nodes without a definition have unknown endpoints: names they are remapped
    to are taken as theirs (no finding), and every other orphan finding says
    which nodes are unknown.
    """

    kinds = tuple(kind for kind, _ in _ORPHANS.values())

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per node endpoint (not the client library's) without a peer."""
        unknown = context.undefined
        maybe: set[str] = set()
        for node in unknown:
            if node.names is None:
                continue
            for rule in node.names.rules:
                if rule.kind not in ('node', 'namespace') and rule.applies_to(node.names.name):
                    try:
                        maybe.add(node.names.expand(rule.replacement))
                    except ValueError:
                        pass
        caveat = ''
        if unknown:
            names = ', '.join(n.fqn for n in unknown[:3]) + (', ...' if len(unknown) > 3 else '')
            caveat = f' (unless {names}, launched without a definition, does)'
        # (a service or action one server offers and no client uses is no orphan: those, most
        # connections of a system, are not even made)
        for connection in context.system.connections(lone_servers=False):
            if connection.connected or connection.name in maybe:
                continue
            if not connection.using and connection.communication != 'topic':
                continue  # servers without clients are no problem
            for bound in connection.endpoints:
                if bound.entity.provider is Provider.CLIENT_LIBRARY:
                    continue
                kind, missing = _ORPHANS.get(bound.entity.kind, (None, ''))
                if kind is None:
                    continue  # a server without clients is no problem
                location = bound.entity.location
                yield make_finding(
                    kind, f'{bound.instance.fqn}: {bound.entity.kind.word} '
                    f'{connection.name} ({bound.entity.type_name}): {missing}{caveat}',
                    context.node_of(bound.instance).location, [bound.instance.fqn],
                    endpoint=connection.name,
                    related=[(location.file, location.line, location.column,
                              f'declared as {bound.entity.name!r}')])
