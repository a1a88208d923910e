"""Check results for people (text), tools (JSON), CI (JUnit XML) and code scanning (SARIF).

Every report shows the result as it stands after ``--ignore`` / ``--error``
(:meth:`~nodl.live.check.CheckResult.with_overrides`): ignored
differences are counted, not listed; promoted ones are errors.
"""

from __future__ import annotations

import json
from typing import Any

from nodl.live.check import CheckResult
from nodl.live.observe import watched_line
from nodl.text_safety import xml_report_attribute as quoteattr, xml_report_text as escape
from nodl.vocabulary import SECTION_KEYS

__all__ = ['format_check_text', 'format_check_json', 'format_check_junit', 'format_check_sarif']


def format_check_text(result: CheckResult, verbose: bool = False) -> str:
    """One line per difference, then a verdict."""
    lines = []
    if result.client_library is not None:
        lines.append(f'{result.fqn}: client library: {result.client_library}')
    if result.watched is not None:
        lines.append(f'{result.fqn}: {watched_line(result.watched)}')
    folded = result.base_differences if not verbose else []
    if result.base_hint:
        more = (f' ({len(folded)} differences of the base, listed with -v)' if folded else '')
        lines.append(f'{result.fqn}: error: base: {result.base_hint}{more}')
    for d in result.differences:
        if (d.severity == 'info' and not verbose) or any(d is f for f in folded):
            continue
        lines.append(f'{result.fqn}: {d}')
    drift = len(result.drift)
    unverifiable = sum(1 for d in result.differences
                       if d.kind == 'unverifiable' and d.severity == 'info')
    if result.conforms:
        verdict = f'{result.fqn} conforms to {result.definition}'
    else:
        verdict = (f'{result.fqn} drifts from {result.definition}: {drift} '
                   f'difference{"s" * (drift != 1)}')
    notes = []
    if unverifiable:
        notes.append(f'{unverifiable} unverifiable' + (', listed with -v' if not verbose else ''))
    if result.ignored:
        notes.append(f'{len(result.ignored)} ignored')
    lines.append(verdict + (f' ({"; ".join(notes)})' if notes else ''))
    return '\n'.join(lines) + '\n'


def _difference_dict(result: CheckResult, difference: Any) -> dict[str, Any]:
    data: dict[str, Any] = difference.to_dict()
    placed = result.diagnostic(difference)
    data.update(file=placed.file, line=placed.line, column=placed.column,
                related=[{'file': f, 'line': li, 'column': c, 'message': m}
                         for f, li, c, m in placed.related])
    return data


def format_check_json(result: CheckResult) -> str:
    """``{"node", "definition", "conforms", "ignored", "namesakes_watched", "differences": [...]}``.

    Each difference has its kind, code, severity (after the overrides),
    section, name, declared and observed values, layer, message, and where
    it points (``file``, ``line``, ``column``, ``related``); ``ignored`` counts
    the differences the overrides silenced.
    """
    data: dict[str, Any] = {'node': result.fqn, 'definition': result.definition,
                            'conforms': result.conforms,
                            'base_hint': result.base_hint,
                            'client_library': (result.client_library._asdict()
                                               if result.client_library is not None else None),
                            'ignored': len(result.ignored),
                            'namesakes_watched': (round(result.watched, 2)
                                                  if result.watched is not None else None),
                            'differences': [_difference_dict(result, d)
                                            for d in result.differences]}
    return json.dumps(data, indent=2, default=str) + '\n'


def format_check_sarif(result: CheckResult) -> str:
    """A SARIF 2.1.0 log: one rule per code, one result per difference, located at the
    entity's declaration (see :meth:`~nodl.live.check.CheckResult.location_of`); each
    message starts with the node's name."""
    from nodl.reporting.sarif import format_sarif

    return format_sarif([d.replace(message=f'{result.fqn}: {d.message}')
                         for d in result.diagnostics])


def format_check_junit(result: CheckResult) -> str:
    """A JUnit XML report: one test case per checked entity; drift is a failure."""
    from nodl.live.conformance import final_name

    cases: dict[tuple[str, str], list[Any]] = {}
    # A difference names the entity as observed (expanded, remapped): find its declaration.
    declared_as: dict[tuple[str, str], tuple[str, str]] = {}
    for section in SECTION_KEYS:
        for entity in result.composed.interface.endpoints(section):
            cases.setdefault((section, entity.name), [])
            full = final_name(entity.name, section, result.observed, result.names or result.remaps)
            declared_as[(section, full)] = (section, entity.name)
    for param in result.composed.interface.parameters or {}:
        cases.setdefault(('parameters', param), [])
    for d in result.differences:
        key = declared_as.get((d.section, d.name), (d.section, d.name))
        cases.setdefault(key, []).append(d)
    failures = sum(1 for ds in cases.values() if any(d.severity == 'error' for d in ds))
    suite = quoteattr(f'nodl check {result.fqn}')
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<testsuite name={suite} tests="{len(cases)}" failures="{failures}" errors="0">']
    for (section, name), diffs in sorted(cases.items()):
        out.append(f'  <testcase classname={quoteattr(section)} name={quoteattr(name)}>')
        # JUnit's schema wants the failures first and at most one system-out
        for d in diffs:
            if d.severity == 'error':
                out.append(f'    <failure type={quoteattr(d.kind)} message={quoteattr(d.message)}>'
                           f'{escape(str(d))}</failure>')
        notes = [escape(str(d)) for d in diffs if d.severity != 'error']
        if notes:
            out.append('    <system-out>' + '\n'.join(notes) + '</system-out>')
        out.append('  </testcase>')
    out.append('</testsuite>')
    return '\n'.join(out) + '\n'
