"""Rendering diagnostics (nodl_schema.reporting)."""

from __future__ import annotations

import json

from nodl_schema.diagnostics import Diagnostic, Severity
from nodl_schema.reporting import Tally, format_json, format_text, summary_line

D1 = Diagnostic(Severity.ERROR, 'bad type', ('main', 'publishers', 0, 'type'), 'a.yaml', 4, 11)
D2 = Diagnostic(Severity.WARNING, 'no description', ('parameters', 'pid.kp'), 'a.yaml', 2, 3, 'key')


def test_text_is_one_compiler_style_line_per_diagnostic() -> None:
    assert format_text([D1, D2]) == (
        'a.yaml:4:11: error: bad type [main.publishers[0].type]\n'
        'a.yaml:2:3: warning: no description [parameters["pid.kp"]]\n')


def test_json_objects_have_the_documented_fields() -> None:
    data = json.loads(format_json([D1]))
    assert data == [{'file': 'a.yaml', 'line': 4, 'column': 11, 'path': 'main.publishers[0].type',
                     'severity': 'error', 'code': '', 'message': 'bad type', 'related': []}]


def test_summary_counts_and_plurals() -> None:
    tally = Tally()
    tally.files = 1
    tally.add([D1, D2, D2])
    assert summary_line(tally) == '1 file, 1 error, 2 warnings'
    assert summary_line(Tally()) == '0 files, 0 errors, 0 warnings'
