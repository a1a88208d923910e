"""Comparing what the source creates with an existing definition (``nodl extract --diff``).

The definition is composed (its mixins resolved) and its base's entities left out, as the
source creates only the node's own.  Each difference is a coded diagnostic (NODL920-926) placed
where a user fixes it: an entity the definition lacks at the source line that creates it, an
entity the source lacks at the definition's entry.  An entity the source leaves open (a gap)
is not compared (NODL926, info), so a gap is never reported as drift.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.extract.model import PARAMETERS, ExtractedEntity, ExtractedNode

if TYPE_CHECKING:
    from typing import Any

    from nodl.loading import CheckedSource
    from nodl.model import Interface

__all__ = ['diff_node', 'definition_entities']


def definition_entities(interface: Interface, base: Interface) -> dict[tuple[str, str], Any]:
    """``(section, name) -> entity`` of a composed interface, without its base's entities."""
    from nodl.model.interface import ENDPOINT_SECTIONS

    out: dict[tuple[str, str], Any] = {}
    inherited = set(base.parameters or {})
    for name, param in (interface.parameters or {}).items():
        if name not in inherited:
            out[(PARAMETERS, name)] = param
    for section in ENDPOINT_SECTIONS:
        from_base = {e.name for e in base.endpoints(section)}
        for endpoint in interface.endpoints(section):
            if endpoint.name not in from_base:
                out[(section, endpoint.name)] = endpoint
    return out


def _word(section: str) -> str:
    if section == PARAMETERS:
        return 'parameter'
    from nodl.vocabulary import SECTION_BY_KEY

    return str(SECTION_BY_KEY[section].word)


class _Differ:
    def __init__(self, node: ExtractedNode, report: CheckedSource, file: str) -> None:
        self.node = node
        self.report = report
        self.file = file
        self.out: list[Diagnostic] = []

    def at_source(self, entity: ExtractedEntity, code: str, message: str, severity: Severity = Severity.ERROR) -> None:
        where = entity.location
        self.out.append(Diagnostic(severity, message, file=where.file, line=where.line, column=where.column,
                                   code=code, related=[(self.file, 0, 0, 'the definition compared')]))

    def at_definition(self, key: tuple[str, str], code: str, message: str) -> None:
        path = self._path(key)
        diagnostic = Diagnostic(Severity.ERROR, message, path, file=self.file, code=code,
                                anchor='key' if key[0] == PARAMETERS else 'value')
        self.out.append(self.report.place(diagnostic) if path else diagnostic)

    def _path(self, key: tuple[str, str]) -> tuple[Any, ...]:
        data = self.report.data if isinstance(self.report.data, dict) else {}
        main = data.get('main') if isinstance(data.get('main'), dict) else {}
        assert isinstance(main, dict)
        section, name = key
        entries = main.get(section)
        if section == PARAMETERS and isinstance(entries, dict) and name in entries:
            return ('main', PARAMETERS, name)
        if isinstance(entries, list):
            for i, entry in enumerate(entries):
                if isinstance(entry, dict) and entry.get('name') == name:
                    return ('main', section, i, 'name')
        return ()


def diff_node(node: ExtractedNode, definition: str) -> list[Diagnostic]:
    """The differences between an extracted node and the definition in file ``definition``
    (raises :class:`~nodl.diagnostics.ValidationError` when it cannot be loaded)."""
    from nodl.composition import compose_report
    from nodl.composition.bases import base_layer
    from nodl.diagnostics import ValidationError
    from nodl.loading import check_source
    from nodl.validation.kinds import Kind

    report = check_source(_path(definition), kind=Kind.NODE, file=definition)
    composed, diagnostics = compose_report(report, client_library='rclpy' if node.language == 'python'
                                           else 'rclcpp')
    if composed is None:
        raise ValidationError(diagnostics)
    written = str(composed.node.base.value) if composed.node.base is not None else 'node'
    base = base_layer(written, composed.client_library).interface
    differ = _Differ(node, report, definition)
    if written != node.base:
        differ.at_definition(('base', ''), 'NODL925', f"the definition's base is {written}, the source's "
                             f'{node.base} (at {node.location})')
    declared = definition_entities(composed.interface, base)
    open_sections = {e.section for e in node.entities if e.name is None}
    seen: set[tuple[str, str]] = set()
    for entity in node.entities:
        if entity.name is None:
            continue
        key = (entity.section, entity.name)
        if key in seen:
            continue
        seen.add(key)
        other = declared.get(key)
        word = _word(entity.section)
        if other is None:
            differ.at_source(entity, 'NODL920', f"{word} '{entity.name}' is created here but the definition "
                             'does not declare it')
            continue
        if not entity.complete:
            missing = ', '.join(sorted({g.what for g in entity.gaps}))
            differ.at_source(entity, 'NODL926', f"{word} '{entity.name}': its {missing} is left open by the "
                             'source, so it is not compared', Severity.INFO)
            continue
        differ_values(differ, entity, other, word)
    for key in declared:
        if key in seen:
            continue
        if key[0] in open_sections:
            differ.at_definition(key, 'NODL926', f"{_word(key[0])} '{key[1]}' is not found in the source, "
                                 'which also creates one whose name it computes at run time: not compared')
            differ.out[-1] = differ.out[-1].replace(severity=Severity.INFO)
            continue
        differ.at_definition(key, 'NODL921', f"{_word(key[0])} '{key[1]}' is declared but the source does not "
                             'create it')
    return differ.out


def differ_values(differ: _Differ, entity: ExtractedEntity, other: Any, word: str) -> None:
    """Report the type, QoS and parameter differences of one entity found on both sides."""
    if entity.type != other.type:
        differ.at_source(entity, 'NODL922', f"{word} '{entity.name}' is a {entity.type} in the source, a "
                         f'{other.type} in the definition')
        return
    if entity.is_parameter:
        changes = []
        if entity.has_default and entity.default_value != other.default_value:
            changes.append(f'default {entity.default_value!r} in the source, {other.default_value!r} in the '
                           'definition')
        if entity.read_only != other.read_only:
            changes.append(f'read_only {str(entity.read_only).lower()} in the source, '
                           f'{str(other.read_only).lower()} in the definition')
        source_bounds = (entity.validation or {}).get('bounds<>')
        written_bounds = (other.validation or {}).get('bounds<>')
        if source_bounds is not None and source_bounds != written_bounds:
            changes.append(f'bounds {source_bounds} in the source, {written_bounds} in the definition')
        if changes:
            differ.at_source(entity, 'NODL924', f"parameter '{entity.name}': " + '; '.join(changes))
        return
    if entity.qos is not None and getattr(other, 'qos', None) is not None:
        mine, theirs = entity.qos.to_dict(), other.qos.to_dict()
        changed = [k for k in mine if k in theirs and mine[k] != theirs[k]]  # unset: not stated
        if changed:
            shown = ', '.join(f'{k} {mine[k]} in the source, {theirs[k]} in the definition'
                              for k in changed)
            differ.at_source(entity, 'NODL923', f"{word} '{entity.name}' QoS: {shown}")


def _path(definition: str) -> Any:
    from pathlib import Path

    return Path(definition)
