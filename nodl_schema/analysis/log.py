"""The log file of an analysis (``nodl analyse --log FILE``), for later debugging.

Plain text in two parts: the resolved system (every node with its final name,
where it is launched, what it runs, its definition, remapping rules,
parameters and every endpoint's declared and final name), then every finding
(info included) with its related places.
"""

from __future__ import annotations

import datetime
import json

from nodl_schema.analysis.system import Analysis

__all__ = ['format_log']


def _value(value: object) -> str:
    return json.dumps(value, default=str)


def format_log(analysis: Analysis) -> str:
    """The whole log text."""
    from nodl_schema import __version__
    from nodl_schema.analysis.report import summary

    out = [f'# nodl analyse {analysis.launch_file or ""}'.rstrip(),
           f'# nodl-toolkit {__version__}, {datetime.datetime.now().isoformat(timespec="seconds")}',
           f'# {summary(analysis)}', '', '== System', '']
    for node in analysis.nodes:
        entry = node.entry
        runs = entry.executable if entry.executable is not None else f'plugin {entry.plugin}'
        out.append(f'node {node.fqn}')
        out.append(f'  launched at     {entry.location}')
        out.append(f'  runs            {entry.package} {runs}'
                   + (f' (in container {entry.container})' if entry.container else ''))
        out.append(f'  definition      {node.match.file or "none"}'
                   + (f' (matched by {node.match.how})' if node.match.file else ''))
        if node.instance is not None:
            out.append(f'  client library  {node.instance.resolved.client_library}')
        for source, target in entry.remaps:
            out.append(f'  remap           {source} -> {target}')
        for name, setting in node.parameters.items():
            out.append(f'  parameter       {name} = {_value(setting.value)}  '
                       f'({setting.origin}, {setting.location})')
        if node.instance is not None:
            for bound in node.instance.endpoints:
                entity = bound.entity
                out.append(f'  {entity.kind.word:<16}{bound.name}  ({entity.type_name}; declared '
                           f'{entity.name!r} in {entity.layer})')
        out.append('')
    out += ['== Findings', '']
    for finding in analysis.findings:
        out.append(f'{finding}  <{finding.kind}>')
        if finding.nodes:
            out.append(f'  nodes: {", ".join(finding.nodes)}')
        for file, line, column, message in finding.diagnostic.related:
            where = f'{file}:{line}:{column}' if line else file
            out.append(f'  {where}: note: {message}')
    if not analysis.findings:
        out.append('no findings')
    return '\n'.join(out) + '\n'
