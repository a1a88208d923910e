"""A check's result as every reporter reads it: :func:`check_report`.

The differences are diagnostics already (:class:`~nodl.live.conformance.LiveDiagnostic`,
placed at their declarations); this module says the rest: the text for
people (:func:`format_check_text`: a line per difference after the node's
name, then the verdict), the JSON payload (:func:`check_payload`) and a JUnit
test case per checked entity (:func:`check_cases`).  The ``nodl.reporters``
(text, JSON, SARIF, JUnit and plug-ins) render the :class:`~nodl.reporting.reporters.Report`.

Every report shows the result as it stands after ``--ignore`` / ``--error``
(:meth:`~nodl.live.check.CheckResult.with_overrides`): ignored
differences are counted, not listed; promoted ones are errors.
"""

from __future__ import annotations

from typing import Any

from nodl.diagnostics import Diagnostic
from nodl.live.check import CheckResult
from nodl.live.conformance import LiveDiagnostic, final_name
from nodl.live.observe import watched_line
from nodl.reporting.junit import JUnitCase, JUnitFailure
from nodl.reporting.reporters import Report
from nodl.vocabulary import SECTION_KEYS

__all__ = ['format_check_text', 'check_payload', 'check_cases', 'check_report']


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
        lines.append(f'{result.fqn}: {d.brief()}')
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


def check_payload(result: CheckResult) -> dict[str, Any]:
    """``{"node", "definition", "conforms", "ignored", "namesakes_watched", "differences": [...]}``.

    Each difference has its kind, code, severity (after the overrides),
    section, name, declared and observed values, layer, message, and where
    it points (``file``, ``line``, ``column``, ``related``); ``ignored`` counts
    the differences the overrides silenced.
    """
    return {'node': result.fqn, 'definition': result.definition,
            'conforms': result.conforms,
            'base_hint': result.base_hint,
            'client_library': (result.client_library._asdict()
                               if result.client_library is not None else None),
            'ignored': len(result.ignored),
            'namesakes_watched': (round(result.watched, 2)
                                  if result.watched is not None else None),
            'differences': [d.to_dict() for d in result.differences]}


def check_cases(result: CheckResult) -> list[JUnitCase]:
    """One JUnit test case per checked entity, in its section's class: each error difference
    is a failure of its kind, the others the case's output."""
    cases: dict[tuple[str, str], list[LiveDiagnostic]] = {}
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
    return [JUnitCase(name, diffs, any(d.severity == 'error' for d in diffs), classname=section,
                      failures=[JUnitFailure(d.kind, d.message, d.brief())
                                for d in diffs if d.severity == 'error'],
                      output=[d.brief() for d in diffs if d.severity != 'error'])
            for (section, name), diffs in sorted(cases.items())]


def check_report(result: CheckResult, verbose: bool = False) -> Report:
    """The check as every reporter reads it: its differences as diagnostics located at the
    entity's declaration, each message the difference's headline after the node's name
    (``/ns/node: missing: ... (declared in main)``), the JSON payload, a test case per
    checked entity, the text report and its verdict line."""
    return Report(f'nodl check {result.fqn}',
                  [Diagnostic(d.severity, f'{result.fqn}: {d.headline()}', d.path, d.file, d.line,
                              d.column, code=d.code, related=d.related)
                   for d in result.differences],
                  summary=format_check_text(result).splitlines()[-1],
                  text=lambda: format_check_text(result, verbose),
                  payload=lambda: check_payload(result), cases=lambda: check_cases(result))
