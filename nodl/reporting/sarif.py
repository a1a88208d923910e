"""SARIF 2.1.0: diagnostics for code-scanning services and editors.

One run, one rule per code that occurs (with the catalogue's one-line
explanation and default level), one result per diagnostic.  Relative file
names become URIs relative to ``SRCROOT`` (the current directory), absolute
ones ``file://`` URIs; names that are not files (``<stdin>``, a node name,
``package/executable``) get no physical location.  A position is given only
when it is known: SARIF lines and columns start at 1.
"""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import Any

from nodl.diagnostics import Diagnostic, Severity
from nodl.text_safety import visible

__all__ = ['SARIF_SCHEMA', 'SARIF_VERSION', 'INFORMATION_URI', 'sarif_log', 'format_sarif']

SARIF_SCHEMA = 'https://json.schemastore.org/sarif-2.1.0.json'
SARIF_VERSION = '2.1.0'
#: Where a user learns about the codes (the catalogue in the repository).
INFORMATION_URI = 'https://github.com/ros-tooling/nodl'
_LEVELS = {Severity.ERROR: 'error', Severity.WARNING: 'warning', Severity.INFO: 'note'}
_SEVERITY_LEVELS = {'error': 'error', 'warning': 'warning', 'info': 'note'}


def _uri(name: str) -> tuple[str, str | None] | None:
    """``(uri, uriBaseId)`` of a file name; None for names that are not files."""
    from pathlib import Path
    from urllib.parse import quote

    if not name or name.startswith('<'):
        return None
    if os.path.isabs(name):
        if not os.path.exists(name):
            return None  # a node name such as /robot/driver, not a file
        return Path(name).as_uri(), None
    if not os.path.exists(name):
        return None  # package/executable
    return quote(name.replace(os.sep, '/')), 'SRCROOT'


def _location(file: str, line: int, column: int, path_text: str = '',
              message: str | None = None) -> dict[str, Any] | None:
    uri = _uri(file)
    location: dict[str, Any] = {}
    if uri is not None:
        artifact: dict[str, Any] = {'uri': uri[0]}
        if uri[1] is not None:
            artifact['uriBaseId'] = uri[1]
        physical: dict[str, Any] = {'artifactLocation': artifact}
        if line > 0:
            region: dict[str, int] = {'startLine': line}
            if column > 0:
                region['startColumn'] = column
            physical['region'] = region
        location['physicalLocation'] = physical
    if path_text:
        location['logicalLocations'] = [{'fullyQualifiedName': path_text}]
    if message:
        location['message'] = {'text': visible(message)}
    return location or None


def sarif_log(diagnostics: Iterable[Diagnostic], tool_name: str = 'nodl') -> dict[str, Any]:
    """The SARIF log object of ``diagnostics`` (JSON-ready)."""
    from pathlib import Path

    from nodl.codes import CODES
    from nodl.version import __version__

    items = list(diagnostics)
    rule_index: dict[str, int] = {}
    rules: list[dict[str, Any]] = []
    for d in items:
        if d.code and d.code not in rule_index:
            rule_index[d.code] = len(rules)
            severity, explanation = CODES.get(d.code, ('warning', ''))
            rules.append({
                'id': d.code,
                'shortDescription': {'text': explanation or d.code},
                'defaultConfiguration': {'level': _SEVERITY_LEVELS[severity]},
            })
    results: list[dict[str, Any]] = []
    for d in items:
        result: dict[str, Any] = {'level': _LEVELS[d.severity], 'message': {'text': visible(d.message)}}
        if d.code:
            result['ruleId'] = d.code
            result['ruleIndex'] = rule_index[d.code]
        location = _location(d.file, d.line, d.column, d.path_text)
        if location is not None:
            result['locations'] = [location]
        related = [loc for loc in (_location(f, line, column, message=text)
                                   for f, line, column, text in d.related) if loc is not None]
        if related:
            for index, loc in enumerate(related):
                loc['id'] = index
            result['relatedLocations'] = related
        results.append(result)
    run: dict[str, Any] = {
        'tool': {'driver': {'name': tool_name, 'version': __version__,
                            'informationUri': INFORMATION_URI, 'rules': rules}},
        'originalUriBaseIds': {'SRCROOT': {'uri': Path(os.getcwd()).as_uri().rstrip('/') + '/'}},
        'results': results,
    }
    return {'$schema': SARIF_SCHEMA, 'version': SARIF_VERSION, 'runs': [run]}


def format_sarif(diagnostics: Iterable[Diagnostic], tool_name: str = 'nodl') -> str:
    """The SARIF log of ``diagnostics`` as JSON text."""
    return json.dumps(sarif_log(diagnostics, tool_name), indent=2) + '\n'
