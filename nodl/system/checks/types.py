"""``type-definition-mismatch``: one type name, different installed definitions on one topic.

Each node's definition is read from a workspace (the ament prefix its file is
installed in, or a definitions folder).  A node built in an overlay sees the
overlay's interface packages first, then the underlays after it in
``AMENT_PREFIX_PATH``: the type it was built against is the definition found
from its own prefix on.  Two endpoints of a topic that share a type name but
whose definitions hash differently (RIHS01) never connect, though the names
agree.
"""

from __future__ import annotations

import os
from collections.abc import Iterator

from nodl.interface_types import interface_index
from nodl.interface_types.hashes import type_hash
from nodl.interface_types.tree import InterfaceFileError
from nodl.registry.registrations import search_path
from nodl.system.checks import CheckExtension
from nodl.system.context import AnalysisContext
from nodl.system.findings import Finding, make_finding

__all__ = ['TypeDefinitionCheck']


def _prefixes_of(file: str, prefixes: list[str]) -> list[str]:
    """The prefixes a definition's node sees: from the one its file is installed in on."""
    path = os.path.abspath(file)
    for number, prefix in enumerate(prefixes):
        if path.startswith(os.path.abspath(prefix).rstrip(os.sep) + os.sep):
            return prefixes[number:]
    return prefixes


class TypeDefinitionCheck(CheckExtension):
    """Endpoints of a topic use one type name with different installed definitions."""

    kinds = ('type-definition-mismatch',)

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per topic whose endpoints' definitions of its type hash differently."""
        prefixes = search_path(list(context.prefixes) if context.prefixes is not None else None)
        if len(prefixes) < 2:
            return  # every node sees the same interface packages: one definition per type name
        for connection in context.system.connections('topic', include_client_library=False):
            endpoints = connection.offering + connection.using
            if len(endpoints) < 2 or len({e.entity.type_name for e in endpoints}) != 1:
                continue  # one endpoint, or several type names (type-mismatch says so)
            views = [_prefixes_of(e.entity.location.file, prefixes) for e in endpoints]
            if all(view == views[0] for view in views):
                continue  # the same prefixes seen from every endpoint: the same definition
            by_hash: dict[str, list[tuple[object, str]]] = {}
            for endpoint, seen in zip(endpoints, views, strict=True):
                try:
                    found = type_hash(interface_index(prefixes=seen), endpoint.entity.type_name)
                except (LookupError, InterfaceFileError):
                    continue  # not installed or unreadable: validate --types reports it
                where = interface_index(prefixes=seen).prefix_of(
                    endpoint.entity.type_name.split('/')[0]) or '?'
                by_hash.setdefault(found, []).append((endpoint, where))
            if len(by_hash) < 2:
                continue
            parts = []
            related = []
            for group in by_hash.values():
                who = ', '.join(e.instance.fqn for e, _ in group)  # type: ignore[attr-defined]
                parts.append(f'{who} (from {group[0][1]})')
                for e, where in group:
                    location = e.entity.location  # type: ignore[attr-defined]
                    related.append((location.file, location.line, location.column,
                                    f'{e.instance.fqn}: its definition of '  # type: ignore[attr-defined]
                                    f'{e.entity.type_name} is the one in {where}'))  # type: ignore[attr-defined]
            first = next(iter(by_hash.values()))[0][0]
            yield make_finding(
                'type-definition-mismatch',
                f'topic {connection.name}: its endpoints all use '
                f'{endpoints[0].entity.type_name} but {len(by_hash)} different definitions of it '
                f'(the middleware will not connect them): {"; ".join(parts)}; build every node '
                'against the same version of the interface package',
                context.node_of(first.instance).location,  # type: ignore[attr-defined]
                [e.instance.fqn for e in endpoints], endpoint=connection.name, related=related)
