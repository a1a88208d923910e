"""``show``: a node's whole interface, resolved, as an interface definition.

The entry points are :func:`show_file` and :func:`show_registered`; both
return the resolved node (:class:`~nodl.system.ResolvedNode`) and its
merged interface (or diagnostics), and :func:`render` prints it as YAML or
JSON, optionally with each entity's layer, stating the client library whose
base was used.
"""

from __future__ import annotations

import json
import os
from typing import Any

from nodl.composition.client_library import ClientLibraryChoice
from nodl.diagnostics import Diagnostic, Severity
from nodl.loading import check_source
from nodl.model import ENDPOINT_SECTIONS, Interface
from nodl.validation.kinds import Kind

__all__ = ['Shown', 'show_file', 'show_registered', 'show_reference', 'render']

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from nodl.composition.resolved import ResolvedNode
    from nodl.registry.overlay import Definitions
    from nodl.targets.resolve import Provenance


class Shown:
    """What ``show`` found: the interface (None on errors) and the diagnostics."""

    def __init__(self, interface: Interface | None, diagnostics: list[Diagnostic],
                 source: str, resolved: ResolvedNode | None = None,
                 provenance: Provenance | None = None) -> None:
        self.interface = interface
        self.diagnostics = diagnostics
        #: The file the definition was read from.
        self.source = source
        #: The resolved node (None for an interface definition, or on errors).
        self.resolved = resolved
        #: Where the definition came from (index, a definitions folder, a file).
        self.provenance = provenance

    @property
    def ok(self) -> bool:
        """True if there is an interface to show."""
        return self.interface is not None

    @property
    def client_library(self) -> ClientLibraryChoice | None:
        """The client library whose base was used, and why (None when there is no base)."""
        if self.resolved is None or self.resolved.base is None:
            return None
        return ClientLibraryChoice(self.resolved.client_library,
                                   self.resolved.client_library_reason)


def _stamp_all(iface: Interface, label: str) -> Interface:
    for param in (iface.parameters or {}).values():
        param.origin = param.origin or label
    for section in ENDPOINT_SECTIONS:
        for entity in getattr(iface, section) or ():
            entity.origin = entity.origin or label
    return iface


def _from_resolved(resolved: ResolvedNode | None, diagnostics: list[Diagnostic],
                   source: str) -> Shown:
    return Shown(resolved.interface if resolved is not None else None, diagnostics, source, resolved)


def show_file(path: str, client_library: str | None = None) -> Shown:
    """The resolved interface of the definition in ``path`` (a node is composed with the
    base of ``client_library``, rclpy by default; ValueError for an unknown library;
    OSError if ``path`` cannot be read)."""
    from pathlib import Path

    from nodl.composition.resolved import resolve_report

    report = check_source(Path(path), file=path)
    if report.has_errors():
        return Shown(None, report.diagnostics, path)
    if report.kind is Kind.NODE:
        resolved, diagnostics = resolve_report(report, client_library=client_library)
        return _from_resolved(resolved, diagnostics, path)
    if report.kind is Kind.INTERFACE:
        return Shown(_stamp_all(report.model(), os.path.basename(path)),  # type: ignore[arg-type]
                     report.diagnostics, path)
    return Shown(None, [Diagnostic(Severity.ERROR, 'a parameter definition has no interface to '
                                   'show; show a node or interface definition', (), path, 1, 1,
                                   code='NODL305')], path)


def show_registered(package: str, executable: str, client_library: str | None = None,
                    prefixes: list[str] | None = None,
                    definitions: Definitions | None = None) -> Shown:
    """The resolved interface of the node definition of ``package``'s ``executable`` (the
    client library defaults to the one of the package's build type), looked up with its
    mixins in the definitions folders ``definitions`` (and those in force), then in
    ``prefixes`` (default: ``AMENT_PREFIX_PATH``); :attr:`Shown.provenance` says which."""
    from nodl.targets.resolve import resolve_target

    found = resolve_target([package, executable], client_library=client_library,
                           prefixes=prefixes, definitions=definitions)
    shown = _from_resolved(found.node, found.diagnostics, found.source)
    shown.provenance = found.provenance
    return shown


def show_reference(reference: str, prefixes: list[str] | None = None,
                   definitions: Definitions | None = None) -> Shown:
    """The interface definition ``nodl://<package>/<name>``, as ``show`` prints it (looked up
    in the definitions folders ``definitions`` and those in force, then in ``prefixes``,
    default: ``AMENT_PREFIX_PATH``)."""
    from nodl.targets.resolve import resolve_reference

    text, file, problems = resolve_reference(reference, prefixes=prefixes, definitions=definitions)
    if text is None:
        return Shown(None, problems, reference)
    report = check_source(text, kind=Kind.INTERFACE, file=file)
    if report.has_errors():
        return Shown(None, report.diagnostics, file)
    return Shown(_stamp_all(report.model(), reference),  # type: ignore[arg-type]
                 report.diagnostics, file)


def _entity_blocks(iface: Interface) -> list[tuple[str, list[tuple[str | None, Any]]]]:
    blocks: list[tuple[str, list[tuple[str | None, Any]]]] = []
    if iface.parameters:
        blocks.append(('parameters', [(p.origin, {name: p.to_dict()})
                                      for name, p in iface.parameters.items()]))
    for section in ENDPOINT_SECTIONS:
        entries = getattr(iface, section)
        if entries:
            blocks.append((section, [(e.origin, [e.to_dict()]) for e in entries]))
    return blocks


def _yaml(data: Any) -> str:
    from nodl.text_safety import dump_yaml

    return dump_yaml(data)


def render(iface: Interface, format: str = 'yaml', layers: bool = False,
           client_library: ClientLibraryChoice | None = None) -> str:
    """The interface as YAML or JSON; with ``layers``, each entity's layer too.

    In YAML the layer is a comment above the entity, so the output stays a
    valid interface definition; so is the ``client_library`` line (the base's
    client library and why it was chosen).  In JSON (which has no comments),
    ``layers`` makes the output ``{"interface": ..., "layers": [...],
    "client_library": {"name": ..., "reason": ...}}``; plain JSON is the
    interface alone.
    """
    from nodl.loading import dump_nodl

    if format == 'json':
        if not layers:
            return dump_nodl(iface, 'json')
        origins = [{'section': section, 'name': next(iter(item)) if isinstance(item, dict)
                    else item[0]['name'], 'layer': origin}
                   for section, items in _entity_blocks(iface) for origin, item in items]
        out: dict[str, Any] = {'interface': iface.to_dict(), 'layers': origins}
        if client_library is not None:
            out['client_library'] = client_library._asdict()
        from nodl.text_safety import json_escapes

        return json_escapes(json.dumps(out, indent=2, ensure_ascii=False)) + '\n'
    if format != 'yaml':
        raise ValueError(f"unsupported format {format!r}; expected 'yaml' or 'json'")
    # One line, whatever the reason says (it may name a package): a comment cannot break out.
    from nodl.text_safety import one_line

    stated = f'# client library: {one_line(client_library)}\n' if client_library is not None else ''
    if not layers:
        return stated + dump_nodl(iface, 'yaml')
    head: dict[str, Any] = {'nodl_version': iface.nodl_version}
    if iface.description is not None:
        head['description'] = iface.description
    lines = ([stated.rstrip('\n')] if stated else []) + [_yaml(head).rstrip('\n')]
    for section, items in _entity_blocks(iface):
        lines.append(f'{section}:')
        for origin, item in items:
            if origin is not None:
                lines.append(f'  # layer: {one_line(origin)}')
            text = _yaml(item).rstrip('\n')
            lines.extend('  ' + line for line in text.splitlines())
    return '\n'.join(lines) + '\n'
