"""An extracted node as a draft NoDL definition: YAML text with a comment per entity.

Each entity is preceded by a comment giving the place in the source that creates it
(``# talker.py:21:25``).  An entity with a gap (a name, type or QoS the source computes at run
time) is written commented out, under a ``# GAP`` marker that says what is missing and where:
the draft stays a valid definition, and nothing in it is made up.  The text is validated by the
toolkit's own validator before it is returned.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.extract.model import PARAMETERS, ExtractedEntity, ExtractedNode, Gap
from nodl.location import Location

if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import Any

__all__ = ['GAP_MARKER', 'check_entities', 'entity_data', 'draft_data', 'draft_text', 'show_path']

#: The first word of the comment above an entity left out because of a gap.
GAP_MARKER = 'GAP'
#: The gap code of an extracted value the validator refuses (an invalid topic or parameter name...).
_INVALID = 'NODL914'


def show_path(path: str, relative_to: str | None) -> str:
    """``path`` as written in comments: relative to ``relative_to`` when it is below it."""
    if relative_to is None:
        return path
    try:
        rel = os.path.relpath(path, relative_to)
    except ValueError:  # another drive
        return path
    return path if rel.startswith('..') else rel


def entity_data(entity: ExtractedEntity) -> Any:
    """The NoDL mapping of one entity as far as it is known (a parameter's mapping without its
    name; an endpoint's with it).  Unknown fields are left out."""
    if entity.is_parameter:
        param: dict[str, Any] = {'type': entity.type} if entity.type is not None else {}
        if entity.has_default and entity.default_value is not None:
            param['default_value'] = entity.default_value
        if entity.description:
            param['description'] = entity.description
        if entity.read_only:
            param['read_only'] = True
        if entity.validation:
            param['validation'] = dict(entity.validation)
        return param
    out: dict[str, Any] = {}
    if entity.name is not None:
        out['name'] = entity.name
    if entity.type is not None:
        out['type'] = entity.type
    if entity.description:
        out['description'] = entity.description
    if entity.qos is not None:
        out['qos'] = entity.qos.to_dict()
    return out


def _sections(node: ExtractedNode) -> dict[str, list[ExtractedEntity]]:
    """Complete entities by section, the first of each name only (rclpy refuses a parameter
    declared twice; a section lists a name once)."""
    out: dict[str, list[ExtractedEntity]] = {}
    seen: set[tuple[str, str | None]] = set()
    for entity in node.entities:
        if not entity.complete or entity.key() in seen:
            continue
        seen.add(entity.key())
        out.setdefault(entity.section, []).append(entity)
    return out


def draft_data(node: ExtractedNode) -> dict[str, Any]:
    """The node definition the complete entities make (what the draft holds, uncommented)."""
    main: dict[str, Any] = {'nodl_version': 2}
    for section, entities in _order(_sections(node)):
        if section == PARAMETERS:
            main[section] = {e.name: entity_data(e) for e in entities}
        else:
            main[section] = [entity_data(e) for e in entities]
    data: dict[str, Any] = {'nodl_version': 2}
    if node.base != 'node':
        data['base'] = node.base
    data['main'] = main
    return data


def _order(sections: dict[str, list[ExtractedEntity]]) -> list[tuple[str, list[ExtractedEntity]]]:
    from nodl.extract.model import ENTITY_SECTIONS

    return [(key, sections[key]) for key in ENTITY_SECTIONS if key in sections]


def check_entities(node: ExtractedNode) -> None:
    """Give every complete entity the validator refuses (an invalid name, a default that does not
    fit its type, a bound of the wrong type) a gap with the validator's reason, so the draft
    comments it out instead of writing an invalid definition."""
    from nodl.validation import Kind, validate_data

    for entity in node.entities:
        if not entity.complete:
            continue
        if entity.is_parameter:
            main: dict[str, Any] = {'nodl_version': 2, PARAMETERS: {entity.name: entity_data(entity)}}
        else:
            main = {'nodl_version': 2, entity.section: [entity_data(entity)]}
        errors = [d for d in validate_data({'nodl_version': 2, 'main': main}, Kind.NODE)
                  if d.severity is Severity.ERROR]
        if errors:
            reason = errors[0].message
            entity.gaps.append(Gap('entity', f'the extracted {_word(entity)} is not valid NoDL ({reason})',
                                   entity.location, _INVALID))


def _word(entity: ExtractedEntity) -> str:
    if entity.is_parameter:
        return 'parameter'
    from nodl.vocabulary import SECTION_BY_KEY

    return str(SECTION_BY_KEY[entity.section].word)


def _comment(text: str, indent: str) -> str:
    from nodl.text_safety import one_line

    return f'{indent}# {one_line(text)}'


def _where(location: Location, relative_to: str | None) -> str:
    shown = Location(show_path(location.file, relative_to), location.line, location.column)
    return str(shown)


def _yaml_block(data: Any, indent: str) -> list[str]:
    from nodl.text_safety import dump_yaml

    return [f'{indent}{line}' for line in dump_yaml(data).rstrip('\n').split('\n')]


def _entity_lines(entity: ExtractedEntity, relative_to: str | None, duplicates: list[ExtractedEntity]) -> list[str]:
    where = _where(entity.location, relative_to)
    lines: list[str] = []
    if entity.is_parameter:
        indent = '    '
        body = _yaml_block({entity.name if entity.name is not None else '?': entity_data(entity)}, indent)
    else:
        indent = '    '
        block = _yaml_block([entity_data(entity) or {'name': None}], '')
        body = [f'{indent}{line}' if line.startswith('-') else f'{indent}{line}' for line in block]
    helper = f' (by {entity.helper})' if entity.helper else ''
    if entity.complete:
        lines.append(_comment(f'{where}{helper}', indent))
        for other in duplicates:
            lines.append(_comment(f'also at {_where(other.location, relative_to)}', indent))
        lines += body
        return lines
    for gap in entity.gaps:
        lines.append(_comment(f'{GAP_MARKER} {_where(gap.location, relative_to)}: {gap.reason}'
                              f'{helper} [{gap.code}]', indent))
    lines.append(_comment('fill in what is missing, then uncomment:', indent))
    lines += [f'{indent}# {line[len(indent):]}' for line in body]
    return lines


def draft_text(node: ExtractedNode, *, relative_to: str | None = None,
               sources: Iterable[str] | None = None) -> str:
    """The draft definition of ``node`` as YAML text, with its provenance in the header, the
    source location of each entity and the gaps as ``# GAP`` comments.

    File names in comments are shown relative to ``relative_to`` (when given and below it).
    Raises :class:`~nodl.diagnostics.ValidationError` if the draft does not validate
    (call :func:`check_entities` first: then it always does).
    """
    shown = [show_path(s, relative_to) for s in (sources if sources is not None else node.sources)]
    what = node.name if node.executable is None else f'{node.package or "?"} {node.executable}'
    header = [_comment(f'Extracted from {", ".join(shown) or node.location.file} by nodl extract '
                       f'({what}, {node.language}).', ''),
              _comment('A draft: check every entity. An entity marked GAP is commented out until its '
                       'missing part is filled in.', ''),
              '# nodl: ignore=NODL216 (source code carries no descriptions: write them)']
    lines = header + ['nodl_version: 2']
    if node.base != 'node':
        lines.append(f'base: {node.base}')
    lines += ['main:', '  nodl_version: 2']
    first: dict[tuple[str, str | None], ExtractedEntity] = {}
    duplicates: dict[int, list[ExtractedEntity]] = {}
    for entity in node.entities:
        if entity.complete and entity.key() in first:
            duplicates.setdefault(id(first[entity.key()]), []).append(entity)
        elif entity.complete:
            first[entity.key()] = entity
    from nodl.extract.model import ENTITY_SECTIONS

    for section in ENTITY_SECTIONS:
        entities = [e for e in node.entities if e.section == section
                    and (not e.complete or first.get(e.key()) is e)]
        if not entities:
            continue
        live = any(e.complete for e in entities)
        lines.append(f'  {section}:' if live else f'  # {section}:')
        for entity in entities:
            lines += _entity_lines(entity, relative_to, duplicates.get(id(entity), []))
    text = '\n'.join(lines) + '\n'
    from nodl.loading import load_node

    load_node(text, file=f'<draft of {node.output_name}>')  # what is written always loads
    return text


def note(node: ExtractedNode, code: str, message: str, location: Location | None = None,
         severity: Severity = Severity.WARNING) -> Diagnostic:
    """Add a diagnostic about ``node`` as a whole to its notes, and return it."""
    where = location or node.location
    diagnostic = Diagnostic(severity, message, file=where.file, line=where.line,
                            column=where.column, code=code)
    node.notes.append(diagnostic)
    return diagnostic
