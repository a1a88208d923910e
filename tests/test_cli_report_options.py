"""nodl.cli.report_options: the one place the command line turns a verb's results into output."""

from __future__ import annotations

import argparse
import io
import json
from pathlib import Path

import pytest

from nodl.cli import report_options
from nodl.diagnostics import Diagnostic, Severity
from nodl.reporting import format_text
from nodl.reporting.reporters import JsonReporter, Report, TextReporter
from nodl.writing import WriteError

ERROR = Diagnostic(Severity.ERROR, 'bad type', file='a.nodl.yaml', line=3, column=5, code='NODL001')


def test_a_report_goes_on_a_stream_and_a_machine_formats_summary_apart() -> None:
    out, err = io.StringIO(), io.StringIO()
    report = Report('nodl x', [ERROR], summary='1 file, 1 error')
    report_options.write_report(TextReporter(), report, out, err)
    assert (out.getvalue(), err.getvalue()) == (f'{ERROR}\n1 file, 1 error\n', '')
    out, err = io.StringIO(), io.StringIO()
    report_options.write_report(JsonReporter(), report, out, err)
    assert json.loads(out.getvalue()) == [ERROR.to_dict()]
    assert err.getvalue() == '1 file, 1 error\n'


def test_a_report_goes_into_a_file_whole(tmp_path: Path) -> None:
    target = tmp_path / 'report.json'
    err = io.StringIO()
    report_options.write_report(JsonReporter(), Report('nodl x', [ERROR], summary='done'),
                                err=err, path=str(target))
    assert json.loads(target.read_text(encoding='utf-8')) == [ERROR.to_dict()]
    assert err.getvalue() == 'done\n'


def test_a_second_report_is_written_in_a_registered_format(tmp_path: Path) -> None:
    target = tmp_path / 'report.xml'
    report_options.write_report_file('junit', Report('nodl x', [ERROR]), str(target))
    assert target.read_text(encoding='utf-8').startswith('<?xml')
    with pytest.raises(WriteError) as caught:
        report_options.write_report_file('no-such-format', Report('nodl x'), str(tmp_path / 'x'))
    assert caught.value.diagnostic.code == 'NODL030' and not (tmp_path / 'x').exists()


def test_diagnostics_beside_a_document_are_shown_as_text() -> None:
    stream = io.StringIO()
    report_options.show_diagnostics([ERROR], stream)
    assert stream.getvalue() == format_text([ERROR])


def test_the_policy_and_the_reporter_are_asked_once(capsys: pytest.CaptureFixture[str]) -> None:
    asked = report_options.policy_and_reporter(
        argparse.Namespace(format='json', ignore=['NODL001'], error=[]), 'nodl x')
    assert asked is not None
    policy, reporter = asked
    assert isinstance(reporter, JsonReporter) and policy.apply('<string>', [ERROR]) == []
    bad_code = argparse.Namespace(format='json', ignore=['NODL0001'], error=[])
    assert report_options.policy_and_reporter(bad_code, 'nodl x') is None
    bad_format = argparse.Namespace(format='sarif', ignore=[], error=[])
    assert report_options.policy_and_reporter(bad_format, 'nodl x', 'listing') is None
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 2 and lines[0].startswith("nodl x: error: unknown code 'NODL0001'")
    assert lines[1].startswith('nodl x: error: --format sarif: this reporter cannot show a listing')
