"""Statuses: level, one-line message, key-values, the DiagnosticStatus and the reports."""

from __future__ import annotations

import json

from nodl.monitor.checks import StatusFinding
from nodl.monitor.status import Status, format_text, jsonl_line, monitor_report, to_message
from nodl.reporting.reporters import JsonReporter, JUnitReporter, SarifReporter, TextReporter


def status() -> Status:
    return Status('nodl: /s', 'pkg/exe', [
        StatusFinding('NODL408', 'info', 'unverifiable', 'cannot be verified: x'),
        StatusFinding('NODL436', 'warning', 'rate /s/data', 'slow'),
        StatusFinding('NODL553', 'error', 'topic /t', 'incompatible')], [('state', 'running')])


def test_level_message_and_values() -> None:
    s = status()
    assert (s.level, s.level_name) == (2, 'ERROR')
    assert s.message == 'incompatible (and 1 more)'
    assert s.values() == [('codes', 'NODL553,NODL436,NODL408'), ('NODL553 topic /t', 'incompatible'),
                          ('NODL436 rate /s/data', 'slow'),
                          ('NODL408 unverifiable', 'cannot be verified: x'), ('state', 'running')]
    assert Status('nodl: /q', 'p/e', [StatusFinding('NODL408', 'info', 'u', 'i')]).level_name == 'OK'


def test_diagnostic_status_message_never_stale() -> None:
    message = to_message(status())
    assert message.level == bytes([2]) and message.name == 'nodl: /s'
    assert message.hardware_id == 'pkg/exe' and message.values[0].value == 'NODL553,NODL436,NODL408'


def test_jsonl_and_reports() -> None:
    line = json.loads(jsonl_line(status(), 0.0))
    assert line == {'time': '1970-01-01T00:00:00.000Z', 'status': 'nodl: /s', 'level': 'ERROR',
                    'message': 'incompatible (and 1 more)', 'codes': ['NODL553', 'NODL436', 'NODL408']}
    text = format_text([status()])
    assert text.startswith('ERROR /s: incompatible (and 1 more)\n')
    assert '<graph>: error: /s: incompatible [NODL553]' in text and 'NODL408' not in text
    # every format through the reporters, as the verb renders the report --format names
    report = monitor_report([status()], note='interrupted')
    assert TextReporter().report(report) == format_text([status()], note='interrupted')
    assert 'failures="1"' in JUnitReporter().report(report)
    data = json.loads(JsonReporter().report(report))
    assert data['note'] == 'interrupted' and [s['level'] for s in data['statuses']] == ['ERROR']
    sarif = json.loads(SarifReporter().report(report))
    assert {r['ruleId'] for r in sarif['runs'][0]['results']} == {'NODL553', 'NODL436', 'NODL408'}
