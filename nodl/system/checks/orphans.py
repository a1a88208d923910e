"""Orphans: ``orphan-subscription``, ``orphan-service-client``, ``orphan-action-client``
(nothing in the system serves them) and ``orphan-publisher`` (nobody subscribes)."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

from nodl.composition.entities import EntityKind, Provider
from nodl.system.checks import CheckExtension
from nodl.system.context import AnalysisContext
from nodl.system.findings import Finding, make_finding

__all__ = ['OrphanCheck']

#: The kind of an endpoint that has no peer -> (finding kind, what is missing).
_ORPHANS = {
    EntityKind.SUBSCRIPTION: ('orphan-subscription', 'no node publishes it'),
    EntityKind.SERVICE_CLIENT: ('orphan-service-client', 'no node serves it'),
    EntityKind.ACTION_CLIENT: ('orphan-action-client', 'no node serves it'),
    EntityKind.PUBLISHER: ('orphan-publisher', 'no node subscribes to it'),
}
#: The kind of an endpoint that has no peer -> the draft section whose unresolved entity could be
#: that peer.
_PEER_SECTION = {
    EntityKind.SUBSCRIPTION: 'publishers',
    EntityKind.SERVICE_CLIENT: 'service_servers',
    EntityKind.ACTION_CLIENT: 'action_servers',
    EntityKind.PUBLISHER: 'subscriptions',
}


class OrphanCheck(CheckExtension):
    """Endpoints without a peer in the system.

    Nodes without a definition have unknown endpoints: names they are remapped
    to are taken as theirs (no finding), and every other orphan finding says
    which nodes are unknown.  Nodes served by an extracted draft with gaps may
    be the missing side too: an orphan finding names those whose unresolved
    entities could be its peer (of the peer's kind, with its name or an unknown one).
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
                    with contextlib.suppress(ValueError):  # a rule rcl would refuse
                        maybe.add(node.names.expand(rule.replacement))
        caveat = ''
        if unknown:
            names = ', '.join(n.fqn for n in unknown[:3]) + (', ...' if len(unknown) > 3 else '')
            caveat = f'{names}, launched without a definition, does'
        drafts = _draft_peers(context)
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
                unless = [caveat] if caveat else []
                gapped = [fqn for fqn, (anywhere, named) in drafts.get(bound.entity.kind, {}).items()
                          if fqn != bound.instance.fqn and (anywhere or connection.name in named)]
                if gapped:
                    shown = ', '.join(gapped[:3]) + (', ...' if len(gapped) > 3 else '')
                    unless.append(f"{shown}'s unresolved entities, under # GAP in its extracted "
                                  'draft, do')
                why = f' (unless {" or unless ".join(unless)})' if unless else ''
                yield make_finding(
                    kind, f'{bound.instance.fqn}: {bound.entity.kind.word} '
                    f'{connection.name} ({bound.entity.type_name}): {missing}{why}',
                    context.node_of(bound.instance).location, [bound.instance.fqn],
                    endpoint=connection.name,
                    related=[(location.file, location.line, location.column,
                              f'declared as {bound.entity.name!r}')])


def _draft_peers(context: AnalysisContext) -> dict[EntityKind, dict[str, tuple[bool, set[str]]]]:
    """The kind of an orphan endpoint -> the nodes whose draft gaps could be its peer: fully
    qualified name -> (True if such a gap's name is unknown, the final names of those named)."""
    peers: dict[EntityKind, dict[str, tuple[bool, set[str]]]] = {}
    if not context.draft_gaps:
        return peers
    for node in context.analysed():
        gaps = context.gaps_of(node)
        for kind, section in _PEER_SECTION.items():
            anywhere = False
            named: set[str] = set()
            for gap in gaps:
                if gap.section != section:
                    continue
                if gap.name is None or node.names is None:
                    anywhere = True
                    continue
                try:
                    named.add(node.names.resolve(gap.name, service=section != 'publishers'
                                                 and section != 'subscriptions'))
                except ValueError:
                    anywhere = True  # a name rcl would refuse: where it ends up is unknown
            if anywhere or named:
                peers.setdefault(kind, {})[node.fqn] = (anywhere, named)
    return peers
