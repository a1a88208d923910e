"""The content of node and package pages, from the resolved node and the registrations.

A node page (:func:`node_page`) has

* a header: the executable, the base, the client library (and why), every
  layer (base, mixins, main) with the file it comes from and its provenance;
* the parameters: name, type as ROS, C++ (rclcpp) and Python (rclpy) name it
  (one table: :mod:`nodl.interface_types.mapping`), default, read-only,
  constraints in the validators' own words, description, the layer;
* a YAML parameter file to start from;
* one table per endpoint section, each name's type linking to its field
  table, QoS in words (:func:`qos_words`: a deadline reads as "expects at
  least N Hz");
* the appendix of field tables (:mod:`nodl.doc.types`) and the findings.

What the client library gives every node (``/rosout``, the parameter
services) is listed in one sentence, not in the tables.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from nodl.composition.entities import Provider
from nodl.diagnostics import Diagnostic
from nodl.doc.blocks import Code, Inline, Link, Literal, Note, Page, Table, label
from nodl.doc.types import type_appendix, type_label
from nodl.interface_types.mapping import PARAMETER_CPP, PARAMETER_PY
from nodl.plan.parameter_plan import ROS_TYPES
from nodl.text_safety import dump_yaml, one_line
from nodl.validation.validators import lookup

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from typing import Any

    from nodl.composition.entities import Entity, Location
    from nodl.composition.resolved import ResolvedNode
    from nodl.interface_types.resolve import InterfaceIndex
    from nodl.model.qos import QoSProfile

__all__ = ['PageSource', 'value_text', 'node_page', 'package_page', 'qos_words', 'parameter_block',
           'PARAMETER_COLUMNS', 'ENDPOINT_COLUMNS', 'SECTION_TITLES', 'findings_table']

#: The columns of the parameters table.
PARAMETER_COLUMNS = ('Name', 'ROS type', 'C++ type', 'Python type', 'Default', 'Read-only',
                     'Constraints', 'Description', 'Declared by')
#: The columns of an endpoint table.
ENDPOINT_COLUMNS = ('Name', 'Type', 'QoS', 'Description', 'Declared by')
#: Endpoint section -> its title.
SECTION_TITLES = {'publishers': 'Publishers', 'subscriptions': 'Subscriptions',
                  'service_servers': 'Service servers', 'service_clients': 'Service clients',
                  'action_servers': 'Action servers', 'action_clients': 'Action clients'}

_HISTORY = {'KEEP_LAST': 'keep last', 'KEEP_ALL': 'keep all', 'SYSTEM_DEFAULT': 'system default history'}
_RELIABILITY = {'RELIABLE': 'reliable', 'BEST_EFFORT': 'best effort',
                'SYSTEM_DEFAULT': 'system default reliability', 'BEST_AVAILABLE': 'best available reliability'}
_DURABILITY = {'TRANSIENT_LOCAL': 'transient local (late joiners get the last messages)',
               'VOLATILE': 'volatile', 'SYSTEM_DEFAULT': 'system default durability',
               'BEST_AVAILABLE': 'best available durability'}
_LIVELINESS = {'AUTOMATIC': 'liveliness asserted automatically',
               'MANUAL_BY_TOPIC': 'liveliness asserted by publishing',
               'SYSTEM_DEFAULT': 'system default liveliness', 'BEST_AVAILABLE': 'best available liveliness'}


def _duration(ns: int) -> str:
    if ns % 1_000_000_000 == 0:
        return f'{ns // 1_000_000_000} s'
    if ns % 1_000_000 == 0:
        return f'{ns // 1_000_000} ms'
    return f'{ns / 1e6:g} ms'


def qos_words(qos: QoSProfile | None) -> str:
    """A QoS profile in words: ``reliable, keep last 10, volatile, expects at least 10 Hz``
    (empty for none)."""
    if qos is None:
        return ''
    words: list[str] = []
    words.append(_RELIABILITY.get(qos.reliability, qos.reliability))
    history = _HISTORY.get(qos.history, qos.history)
    words.append(f'{history} {qos.depth}' if qos.history == 'KEEP_LAST' and qos.depth is not None
                 else history)
    if qos.durability:
        words.append(_DURABILITY.get(qos.durability, qos.durability))
    if qos.deadline_ns:
        words.append(f'expects at least {1e9 / qos.deadline_ns:.4g} Hz (deadline '
                     f'{_duration(qos.deadline_ns)})')
    if qos.lifespan_ns:
        words.append(f'messages expire after {_duration(qos.lifespan_ns)}')
    if qos.liveliness:
        lease = (f' (lease {_duration(qos.liveliness_lease_duration_ns)})'
                 if qos.liveliness_lease_duration_ns else '')
        words.append(_LIVELINESS.get(qos.liveliness, qos.liveliness) + lease)
    return ', '.join(words)


class PageSource:
    """What a node page says of where its definition comes from."""

    def __init__(self, package: str | None, executable: str | None, file: str,
                 provenance: str) -> None:
        self.package = package
        self.executable = executable
        #: The definition's file, as the page shows it.
        self.file = file
        #: ``index``, ``overlay DIR``, ``file``, with ``extracted``/``described``.
        self.provenance = provenance

    @property
    def title(self) -> str:
        """``package/executable``, or the file's stem."""
        if self.package and self.executable:
            return f'{self.package}/{self.executable}'
        name = os.path.basename(self.file)
        for ending in ('.nodl.yaml', '.nodl.yml', '.nodl.json', '.yaml', '.yml', '.json'):
            if name.endswith(ending):
                return name[:-len(ending)]
        return name

    @property
    def path(self) -> str:
        """The page's path under the output folder, without the extension."""
        if self.package and self.executable:
            return f'{self.package}/{self.executable}'
        return label(self.title)


def value_text(value: Any) -> str:
    """A value as a reader writes it: ``true``, ``0.5``, ``laser``, ``[-2.35, 2.35]``."""
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, (list, tuple)):
        return '[' + ', '.join(value_text(item) for item in value) + ']'
    if isinstance(value, str):
        return value if value.strip() == value and value else repr(value)
    if isinstance(value, bytes):
        return repr(value)
    return str(value)


def _parameter_row(entity: Entity) -> tuple[tuple[Inline, ...], ...]:
    definition = entity.definition
    spec = definition.type_spec
    base = spec.base if spec is not None else ''
    element = base
    constraints: list[str] = []
    if definition.additional_constraints:
        constraints.append(definition.additional_constraints)
    for key, raw in (definition.validation or {}).items():
        rule = lookup(key)
        constraints.append(rule.describe(raw) if rule is not None and rule.accepts(raw)
                           else f'must pass the custom validator {key}')
    if spec is not None and spec.size is not None:
        constraints.append(f'must hold at most {spec.size} '
                           f'{"characters" if spec.base == "string" else "elements"}')
    default = value_text(entity.default_value) if entity.default_value is not None else (
        '' if base == 'none' else 'required')
    return ((Literal(entity.name),),
            (Literal(ROS_TYPES.get(element, entity.type_name)),),
            (Literal(PARAMETER_CPP.get(element, '')),) if element in PARAMETER_CPP else ('any',),
            (Literal(PARAMETER_PY.get(element, '')),) if element in PARAMETER_PY else ('any',),
            (Literal(default),) if default and default != 'required' else (default,),
            ('yes' if entity.read_only else 'no',),
            ('; '.join(constraints),),
            (_one_line(entity.description or ''),),
            (entity.layer,))


def _one_line(text: str) -> str:
    return ' '.join(text.split())


def parameter_block(entities: Sequence[Entity]) -> str:
    """A ready-to-use YAML parameter file for the node's parameters (their defaults; a
    parameter without a default is listed in a comment, to be given)."""
    values: dict[str, Any] = {}
    required: list[str] = []
    for entity in entities:
        if entity.default_value is None:
            required.append(entity.name)
            continue
        values[entity.name] = entity.default_value
    head = ''.join(f'# required, no default: {one_line(name)}\n' for name in required)
    if not values:
        return head + "/**:\n  ros__parameters: {}\n"
    body = dump_yaml({'/**': {'ros__parameters': values}}, width=100)
    return head + body


def findings_table(findings: Sequence[Diagnostic], display: Callable[[str], str]) -> Table:
    """The findings as a table: severity, code, where, message."""
    rows = []
    for d in findings:
        where = display(d.file) if d.file else ''
        if where and d.line:
            where += f':{d.line}' + (f':{d.column}' if d.column else '')
        rows.append(((d.severity.value,), (Literal(d.code or ''),), (where,), (_one_line(d.message),)))
    return Table(('Severity', 'Code', 'Where', 'Message'), tuple(rows))


def node_page(resolved: ResolvedNode, source: PageSource, index: InterfaceIndex,
              display: Callable[[str], str], findings: Sequence[Diagnostic] = ()) -> tuple[Page, list[Diagnostic]]:
    """The page of a resolved node, and the findings made while building it (field tables
    that are unavailable).  ``display`` turns a file path into the words a page shows
    (paths relative to a root, so the pages do not depend on where they are built)."""
    anchor = label('node', source.title)
    page = Page(source.path, source.title, anchor)
    page.heading(1, source.title, anchor)
    page.paragraph(_one_line(resolved.interface.description or ''))
    base = resolved.base.value if resolved.base is not None else 'none'
    facts: list[tuple[tuple[Inline, ...], tuple[Inline, ...]]] = []
    if source.package and source.executable:
        facts.append((('Executable',), (Literal(f'ros2 run {source.package} {source.executable}'),)))
    facts.append((('Definition',), (source.file, f' ({source.provenance})')))
    facts.append((('Base',), (Literal(base),)))
    facts.append((('Client library',), (Literal(resolved.client_library),
                                         f' ({resolved.client_library_reason})')))
    page.blocks.append(Table(('Property', 'Value'), tuple(facts)))
    page.heading(2, 'Layers', label(anchor, 'layers'))
    page.blocks.append(Table(('Layer', 'Role', 'Provenance'), tuple(
        ((layer.label,), (layer.role,), (display(layer.file) if layer.file else 'built in',))
        for layer in resolved.layers)))

    parameters = [e for e in resolved.parameters]
    page.heading(2, 'Parameters', label(anchor, 'parameters'))
    if parameters:
        page.blocks.append(Table(PARAMETER_COLUMNS, tuple(_parameter_row(e) for e in parameters)))
        page.heading(3, 'Parameter file', label(anchor, 'parameter-file'))
        page.paragraph('A parameter file with every default, to copy and edit (',
                       Literal('--ros-args --params-file FILE'), '):')
        page.blocks.append(Code('yaml', parameter_block(parameters)))
    else:
        page.paragraph('No parameters.')

    used: dict[str, Location | None] = {}
    library: list[Entity] = []
    for section, title in SECTION_TITLES.items():
        entities = [e for e in resolved.endpoints if e.section == section]
        own = [e for e in entities if e.provider is not Provider.CLIENT_LIBRARY]
        library += [e for e in entities if e.provider is Provider.CLIENT_LIBRARY]
        if not own:
            continue
        page.heading(2, title, label(anchor, section))
        rows = []
        for entity in own:
            typed = str(entity.type) if entity.type is not None else entity.type_name
            if typed not in used:
                used[typed] = entity.location
            rows.append(((Literal(entity.name),), (Link(typed, type_label(anchor, typed)),),
                         (qos_words(entity.qos),), (_one_line(entity.description or ''),),
                         (entity.layer,)))
        page.blocks.append(Table(ENDPOINT_COLUMNS, tuple(rows)))
    if library:
        parts: list[Inline] = [f'The client library ({resolved.client_library}) also gives this '
                               'node: ']
        for i, entity in enumerate(library):
            parts += [', ' if i else '', Literal(entity.name), f' ({entity.kind.word})']
        parts.append('.')
        page.paragraph(*parts)

    found: list[Diagnostic] = []
    if used:
        page.heading(2, 'Types', label(anchor, 'types'))
        blocks, found = type_appendix(index, anchor, used)
        page.blocks += blocks
    every = [*findings, *found]
    if every:
        page.heading(2, 'Findings', label(anchor, 'findings'))
        page.blocks.append(findings_table(every, display))
    return page, found


def package_page(package: str, nodes: Sequence[tuple[str, str, str]],
                 interfaces: Sequence[tuple[str, str]], types: Sequence[str],
                 missing: Sequence[tuple[str, str]] = ()) -> Page:
    """A package's index: ``nodes`` (executable, page path, description), its interface
    definitions (``nodl://`` name, description), the interface types it defines, and the
    registered nodes whose page could not be made (executable, why)."""
    anchor = label('package', package)
    page = Page(f'{package}/index', package, anchor)
    page.heading(1, package, anchor)
    page.heading(2, 'Nodes', label(anchor, 'nodes'))
    if nodes:
        page.blocks.append(Table(('Executable', 'Description'), tuple(
            ((Link(executable, label('node', f'{package}/{executable}'), path),),
             (_one_line(description),)) for executable, path, description in nodes)))
    else:
        page.paragraph('No node definitions.')
    for executable, why in missing:
        page.blocks.append(Note('warning', (Literal(executable), f': no page: {_one_line(why)}')))
    if interfaces:
        page.heading(2, 'Interface definitions', label(anchor, 'interface-definitions'))
        page.blocks.append(Table(('Reference', 'Description'), tuple(
            ((Literal(name),), (_one_line(description),)) for name, description in interfaces)))
    if types:
        page.heading(2, 'Interface types', label(anchor, 'interface-types'))
        page.blocks.append(Table(('Type',), tuple(((Literal(t),),) for t in types)))
    return page

