"""``nodl system show``: the composition and its findings, as a report every reporter reads.

The text for people lists each node (final name, what it runs, its id, whether it is
read-only and why), its parameters and remapping rules, its ports (without the client
library's own, unless verbose), the connections, the pieces kept verbatim, then the
analysis's findings (those of ``nodl analyse``, with the same codes).  The JSON payload is
:meth:`Composition.to_dict`.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from nodl.composer.model import Group, Param, Remap
from nodl.composer.ports import ports_of
from nodl.composer.values import python_value
from nodl.reporting import plural
from nodl.reporting.reporters import Report
from nodl.text_safety import visible

if TYPE_CHECKING:
    from nodl.composer.composition import Composition

__all__ = ['show_report', 'show_text']


def _value(value: Any) -> str:
    return python_value(value)


def show_text(composition: Composition, verbose: bool = False) -> str:
    """The composition for people (see the module docstring)."""
    analysis = composition.analyse()
    nodes = composition.nodes
    kept = composition.document.kept()
    head = (f'{composition.path} ({composition.format}): {len(nodes)} node'
            f'{"s" if len(nodes) != 1 else ""}, {len(kept)} part{"s" if len(kept) != 1 else ""} '
            'kept as written')
    lines = [head]
    groups = [g for g, _ in composition.document.walk() if isinstance(g, Group)]
    for group in groups:
        pushed = group.namespace or ('(a namespace only the running launch knows)'
                                     if group.namespace_unknown else '(no namespace)')
        lines.append(f'  group [{group.id}] {pushed}' +
                     ('  (conditional)' if group.conditional else ''))
    for node in nodes:
        indent = '    ' if node.kind == 'composable' else '  '
        state = '' if node.editable else f'  read-only: {node.read_only_reason}'
        launched = analysis.node(node.id)
        if launched is None:
            state += '  (not launched with the default arguments)'
        lines.append(f'{indent}{composition.fqn(node)}  {node.label}  [{node.id}]{state}')
        for item in node.params:
            if isinstance(item, Param):
                lines.append(f'{indent}  param {item.name} = {_value(item.value)}')
            else:
                lines.append(f'{indent}  param: {item.what} (kept, line {item.line})')
        for rule in node.remaps:
            if isinstance(rule, Remap):
                lines.append(f'{indent}  remap {rule.source}:={rule.target}')
            else:
                lines.append(f'{indent}  remap: {rule.what} (kept, line {rule.line})')
        for port in ports_of(node.id, launched):
            if port.provider == 'client_library' and not verbose:
                continue
            lines.append(f'{indent}  {port.kind.replace("_", " ")} {port.name} -> '
                         f'{port.final_name} ({port.type})')
    connections = composition.connections()
    if connections:
        lines.append('connections:')
        for joined in connections:
            first, second = joined['from'], joined['to']
            if first['provider'] == 'client_library' and not verbose:
                continue
            mark = '' if joined['verdict'] == 'ok' else f"  {joined['verdict']}: {joined['reason']}"
            lines.append(f"  {first['final_name']}: {_fqn(composition, first['node'])} -> "
                         f"{_fqn(composition, second['node'])}{mark}")
    if kept:
        lines.append('kept as written (read-only here):')
        for piece in kept:
            lines.append(f'  line {piece.line}: {piece.what}')
    findings = [f for f in composition.findings if verbose or f.severity.value != 'info']
    if findings:
        lines.append('findings:')
        lines += [f'  {f.diagnostic}' for f in findings]
    return visible("\n".join(lines)) + "\n"


def _fqn(composition: Composition, node_id: str) -> str:
    node = composition.node(node_id)
    return composition.fqn(node) if node is not None else node_id


def show_report(composition: Composition, verbose: bool, tool: str) -> Report:
    """The report of ``nodl system show``."""
    findings = composition.findings
    counts = {'error': 0, 'warning': 0, 'info': 0}
    for finding in findings:
        counts[finding.severity.value] += 1
    summary = (f'{os.path.basename(composition.path)}: {plural(len(composition.nodes), "node")}, '
               f"{plural(counts['error'], 'error')}, {plural(counts['warning'], 'warning')}, "
               f"{counts['info']} info")
    diagnostics = [f.diagnostic for f in findings] + composition.kept_diagnostics()
    text = show_text(composition, verbose)
    return Report(tool, diagnostics, summary=summary, text=text + summary + '\n',
                  payload=lambda: composition.to_dict())
