"""``show``: a node's whole interface, resolved, as an interface definition.

The entry points are :func:`show_file` and :func:`show_registered`; both
return the merged interface (or diagnostics), and :func:`render` prints it
as YAML or JSON, optionally with each entity's layer.
"""

from __future__ import annotations

import json
import os
from typing import Any

from nodl_schema.composition import compose_report
from nodl_schema.diagnostics import Diagnostic, Severity
from nodl_schema.loading import check_source
from nodl_schema.model import ENDPOINT_SECTIONS, Interface
from nodl_schema.validation.kinds import Kind

__all__ = ['Shown', 'show_file', 'show_registered', 'render']


class Shown:
    """What ``show`` found: the interface (None on errors) and the diagnostics."""

    def __init__(self, interface: Interface | None, diagnostics: list[Diagnostic],
                 source: str) -> None:
        self.interface = interface
        self.diagnostics = diagnostics
        #: The file the definition was read from.
        self.source = source

    @property
    def ok(self) -> bool:
        """True if there is an interface to show."""
        return self.interface is not None


def _stamp_all(iface: Interface, label: str) -> Interface:
    for param in (iface.parameters or {}).values():
        param.origin = param.origin or label
    for section in ENDPOINT_SECTIONS:
        for entity in getattr(iface, section) or ():
            entity.origin = entity.origin or label
    return iface


def show_file(path: str) -> Shown:
    """The resolved interface of the definition in ``path`` (a node is composed)."""
    from pathlib import Path

    report = check_source(Path(path), file=path)
    if report.has_errors():
        return Shown(None, report.diagnostics, path)
    if report.kind is Kind.NODE:
        composed, diagnostics = compose_report(report)
        return Shown(composed.interface if composed else None, diagnostics, path)
    if report.kind is Kind.INTERFACE:
        return Shown(_stamp_all(report.model(), os.path.basename(path)),  # type: ignore[arg-type]
                     report.diagnostics, path)
    return Shown(None, [Diagnostic(Severity.ERROR, 'a parameter definition has no interface to '
                                   'show; show a node or interface definition', (), path, 1, 1,
                                   code='NODL305')], path)


def show_registered(package: str, executable: str) -> Shown:
    """The resolved interface of the node definition registered for ``package``'s ``executable``."""
    from nodl_schema.index.registry import compose_registered

    composed, diagnostics, source = compose_registered(package, executable)
    return Shown(composed.interface if composed is not None else None, diagnostics, source)


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
    import yaml

    dumper = getattr(yaml, 'CSafeDumper', yaml.SafeDumper)
    return yaml.dump(data, Dumper=dumper, sort_keys=False, default_flow_style=False,
                     allow_unicode=True, width=100)


def render(iface: Interface, format: str = 'yaml', layers: bool = False) -> str:
    """The interface as YAML or JSON; with ``layers``, each entity's layer too.

    In YAML the layer is a comment above the entity, so the output stays a
    valid interface definition.  In JSON (which has no comments) the output
    becomes ``{"interface": ..., "layers": [...]}``.
    """
    from nodl_schema.loading import dump_nodl

    if format == 'json':
        if not layers:
            return dump_nodl(iface, 'json')
        origins = [{'section': section, 'name': next(iter(item)) if isinstance(item, dict)
                    else item[0]['name'], 'layer': origin}
                   for section, items in _entity_blocks(iface) for origin, item in items]
        return json.dumps({'interface': iface.to_dict(), 'layers': origins}, indent=2,
                          ensure_ascii=False) + '\n'
    if format != 'yaml':
        raise ValueError(f"unsupported format {format!r}; expected 'yaml' or 'json'")
    if not layers:
        return dump_nodl(iface, 'yaml')
    head: dict[str, Any] = {'nodl_version': iface.nodl_version}
    if iface.description is not None:
        head['description'] = iface.description
    lines = [_yaml(head).rstrip('\n')]
    for section, items in _entity_blocks(iface):
        lines.append(f'{section}:')
        for origin, item in items:
            if origin is not None:
                lines.append(f'  # layer: {origin}')
            text = _yaml(item).rstrip('\n')
            lines.extend('  ' + line for line in text.splitlines())
    return '\n'.join(lines) + '\n'
