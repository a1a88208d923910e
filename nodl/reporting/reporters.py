"""Output formats as extensions: the ``nodl.reporters`` extension point.

Every verb that reports a result builds one :class:`Report` (its diagnostics,
a summary line for people, and optionally its own text, JSON payload and JUnit
test cases) and hands it to the reporter ``--format`` names.  The built-in
reporters (``text``, ``json``, ``sarif``, ``junit``) are registered in
``pyproject.toml`` under ``nodl.reporters`` exactly as a plug-in registers its
own, so a plug-in format (GitHub annotations, Checkstyle, ...) is offered by
every verb at once.

A reporter is a :class:`ReporterExtension`: it renders a :class:`Report` to
text (:meth:`~ReporterExtension.report`) and may show each unit of work as the
verb finishes it (:meth:`~ReporterExtension.unit`: ``nodl validate`` prints
each file's diagnostics at once in text).  Every reporter shows diagnostics;
:attr:`~ReporterExtension.KINDS` names the other kinds of result it can show
(``nodl list``'s ``listing``), ``'*'`` meaning every kind.  The library never
prints: a reporter returns text, the verb writes it.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from typing import Any

    from nodl.reporting.junit import JUnitCase

from nodl.diagnostics import Diagnostic, Severity
from nodl.plugins import ExtensionPoint
from nodl.reporting import format_text

__all__ = ['GROUP', 'DIAGNOSTICS', 'Report', 'ReporterExtension', 'TextReporter', 'JsonReporter',
           'SarifReporter', 'JUnitReporter', 'cases_by_file']

#: The entry point group of reporters.
GROUP = 'nodl.reporters'
#: The kind of result every verb that checks something reports, and every reporter shows.
DIAGNOSTICS = 'diagnostics'


class Report:
    """What a verb reports, in the one shape every reporter reads.

    ``tool``: the verb (``nodl validate``), the name of a JUnit test suite;
    ``diagnostics``: what the run found, as it should be reported (overrides
    applied); ``kind``: :data:`DIAGNOSTICS` or the verb's own kind of result;
    ``summary``: the summary line(s) for people (a machine format leaves it
    to standard error); ``text``: the verb's own rendering for people (None:
    the diagnostics, then the summary); ``payload``: the verb's structured
    result, JSON-ready (None: the list of diagnostics); ``cases``: JUnit test
    cases (None: one per file of the diagnostics).  ``text``, ``payload`` and
    ``cases`` may be given as functions that make them: only a reporter that asks
    (:meth:`people_text`, :meth:`json_payload`, :meth:`junit_cases`) pays for them.
    """

    __slots__ = ('tool', 'diagnostics', 'kind', 'summary', 'text', 'payload', 'cases')

    def __init__(self, tool: str, diagnostics: Sequence[Diagnostic] = (), *,
                 kind: str = DIAGNOSTICS, summary: str = '',
                 text: str | Callable[[], str] | None = None,
                 payload: Any = None,
                 cases: Sequence[JUnitCase] | Callable[[], Sequence[JUnitCase]] | None = None
                 ) -> None:
        self.tool = tool
        self.diagnostics: list[Diagnostic] = list(diagnostics)
        self.kind = kind
        self.summary = summary
        self.text = text
        self.payload = payload
        self.cases = cases

    def people_text(self) -> str | None:
        """The verb's own text for people (made now if given as a function), or None."""
        return self.text() if callable(self.text) else self.text

    def json_payload(self) -> Any:
        """The verb's structured result (made now if given as a function), or the list of
        diagnostic objects."""
        payload = self.payload() if callable(self.payload) else self.payload
        return payload if payload is not None else [d.to_dict() for d in self.diagnostics]

    def junit_cases(self) -> Sequence[JUnitCase]:
        """The verb's JUnit test cases (made now if given as a function), or one per file of
        the diagnostics."""
        cases = self.cases() if callable(self.cases) else self.cases
        return cases if cases is not None else cases_by_file(self.diagnostics)


def cases_by_file(diagnostics: Sequence[Diagnostic], strict: bool = False) -> list[JUnitCase]:
    """One JUnit test case per file of ``diagnostics`` (sorted), failed when it holds an error
    (with ``strict``: any diagnostic)."""
    from nodl.reporting.junit import JUnitCase

    by_file: dict[str, list[Diagnostic]] = {}
    for d in diagnostics:
        by_file.setdefault(d.file, []).append(d)
    return [JUnitCase(file, found, any(strict or d.severity is Severity.ERROR for d in found))
            for file, found in sorted(by_file.items())]


class ReporterExtension(ExtensionPoint):
    """Base class of the ``nodl.reporters`` extensions: one output format of every verb."""

    EXTENSION_POINT_VERSION = '1.0'
    #: The media type of what it writes.
    MEDIA_TYPE: str = 'text/plain'
    #: The usual suffix of a file holding it.
    SUFFIX: str = '.txt'
    #: The kinds of result it shows besides diagnostics (``'*'``: every kind).
    KINDS: frozenset[str] = frozenset()
    #: True for a format for people: the report holds the summary; otherwise the verb
    #: writes the summary on standard error, apart from the machine-readable output.
    FOR_PEOPLE: bool = False

    def supports(self, kind: str) -> bool:
        """Whether it can show a result of ``kind``."""
        return kind == DIAGNOSTICS or '*' in self.KINDS or kind in self.KINDS

    def unit(self, diagnostics: Sequence[Diagnostic], header: str | None = None) -> str:
        """What to show as soon as one unit (a file) is done: nothing unless the format
        shows progress (the final :meth:`report` holds everything)."""
        return ''

    def report(self, report: Report) -> str:
        """The whole report of a run."""
        raise NotImplementedError


class TextReporter(ReporterExtension):
    """For people: ``FILE:LINE:COL: severity: message [CODE]`` lines, then the summary."""

    PRIORITY = 400
    KINDS = frozenset({'*'})
    FOR_PEOPLE = True

    def unit(self, diagnostics: Sequence[Diagnostic], header: str | None = None) -> str:
        return (f'{header}\n' if header else '') + format_text(diagnostics)

    def report(self, report: Report) -> str:
        text = report.people_text()
        if text is not None:
            return text
        return format_text(report.diagnostics) + (f'{report.summary}\n' if report.summary else '')


class JsonReporter(ReporterExtension):
    """For tools: the verb's JSON payload, or a JSON array of diagnostic objects."""

    PRIORITY = 300
    MEDIA_TYPE = 'application/json'
    SUFFIX = '.json'
    KINDS = frozenset({'*'})

    def report(self, report: Report) -> str:
        return json.dumps(report.json_payload(), indent=2, default=str) + '\n'


class SarifReporter(ReporterExtension):
    """For code scanning and editors: SARIF 2.1.0, one result per diagnostic."""

    PRIORITY = 200
    MEDIA_TYPE = 'application/sarif+json'
    SUFFIX = '.sarif'

    def report(self, report: Report) -> str:
        from nodl.reporting.sarif import format_sarif

        return format_sarif(report.diagnostics)


class JUnitReporter(ReporterExtension):
    """For continuous integration: JUnit XML, one test case per checked unit."""

    PRIORITY = 100
    MEDIA_TYPE = 'application/xml'
    SUFFIX = '.xml'

    def report(self, report: Report) -> str:
        from nodl.reporting.junit import format_junit

        return format_junit(report.junit_cases(), report.tool)
