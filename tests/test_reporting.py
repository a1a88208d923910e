"""Rendering diagnostics (nodl.reporting)."""

from __future__ import annotations

import json

from nodl.diagnostics import Diagnostic, Severity
from nodl.reporting import Tally, format_json, format_text, summary_line

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


def test_sarif_is_a_2_1_0_log_with_one_rule_per_code(tmp_path, monkeypatch) -> None:
    from nodl.codes import CODES
    from nodl.reporting.sarif import sarif_log

    monkeypatch.chdir(tmp_path)
    (tmp_path / 'a b.yaml').write_text('x: 1\n', encoding='utf-8')
    first = Diagnostic(Severity.ERROR, 'bad', ('main', 'x'), 'a b.yaml', 4, 11, code='NODL101',
                       related=[('a b.yaml', 2, 3, 'the earlier one')])
    second = Diagnostic(Severity.INFO, 'note', (), 'a b.yaml', 0, 0, code='NODL304')
    third = Diagnostic(Severity.WARNING, 'again', (), '<stdin>', 1, 1, code='NODL101')
    log = sarif_log([first, second, third])
    assert log['version'] == '2.1.0' and log['$schema'].endswith('sarif-2.1.0.json')
    [run] = log['runs']
    driver = run['tool']['driver']
    assert driver['name'] == 'nodl' and driver['version'] and driver['informationUri']
    assert [r['id'] for r in driver['rules']] == ['NODL101', 'NODL304']
    assert driver['rules'][1] == {'id': 'NODL304', 'shortDescription': {'text': CODES['NODL304'][1]},
                                  'defaultConfiguration': {'level': 'note'}}
    assert run['originalUriBaseIds']['SRCROOT']['uri'].startswith('file:///')
    assert run['originalUriBaseIds']['SRCROOT']['uri'].endswith('/')
    one, two, three = run['results']
    assert (one['ruleId'], one['ruleIndex'], one['level'], one['message']) == (
        'NODL101', 0, 'error', {'text': 'bad'})
    physical = one['locations'][0]['physicalLocation']
    assert physical == {'artifactLocation': {'uri': 'a%20b.yaml', 'uriBaseId': 'SRCROOT'},
                        'region': {'startLine': 4, 'startColumn': 11}}
    assert one['locations'][0]['logicalLocations'] == [{'fullyQualifiedName': 'main.x'}]
    assert one['relatedLocations'][0]['physicalLocation']['region'] == {'startLine': 2,
                                                                        'startColumn': 3}
    assert one['relatedLocations'][0]['message'] == {'text': 'the earlier one'}
    # an unknown position has no region (SARIF positions start at 1); <stdin> is not a file
    assert 'region' not in two['locations'][0]['physicalLocation'] and two['level'] == 'note'
    assert 'locations' not in three and three['level'] == 'warning'
    for result in run['results']:
        assert set(result) <= {'ruleId', 'ruleIndex', 'level', 'message', 'locations',
                               'relatedLocations'}


def test_sarif_from_the_command_line_is_json_with_a_summary_on_stderr() -> None:
    import subprocess
    import sys
    from pathlib import Path

    repo = Path(__file__).resolve().parent.parent
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--format', 'sarif',
                             'examples/mistakes/typos.yaml'], cwd=repo, capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 1
    log = json.loads(result.stdout)
    results = log['runs'][0]['results']
    assert len(results) == 7 and all(r['ruleId'].startswith('NODL') for r in results)
    assert result.stderr == '1 file, 7 errors, 0 warnings\n'


def test_sarif_of_validate_has_the_shape_sarif_2_1_0_defines(tmp_path) -> None:
    """Every object the standard allows and nothing else, for a log with related locations,
    standard input, an unreadable path and relative and absolute files."""
    import subprocess
    import sys
    from pathlib import Path

    from sarif_shape import assert_sarif_2_1_0

    repo = Path(__file__).resolve().parent.parent
    overrides = repo / 'tests' / 'fixtures' / 'composition' / 'overrides'
    result = subprocess.run(
        [sys.executable, '-m', 'nodl', 'validate', '--resolve', '--format', 'sarif',
         'examples/mistakes/', str(overrides / 'base_redefined.nodl.yaml'),
         str(tmp_path / 'missing.nodl.yaml'), '-'],
        cwd=repo, capture_output=True, text=True, timeout=60, input='nodl_version: 2\nx: 1\n')
    assert result.returncode == 2, result.stderr  # the missing path
    log = json.loads(result.stdout)
    assert_sarif_2_1_0(log)
    results = log['runs'][0]['results']
    assert any('relatedLocations' in r for r in results)
    assert {r['ruleId'] for r in results} >= {'NODL020', 'NODL101', 'NODL307'}
    uris = {r['locations'][0]['physicalLocation']['artifactLocation']['uri']
            for r in results if 'locations' in r and 'physicalLocation' in r['locations'][0]}
    assert any(u.startswith('file:///') for u in uris) and any(u.startswith('examples/') for u in uris)


def test_the_sarif_shape_check_rejects_what_the_standard_rejects() -> None:
    import copy
    from typing import Any

    import pytest

    from nodl.reporting.sarif import sarif_log
    from sarif_shape import assert_sarif_2_1_0

    good = sarif_log([D1.replace(code='NODL101'), D2.replace(code='NODL216')])
    assert_sarif_2_1_0(good)

    def broken(change: Any) -> dict[str, Any]:
        log = copy.deepcopy(good)
        change(log['runs'][0])
        return log

    for bad in (broken(lambda run: run['results'][0].update(severity='error')),  # not a SARIF key
                broken(lambda run: run['results'][0].update(level='info')),  # SARIF says note
                broken(lambda run: run['tool']['driver'].pop('name')),
                broken(lambda run: run['results'][0].pop('message')),
                broken(lambda run: run['results'][0].update(ruleIndex=5)),
                broken(lambda run: run['tool']['driver']['rules'].append(
                    run['tool']['driver']['rules'][0]))):
        with pytest.raises(AssertionError):
            assert_sarif_2_1_0(bad)


def test_junit_escapes_what_documents_hold() -> None:
    import xml.etree.ElementTree as ElementTree

    from nodl.reporting.junit import JUnitCase, format_junit

    hostile = Diagnostic(Severity.ERROR, 'bad <key> & "quote"\x01\x1b[31m', (), 'a&b.yaml', 1, 2,
                         code='NODL101')
    text = format_junit([JUnitCase('a&b.yaml', [hostile], True),
                         JUnitCase('ok.yaml', [], False),
                         JUnitCase('gone.yaml', [hostile.replace(message='cannot be read')], True, True)],
                        'suite <x>')
    suite = ElementTree.fromstring(text)  # well-formed although the message held control characters
    assert (suite.get('name'), suite.get('tests'), suite.get('failures'), suite.get('errors')) == \
        ('suite <x>', '3', '1', '1')
    failure = suite.find("testcase[@name='a&b.yaml']/failure")
    assert failure is not None and 'bad <key> & "quote"\\x01\\x1b[31m' in (failure.text or '')
    assert suite.find("testcase[@name='ok.yaml']/failure") is None
    assert suite.find("testcase[@name='gone.yaml']/error").get('message') == 'cannot be read'  # type: ignore[union-attr]


def test_junit_and_sarif_show_control_and_bidi_characters() -> None:
    import xml.etree.ElementTree as ET

    from nodl.reporting.junit import _attribute, _text
    from nodl.reporting.sarif import format_sarif

    hostile = 'evil \u202e \x1b[2J \x00 end'
    element = ET.fromstring(f'<f m={_attribute(hostile)}>{_text(hostile)}</f>')
    assert element.text == element.get('m') == 'evil \\u202e \\x1b[2J \\x00 end'
    sarif = json.loads(format_sarif([Diagnostic(Severity.ERROR, hostile, (), 'x.yaml', 1, 1, code='NODL219')]))
    assert sarif['runs'][0]['results'][0]['message']['text'] == 'evil \\u202e \\x1b[2J \\x00 end'
