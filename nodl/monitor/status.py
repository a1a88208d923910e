"""Statuses: one per expected node (``nodl: <final name>``) and one for the system
(``nodl: system``), as ``diagnostic_msgs/DiagnosticStatus`` and as reports.

A status's level is the worst of its findings (info OK, warning WARN, error ERROR); STALE
is never published (it belongs to the aggregator).  Its message is one line: the worst
finding's, with how many more there are.  Its key-values are ``codes`` (the codes of its
findings, comma-separated), one ``<CODE> <subject>`` key per finding with its message,
then facts (``state``, ``definition``, ``instances``, ``restarts``, measured rates).
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from nodl.composition.entities import Location
from nodl.diagnostics import Diagnostic
from nodl.monitor.checks import StatusFinding

if TYPE_CHECKING:
    from nodl.reporting.reporters import Report

__all__ = ['Status', 'SYSTEM', 'PREFIX', 'LEVEL_NAMES', 'status_name', 'to_message',
           'format_text', 'jsonl_line', 'diagnostics_of', 'monitor_report']

#: What every status name starts with.
PREFIX = 'nodl: '
#: The name of the system's status.
SYSTEM = PREFIX + 'system'
LEVEL_NAMES = {0: 'OK', 1: 'WARN', 2: 'ERROR'}


def status_name(fqn: str) -> str:
    """The status name of the node ``fqn``: ``nodl: /ns/node``."""
    return PREFIX + fqn


@dataclass
class Status:
    """One status: its name, hardware id, findings and facts."""

    name: str
    hardware_id: str
    findings: list[StatusFinding] = field(default_factory=list)
    #: Facts shown as key-values after the findings (``state``, ``definition``...).
    facts: list[tuple[str, str]] = field(default_factory=list)
    #: The message when there is no finding (``running``, ``waiting``...).
    ok_message: str = 'OK'
    #: Where findings without a location of their own point (launch entry, definition).
    location: Location | None = None

    @property
    def level(self) -> int:
        """The worst level of its findings (0 OK, 1 WARN, 2 ERROR)."""
        return max((f.level for f in self.findings), default=0)

    @property
    def level_name(self) -> str:
        """``OK``, ``WARN`` or ``ERROR``."""
        return LEVEL_NAMES[self.level]

    @property
    def codes(self) -> list[str]:
        """The codes of its findings, in order, each once."""
        return list(dict.fromkeys(f.code for f in self.ordered()))

    def ordered(self) -> list[StatusFinding]:
        """Its findings, the worst first."""
        return sorted(self.findings, key=lambda f: (-f.level, f.code, f.subject))

    @property
    def message(self) -> str:
        """One line: the worst finding's message (and how many more), else ``ok_message``."""
        shown = [f for f in self.ordered() if f.level > 0]
        if not shown:
            return self.ok_message
        first = shown[0].message.replace('\n', ' ')
        return first + (f' (and {len(shown) - 1} more)' if len(shown) > 1 else '')

    def values(self) -> list[tuple[str, str]]:
        """The key-values: ``codes``, one per finding, then the facts."""
        out = [('codes', ','.join(self.codes))]
        seen: set[str] = set()
        for finding in self.ordered():
            key = f'{finding.code} {finding.subject}'
            base, n = key, 2
            while key in seen:
                key, n = f'{base} #{n}', n + 1
            seen.add(key)
            out.append((key, finding.message))
        return out + list(self.facts)

    def signature(self) -> tuple[Any, ...]:
        """What a change of which is published at once: the level and the findings' keys."""
        return self.level, tuple(sorted(f.key for f in self.findings))

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping."""
        return {'name': self.name, 'hardware_id': self.hardware_id, 'level': self.level_name,
                'message': self.message, 'codes': self.codes,
                'findings': [{'code': f.code, 'severity': f.severity, 'subject': f.subject,
                              'message': f.message} for f in self.ordered()],
                'values': dict(self.values())}


def to_message(status: Status) -> Any:
    """The status as a ``diagnostic_msgs/msg/DiagnosticStatus``."""
    from diagnostic_msgs.msg import DiagnosticStatus, KeyValue  # type: ignore[import-untyped]

    return DiagnosticStatus(level=bytes([status.level]), name=status.name,
                            message=status.message, hardware_id=status.hardware_id,
                            values=[KeyValue(key=k, value=v) for k, v in status.values()])


def jsonl_line(status: Status, when: float) -> str:
    """One JSON line for a change of level: ``{"time", "status", "level", "message",
    "codes"}`` (``time``: ISO 8601, UTC, milliseconds)."""
    import datetime

    stamp = datetime.datetime.fromtimestamp(when, datetime.timezone.utc)
    return json.dumps({'time': stamp.isoformat(timespec='milliseconds').replace('+00:00', 'Z'),
                       'status': status.name, 'level': status.level_name,
                       'message': status.message, 'codes': status.codes})


def diagnostics_of(statuses: Iterable[Status], verbose: bool = False) -> list[Diagnostic]:
    """Every finding of ``statuses`` as a diagnostic (infos only if ``verbose``), placed at
    its location or its status's."""
    out: list[Diagnostic] = []
    for status in statuses:
        for finding in status.ordered():
            if finding.severity == 'info' and not verbose:
                continue
            d = finding.diagnostic(status.location)
            subject = status.name[len(PREFIX):]
            out.append(d.replace(message=f'{subject}: {d.message}'))
    return out


def format_text(statuses: list[Status], verbose: bool = False, note: str = '') -> str:
    """The ``--once`` report for people: one line per status (level, name, message), then
    every finding as ``FILE:LINE:COL: severity: message [CODE]``, then a summary."""
    lines = [f'{s.level_name:<5} {s.name[len(PREFIX):]}: {s.message}' for s in statuses]
    diagnostics = diagnostics_of(statuses, verbose)
    if diagnostics:
        lines.append('')
        lines += [str(d) for d in diagnostics]
    counts = {name: sum(1 for s in statuses if s.level_name == name)
              for name in ('OK', 'WARN', 'ERROR')}
    lines.append('')
    if note:
        lines.append(note)
    lines.append(f"{len(statuses)} statuses: {counts['OK']} OK, {counts['WARN']} WARN, "
                 f"{counts['ERROR']} ERROR")
    return '\n'.join(lines) + '\n'


def monitor_report(statuses: list[Status], verbose: bool = False, note: str = '') -> Report:
    """The ``--once`` report as every reporter (``nodl.reporters``) renders it: every finding
    as a diagnostic (SARIF), the statuses and ``note`` as the JSON payload
    (``{"statuses": [...], "note": ...}``), a test case per status, failed when ERROR
    (JUnit), and :func:`format_text` for people."""
    from nodl.reporting.junit import JUnitCase
    from nodl.reporting.reporters import Report

    return Report('nodl monitor', diagnostics_of(statuses, True),
                  text=lambda: format_text(statuses, verbose, note),
                  payload={'statuses': [s.to_dict() for s in statuses], 'note': note},
                  cases=lambda: [JUnitCase(s.name, diagnostics_of([s], True), s.level == 2)
                                 for s in statuses])
