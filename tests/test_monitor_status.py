"""Statuses: level, one-line message, key-values, the DiagnosticStatus and the reports."""

from __future__ import annotations

import json

from nodl.monitor.checks import Finding
from nodl.monitor.status import Status, format_junit, format_text, jsonl_line, to_message


def status() -> Status:
    return Status('nodl: /s', 'pkg/exe', [
        Finding('NODL408', 'info', 'unverifiable', 'cannot be verified: x'),
        Finding('NODL436', 'warning', 'rate /s/data', 'slow'),
        Finding('NODL553', 'error', 'topic /t', 'incompatible')], [('state', 'running')])


def test_level_message_and_values() -> None:
    s = status()
    assert (s.level, s.level_name) == (2, 'ERROR')
    assert s.message == 'incompatible (and 1 more)'
    assert s.values() == [('codes', 'NODL553,NODL436,NODL408'), ('NODL553 topic /t', 'incompatible'),
                          ('NODL436 rate /s/data', 'slow'),
                          ('NODL408 unverifiable', 'cannot be verified: x'), ('state', 'running')]
    assert Status('nodl: /q', 'p/e', [Finding('NODL408', 'info', 'u', 'i')]).level_name == 'OK'


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
    assert 'failures="1"' in format_junit([status()])
