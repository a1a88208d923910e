"""The log file of an analysis (``nodl analyse --log FILE``), for later debugging.

Plain text in two parts.  The resolved system: every node in launch order with its final
name (and how the name came about: given, recorded at registration, assumed, renamed by a
rule), where it is launched, what it runs (and in which container), its definition and
client library, its remapping rules in rcl's order with where each is written, every
parameter with its final value and origin (given values with their place, declared
defaults with the definition's; ``run time`` lines say where parameters or remapping
rules only the running launch knows come from), and every endpoint with its final name,
type, declared name, layer and QoS.  Then every finding (info included) with its place, the nodes,
endpoint or parameter it concerns and its related places.  The text is deterministic:
the same launch, definitions and toolkit give the same bytes (no time stamps).
"""

from __future__ import annotations

import json
from typing import Any

from nodl.launch.params import RuntimeValue
from nodl.system.findings import Finding
from nodl.system.launched import SystemNode
from nodl.system.run import LAUNCH_KIND, Analysis
from nodl.text_safety import visible
from nodl.version import __version__

__all__ = ['format_log']

#: The width of the label column.
_LABEL = 16
#: A part of a node known only at run time -> what the log says of it.
_RUN_TIME = {'parameters': 'more parameters, known only when the launch runs (not listed; none is '
                           'reported missing)',
             'remaps': 'more remapping rules, known only when the launch runs (not listed)',
             'arguments': 'arguments known only when the launch runs (not listed; they may hold '
                          'parameters and remapping rules)'}
#: A launch entry's role -> the words for it.
_ROLES = {'node': 'process', 'container': 'container process', 'composable': 'composable node'}


def _value(value: object) -> str:
    return json.dumps(value, default=str, sort_keys=True)


def _line(label: str, text: str) -> str:
    return f'  {label:<{_LABEL}}{text}'.rstrip()


def _name_origin(node: SystemNode) -> str:
    entry = node.entry
    if entry.name:
        how = 'given in the launch file'
    elif node.match.node_name:
        how = 'recorded at registration'
    else:
        how = "assumed: the executable's name"
    text = f'{node.created_name} ({how})'
    if node.names is not None and node.names.name != node.created_name:
        text += f', renamed {node.names.name} by a __node rule'
    return text


def _qos(qos: Any) -> str:
    if qos is None:
        return ''
    return '; qos ' + ', '.join(f'{k}={v}' for k, v in qos.to_dict().items())


def _node(node: SystemNode) -> list[str]:
    entry = node.entry
    out = [f'node {node.fqn}', _line('launched at', str(entry.location))]
    role = _ROLES.get(entry.role, entry.role)
    if entry.container:
        role += f' in container {entry.container}'
    out.append(_line('kind', role))
    runs = entry.executable if entry.executable is not None else f'plugin {entry.plugin}'
    out.append(_line('runs', f'{node.package} {runs}'))
    out.append(_line('name', _name_origin(node)))
    namespace = node.names.namespace if node.names is not None else entry.namespace
    out.append(_line('namespace', namespace + (f' (launched in {entry.namespace})'
                                               if namespace != entry.namespace else '')))
    out.append(_line('definition', f'{node.match.file or "none"}'
                     + (f' (matched by {node.match.how})' if node.match.file else '')))
    if node.instance is not None:
        out.append(_line('client library', node.instance.resolved.client_library))
    for index, (source, target) in enumerate(entry.remaps):
        out.append(_line('remap', f'{source} -> {target}  ({entry.remap_location(index)})'))
    for part, where in entry.run_time:
        out.append(_line('run time', _RUN_TIME.get(part, part) + f'  ({where})'))
    given = node.parameters
    for name, setting in given.items():
        if isinstance(setting.value, RuntimeValue):  # no value to show: say so, no stand-in
            out.append(_line('parameter', f'{name}, known only at run time  '
                                          f'({setting.origin}, {setting.location})'))
            continue
        out.append(_line('parameter', f'{name} = {_value(setting.value)}  '
                                      f'({setting.origin}, {setting.location})'))
    if node.instance is not None:
        default = 'declared default' if not entry.run_time or entry.parameters_complete \
            else 'declared default unless set at run time'
        for bound in node.instance.entities:
            entity = bound.entity
            if not entity.is_parameter or bound.name in given:
                continue
            value = _value(entity.default_value) if entity.default_value is not None else 'unset'
            out.append(_line('parameter', f'{bound.name} = {value}  ({default}, '
                                          f'{entity.location})'))
        for bound in node.instance.endpoints:
            entity = bound.entity
            out.append(_line(entity.kind.word, f'{bound.name}  ({entity.type_name}; declared '
                                               f'{entity.name!r} in {entity.layer}'
                                               f'{_qos(getattr(entity, "qos", None))})'))
    return out


def _sort_key(finding: Finding) -> tuple[Any, ...]:
    d = finding.diagnostic
    return (finding.kind != LAUNCH_KIND, d.file, d.line, d.column, d.code, d.message, finding.nodes)


def _finding(finding: Finding) -> list[str]:
    out = [f'{finding}  <{finding.kind}>']
    if finding.nodes:
        out.append(f'  nodes: {", ".join(finding.nodes)}')
    if finding.endpoint is not None:
        out.append(f'  endpoint: {finding.endpoint}')
    if finding.parameter is not None:
        out.append(f'  parameter: {finding.parameter}')
    for file, line, column, message in finding.diagnostic.related:
        where = f'{file}:{line}:{column}' if line else file
        out.append(f'  {where}: note: {message}')
    return out


def format_log(analysis: Analysis) -> str:
    """The whole log text."""
    out = [f'# nodl analyse {analysis.launch_file or ""}'.rstrip(),
           f'# nodl-toolkit {__version__}',
           f'# {analysis.summary()}', '', f'== System ({len(analysis.nodes)} nodes)', '']
    for node in analysis.nodes:
        out += _node(node)
        out.append('')
    out += [f'== Findings ({len(analysis.findings)})', '']
    for finding in sorted(analysis.findings, key=_sort_key):
        out += _finding(finding)
        out.append('')
    if not analysis.findings:
        out += ['no findings', '']
    # names, values and messages from launch files: no control or bidi character reaches the log
    return visible('\n'.join(out))
