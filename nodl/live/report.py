"""Check results for people (text), tools (JSON), CI (JUnit XML) and code scanning (SARIF).

Every report shows the result as it stands after ``--ignore`` / ``--error``
(:meth:`~nodl.live.check.CheckResult.with_overrides`): ignored
differences are counted, not listed; promoted ones are errors.
"""

from __future__ import annotations

from typing import Any

from nodl.live.check import CheckResult
from nodl.live.observe import watched_line
from nodl.vocabulary import SECTION_KEYS

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from nodl.reporting.junit import JUnitCase
    from nodl.reporting.reporters import Report

__all__ = ['format_check_text', 'format_check_json', 'format_check_junit', 'format_check_sarif',
           'check_payload', 'check_cases', 'check_report']


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
    """The JSON report (:func:`check_payload`)."""
    from nodl.reporting.reporters import JsonReporter

    return JsonReporter().report(check_report(result))


def check_payload(result: CheckResult) -> dict[str, Any]:
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
    return data


def format_check_sarif(result: CheckResult) -> str:
    """A SARIF 2.1.0 log: one rule per code, one result per difference, located at the
    entity's declaration (see :meth:`~nodl.live.check.CheckResult.location_of`); each
    message starts with the node's name."""
    from nodl.reporting.reporters import SarifReporter

    return SarifReporter().report(check_report(result))


def format_check_junit(result: CheckResult) -> str:
    """A JUnit XML report: one test case per checked entity (:func:`check_cases`)."""
    from nodl.reporting.reporters import JUnitReporter

    return JUnitReporter().report(check_report(result))


def check_cases(result: CheckResult) -> list[JUnitCase]:
    """One JUnit test case per checked entity, in its section's class: each error difference
    is a failure of its kind, the others the case's output."""
    from nodl.live.conformance import final_name
    from nodl.reporting.junit import JUnitCase, JUnitFailure

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
    return [JUnitCase(name, [result.diagnostic(d) for d in diffs],
                      any(d.severity == 'error' for d in diffs), classname=section,
                      failures=[JUnitFailure(d.kind, d.message, str(d))
                                for d in diffs if d.severity == 'error'],
                      output=[str(d) for d in diffs if d.severity != 'error'])
            for (section, name), diffs in sorted(cases.items())]


def check_report(result: CheckResult, verbose: bool = False) -> Report:
    """The check as every reporter reads it: its differences as diagnostics located at the
    entity's declaration, each message starting with the node's name (see
    :meth:`~nodl.live.check.CheckResult.location_of`), the JSON payload, a test case per
    checked entity, the text report and its verdict line."""
    from nodl.reporting.reporters import Report

    return Report(f'nodl check {result.fqn}',
                  [d.replace(message=f'{result.fqn}: {d.message}') for d in result.diagnostics],
                  summary=format_check_text(result).splitlines()[-1], text=lambda: format_check_text(result, verbose),
                  payload=lambda: check_payload(result), cases=lambda: check_cases(result))
