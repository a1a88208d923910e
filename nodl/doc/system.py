"""The page of a launched system, from the analysis (as ``nodl analyse`` makes it).

* every launched node: final name, package, executable, where its definition
  comes from (linked to the node's page when it has one);
* every topic, service and action (what the client library gives every node
  left out, as the graph leaves it out): final name, type(s), publishers and
  subscriptions, servers and clients;
* the parameters each node receives, with where each value is written and how
  (inline, a parameter file, ``set_parameter``, ``-p``);
* the findings of the analysis;
* the graph (:mod:`nodl.graph`), embedded.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.doc.blocks import Inline, Link, Literal, Note, Page, Picture, Table, label
from nodl.doc.model import findings_table, value_text
from nodl.graph import GraphError, render_graph

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

    from nodl.composition.instance import InstanceEntity
    from nodl.diagnostics import Diagnostic
    from nodl.system.run import Analysis

__all__ = ['system_page', 'graph_picture']

_SIDES = {'topic': ('Publishers', 'Subscriptions'), 'service': ('Servers', 'Clients'),
          'action': ('Servers', 'Clients')}
_TITLES = {'topic': 'Topics', 'service': 'Services', 'action': 'Actions'}


def graph_picture(analysis: Analysis, file: str) -> tuple[Picture | None, Diagnostic | None]:
    """The system's graph as SVG (kept as ``file`` next to the page), or why it cannot be
    drawn (NODL274: the layout program is missing or fails)."""
    try:
        svg = render_graph(analysis, 'svg')
    except GraphError as exc:
        return None, Diagnostic(Severity.WARNING, f'the graph of the system cannot be drawn: {exc}',
                                file=analysis.launch_file or '', code='NODL274')
    return Picture(svg, file, 'The nodes of the system and the topics, services and actions '
                              'between them'), None


def system_page(analysis: Analysis, path: str, node_pages: Mapping[int, tuple[str, str]],
                display: Callable[[str], str], picture: Picture | None,
                extra: list[Diagnostic] | None = None) -> Page:
    """The page of ``analysis`` at ``path``; ``node_pages``: ``id(match)`` -> (page path,
    title) of the node pages made for the system's definitions."""
    title = display(analysis.launch_file) if analysis.launch_file else 'system'
    anchor = label('system', path)
    page = Page(path, title, anchor)
    page.heading(1, f'System: {title}', anchor)
    nodes = analysis.nodes
    page.paragraph(f'{len(nodes)} launched node{"s" if len(nodes) != 1 else ""}, as the analysis '
                   'of the launch file finds them (final names after namespaces and remapping).')
    page.heading(2, 'Nodes', label(anchor, 'nodes'))
    rows = []
    for node in nodes:
        match = node.match
        found = node_pages.get(id(match))
        if found is not None:
            definition: tuple[Inline, ...] = (Link(found[1], label('node', found[1]), found[0]),
                                              f' ({match.origin})')
        elif match.file:
            definition = (display(match.file), ' (does not resolve)')
        else:
            definition = ('no definition',)
        what = node.entry.executable or node.entry.plugin or ''
        rows.append(((Literal(node.fqn),), (Literal(node.package),), (Literal(what),),
                     definition))
    page.blocks.append(Table(('Final name', 'Package', 'Executable', 'Definition'), tuple(rows)))
    system = analysis.context.system if analysis.context is not None else None
    for communication in ('topic', 'service', 'action'):
        connections = system.connections(communication, include_client_library=False) \
            if system is not None else []
        if not connections:
            continue
        offer, use = _SIDES[communication]
        page.heading(2, _TITLES[communication], label(anchor, communication + 's'))
        table_rows = []
        for connection in sorted(connections, key=lambda c: c.name):
            types: list[Inline] = []
            for i, type_name in enumerate(connection.types):
                types += [', ' if i else '', Literal(type_name)]
            table_rows.append(((Literal(connection.name),), tuple(types),
                               _fqns(connection.offering), _fqns(connection.using)))
        page.blocks.append(Table(('Name', 'Type', offer, use), tuple(table_rows)))
    page.heading(2, 'Parameters', label(anchor, 'parameters'))
    any_parameters = False
    seen: dict[str, int] = {}
    for node in nodes:
        settings = node.parameters
        if not settings:
            continue
        any_parameters = True
        # a name launched twice (a finding of its own) is two sections, each with its target
        seen[node.fqn] = count = seen.get(node.fqn, 0) + 1
        heading, target = node.fqn, label(anchor, 'launched', node.fqn)
        if count > 1:
            where = getattr(node.entry, 'location', None)
            place = f'{display(where.file)}:{where.line}' if where is not None and where.file else ''
            heading = f'{node.fqn} (launched again{", at " + place if place else ""})'
            target = label(target, str(count))
        page.heading(3, heading, target)
        param_rows = []
        for name, setting in settings.items():
            where = display(setting.location.file)
            if setting.location.line:
                where += f':{setting.location.line}'
            param_rows.append(((Literal(name),), (Literal(value_text(setting.value)),),
                               (setting.origin,), (where,)))
        page.blocks.append(Table(('Parameter', 'Value', 'Given as', 'Where'), tuple(param_rows)))
    if not any_parameters:
        page.paragraph('No node receives parameters from the launch files.')
    findings = [f.diagnostic for f in analysis.findings] + list(extra or ())
    page.heading(2, 'Findings', label(anchor, 'findings'))
    if findings:
        page.blocks.append(findings_table(findings, display))
    else:
        page.paragraph('The analysis finds nothing.')
    page.heading(2, 'Graph', label(anchor, 'graph'))
    if picture is not None:
        page.blocks.append(picture)
    else:
        page.blocks.append(Note('warning', ('The graph cannot be drawn here (see the findings).',)))
    return page


def _fqns(side: tuple[InstanceEntity, ...]) -> tuple[Inline, ...]:
    parts: list[Inline] = []
    for i, bound in enumerate(sorted(side, key=lambda b: b.instance.fqn)):
        parts += [', ' if i else '', Literal(bound.instance.fqn)]
    return tuple(parts) or ('none',)
