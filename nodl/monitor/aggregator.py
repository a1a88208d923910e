"""A diagnostic_aggregator analyzer configuration grouping the monitor's statuses by namespace.

diagnostic_aggregator's ``aggregator_node`` (C++) reads its analyzers from its parameters
(``analyzers: ros__parameters: ...``).  The configuration written here has one
``diagnostic_aggregator/AnalyzerGroup`` (``path: NoDL``) holding a
``diagnostic_aggregator/GenericAnalyzer`` per namespace of the expected system and one
for ``nodl: system``.  Each analyzer matches its statuses by exact name (``expected``:
the aggregator then shows a node as stale when the monitor stops publishing it) and
strips ``nodl: /ns/`` from their names (``remove_prefix``), since the aggregator turns
every ``/`` left in an item name into a space.  The tree it gives::

    /NoDL
    /NoDL/System/system
    /NoDL/<namespace>/<node>        (root namespace: /NoDL/root/<node>)
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from typing import Any

from nodl.monitor.status import PREFIX, SYSTEM, status_name

__all__ = ['analyzer_config', 'format_config', 'tree_paths', 'GROUP_PATH']

#: The path of the group holding every analyzer.
GROUP_PATH = 'NoDL'
_KEY = re.compile('[^a-z0-9_]')


def _path(namespace: str) -> str:
    return namespace.strip('/').replace('/', ' ') or 'root'


def _key(namespace: str, taken: set[str]) -> str:
    key = 'ns_' + (_KEY.sub('_', namespace.strip('/').lower()) or 'root')
    base, n = key, 2
    while key in taken:
        key, n = f'{base}_{n}', n + 1
    taken.add(key)
    return key


def analyzer_config(fqns: Iterable[str], timeout: float = 5.0) -> dict[str, Any]:
    """The aggregator's parameters (``{'analyzers': {'ros__parameters': ...}}``) for the
    statuses of the nodes ``fqns`` and the system's.  ``timeout``: seconds without a status
    before the aggregator calls it stale."""
    by_namespace: dict[str, list[str]] = {}
    for fqn in sorted(set(fqns)):
        namespace = fqn.rpartition('/')[0] or '/'
        by_namespace.setdefault(namespace, []).append(fqn)
    analyzers: dict[str, Any] = {
        'system': {'type': 'diagnostic_aggregator/GenericAnalyzer', 'path': 'System',
                   'expected': [SYSTEM], 'remove_prefix': [PREFIX], 'timeout': timeout}}
    taken = {'system'}
    for namespace, names in sorted(by_namespace.items()):
        prefix = PREFIX + namespace.rstrip('/') + '/'
        analyzers[_key(namespace, taken)] = {
            'type': 'diagnostic_aggregator/GenericAnalyzer', 'path': _path(namespace),
            'expected': [status_name(n) for n in names], 'remove_prefix': [prefix],
            'timeout': timeout}
    group = {'type': 'diagnostic_aggregator/AnalyzerGroup', 'path': GROUP_PATH,
             'analyzers': analyzers}
    return {'analyzers': {'ros__parameters': {'nodl': group}}}


def tree_paths(config: dict[str, Any], names: Iterable[str]) -> dict[str, str]:
    """Where the aggregator files each status name under ``config``: ``/NoDL/<path>/<item>``
    (the item: the name less the analyzer's prefix, every ``/`` a space, as the aggregator
    writes it).  A name no analyzer expects is left out."""
    group = config['analyzers']['ros__parameters']['nodl']
    out: dict[str, str] = {}
    for name in names:
        for analyzer in group['analyzers'].values():
            if name in analyzer['expected']:
                item = name
                for prefix in analyzer['remove_prefix']:
                    if item.startswith(prefix):
                        item = item[len(prefix):]
                        break
                out[name] = f"/{group['path']}/{analyzer['path']}/{item.replace('/', ' ')}"
                break
    return out


def _yaml(value: Any, indent: int) -> list[str]:
    pad = '  ' * indent
    lines: list[str] = []
    for key, item in value.items():
        if isinstance(item, dict):
            lines.append(f'{pad}{key}:')
            lines += _yaml(item, indent + 1)
        else:
            lines.append(f'{pad}{key}: {json.dumps(item)}')
    return lines


def format_config(config: dict[str, Any]) -> str:
    """The configuration as YAML (strings JSON-quoted: valid YAML, any character escaped)."""
    header = ['# diagnostic_aggregator analyzers for nodl monitor (written by nodl monitor',
              '# --aggregator-config); give it to aggregator_node as a parameter file.']
    return '\n'.join(header + _yaml(config, 0)) + '\n'
