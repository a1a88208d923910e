"""The palette: every node definition the toolkit can find, with its ports.

The registry lists the definitions (the definitions folders in force first, then the
ament index: :func:`nodl.registry.registrations.list_registrations`); each is resolved as
``nodl show PACKAGE EXECUTABLE`` resolves it (:func:`nodl.targets.resolve.resolve_target`),
so that the palette can show its ports and be searched by interface type.  What the
client library gives every node (``/rosout``, the parameter services) is left out.
"""

from __future__ import annotations

from typing import Any

from nodl.composition.entities import Provider
from nodl.diagnostics import Severity
from nodl.registry.node_info import read_node_info
from nodl.registry.registrations import list_registrations, one_run
from nodl.targets.resolve import resolve_target

__all__ = ['PORT_KINDS', 'build_palette', 'matches', 'port_of']

#: The port kinds, in the order the page lists them (entity kind values).
PORT_KINDS = ('publisher', 'subscription', 'service_server', 'service_client', 'action_server',
              'action_client')


def port_of(entity: Any) -> dict[str, Any]:
    """A definition's endpoint as the page shows it: kind, declared name, type."""
    return {'kind': entity.kind.value, 'name': entity.name, 'type': entity.type_name}


def build_palette() -> list[dict[str, Any]]:
    """The palette's entries (the definitions in force, then the index's), sorted by package
    and executable: ``{package, executable, node_name, origin, file, ports, parameters,
    description, problems}``.  A definition that does not resolve is listed with its first
    error in ``problems`` and no ports."""
    out: list[dict[str, Any]] = []
    with one_run():
        for registration in list_registrations(kind='node'):
            try:
                target = resolve_target([registration.package, registration.name])
            except (OSError, ValueError) as exc:
                out.append(_entry(registration, None, [str(exc)]))
                continue
            problems = [d.message for d in target.diagnostics if d.severity is Severity.ERROR]
            node = target.node
            ports: list[dict[str, Any]] = []
            parameters: list[str] = []
            description = None
            if node is not None:
                for entity in node.entities:
                    if entity.provider is Provider.CLIENT_LIBRARY:
                        continue
                    if entity.is_parameter:
                        parameters.append(entity.name)
                    else:
                        ports.append(port_of(entity))
                description = getattr(node.node, 'description', None)
            info = read_node_info(registration.package, registration.name)
            entry = _entry(registration, info.node_name if info else None, problems[:1])
            entry.update(ports=ports, parameters=parameters, description=description)
            out.append(entry)
    return out


def _entry(registration: Any, node_name: str | None, problems: list[str]) -> dict[str, Any]:
    return {'package': registration.package, 'executable': registration.name,
            'node_name': node_name or registration.name, 'origin': registration.origin,
            'file': registration.file, 'ports': [], 'parameters': [], 'description': None,
            'problems': problems}


def matches(entry: dict[str, Any], query: str) -> bool:
    """True if every word of ``query`` is in the entry's package, executable or one of its
    ports' types (case-insensitive): what the page's search box does, for tests."""
    words = query.lower().split()
    haystack = ' '.join([entry['package'], entry['executable']]
                        + [p['type'] for p in entry['ports']]).lower()
    return all(word in haystack for word in words)
