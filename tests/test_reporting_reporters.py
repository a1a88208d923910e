"""Output formats as extensions (nodl.reporting.reporters): the built-ins and a plug-in format."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl import plugins
from nodl.diagnostics import Diagnostic, Severity
from nodl.reporting.junit import JUnitCase, JUnitFailure
from nodl.reporting.reporters import (
    GROUP,
    JsonReporter,
    JUnitReporter,
    Report,
    ReporterExtension,
    SarifReporter,
    TextReporter,
    cases_by_file,
)

ERROR = Diagnostic(Severity.ERROR, 'bad type', file='a.nodl.yaml', line=3, column=5, code='NODL001')
WARNING = Diagnostic(Severity.WARNING, 'unused', file='b.nodl.yaml', line=1, column=1, code='NODL002')
INVALID = FIXTURES / 'invalid' / 'duplicate_endpoints.nodl.yaml'


def test_the_builtin_formats_are_registered_as_plugins_are() -> None:
    loaded = plugins.load_plugins(GROUP)
    assert {name: cls for name, cls in loaded.items()} == {
        'text': TextReporter, 'json': JsonReporter, 'sarif': SarifReporter, 'junit': JUnitReporter}
    assert all(issubclass(cls, ReporterExtension) for cls in loaded.values())
    assert list(loaded) == ['text', 'json', 'sarif', 'junit']  # by priority


def test_text_is_the_diagnostics_then_the_summary_unless_the_verb_gives_its_own() -> None:
    report = Report('nodl x', [ERROR], summary='1 file, 1 error')
    assert TextReporter().report(report) == f'{ERROR}\n1 file, 1 error\n'
    assert TextReporter().report(Report('nodl x', [ERROR], text='own\n')) == 'own\n'
    assert TextReporter().unit([WARNING], 'b.nodl.yaml: valid node definition') == \
        f'b.nodl.yaml: valid node definition\n{WARNING}\n'
    assert JsonReporter().unit([WARNING]) == ''  # a machine format shows it all at the end


def test_json_is_the_verbs_payload_or_the_diagnostics() -> None:
    assert json.loads(JsonReporter().report(Report('nodl x', [ERROR]))) == [ERROR.to_dict()]
    payload = {'nodes': [{'name': '/a'}], 'findings': []}
    assert JsonReporter().report(Report('nodl x', [ERROR], payload=payload)) == \
        json.dumps(payload, indent=2) + '\n'


def test_sarif_has_one_result_per_diagnostic() -> None:
    log = json.loads(SarifReporter().report(Report('nodl x', [ERROR, WARNING])))
    assert [r['ruleId'] for r in log['runs'][0]['results']] == ['NODL001', 'NODL002']


def test_junit_has_a_case_per_file_or_the_verbs_own_cases() -> None:
    assert cases_by_file([WARNING, ERROR]) == [JUnitCase('a.nodl.yaml', [ERROR], True),
                                               JUnitCase('b.nodl.yaml', [WARNING], False)]
    assert cases_by_file([WARNING], strict=True)[0].failed
    suite = ET.fromstring(JUnitReporter().report(Report('nodl x', [ERROR, WARNING])))
    assert (suite.get('name'), suite.get('tests'), suite.get('failures')) == ('nodl x', '2', '1')
    own = JUnitCase('~/scan', [], True, classname='subscribers',
                    failures=[JUnitFailure('type', 'declared a', 'error: type: declared a')],
                    output=['warning: qos'])
    text = JUnitReporter().report(Report('nodl x', cases=[own]))
    case = ET.fromstring(text).find('testcase')
    assert case is not None and case.get('classname') == 'subscribers'
    failure = case.find('failure')
    assert failure is not None and (failure.get('type'), failure.text) == ('type', 'error: type: declared a')
    assert case.findtext('system-out') == 'warning: qos'


def test_every_reporter_shows_diagnostics_and_kinds_it_names() -> None:
    assert SarifReporter().supports('diagnostics') and not SarifReporter().supports('listing')
    assert TextReporter().supports('listing') and JsonReporter().supports('listing')


# --------------------------------------------------------------------------
# A plug-in format, installed by a real pip install, offered by every verb

GITHUB = FIXTURES / 'plugins' / 'github_reporter'


@pytest.fixture(scope='module')
def github_site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp('github')
    shutil.copytree(GITHUB, root / 'source')
    target = root / 'site'
    result = subprocess.run(
        [sys.executable, '-m', 'pip', 'install', '--no-deps', '--no-build-isolation', '--no-index',
         '--disable-pip-version-check', '--target', str(target), str(root / 'source')],
        cwd=root, text=True, capture_output=True, timeout=180,
        env={k: v for k, v in os.environ.items() if k != 'PIP_REQUIRE_VIRTUALENV'})
    assert result.returncode == 0, result.stdout + result.stderr
    return target


def _nodl(site: Path, *args: str, **env: str) -> subprocess.CompletedProcess[str]:
    environment = dict(os.environ, PYTHONPATH=str(site), **env)
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, env=environment,
                          text=True, capture_output=True, timeout=60)


def test_a_plugin_format_is_offered_and_used_by_the_verbs(github_site: Path) -> None:
    validated = _nodl(github_site, 'validate', '--format', 'github', str(INVALID))
    assert validated.returncode == 1, validated.stderr
    assert validated.stdout.startswith(f'::error file={INVALID},line=')
    assert 'title=NODL' in validated.stdout
    assert '1 file, ' in validated.stderr  # the summary for the person, apart
    helped = _nodl(github_site, 'analyse', '--help')
    assert 'github' in helped.stdout
    analysed = _nodl(github_site, 'analyse', '--format', 'github',
                     str(FIXTURES / 'analysis' / 'launch' / 'checks.launch.xml'))
    assert analysed.stdout.startswith('::'), analysed.stdout + analysed.stderr


def test_a_verb_offers_only_the_formats_that_can_show_its_result(github_site: Path) -> None:
    listed = _nodl(github_site, 'list', '--format', 'github')
    assert listed.returncode == 2 and "invalid choice: 'github'" in listed.stderr
    assert 'github' not in _nodl(github_site, 'list', '--help').stdout


def test_a_blocked_or_broken_format_is_a_usage_error_in_one_line(github_site: Path) -> None:
    blocked = _nodl(github_site, 'validate', '--format', 'github', str(INVALID),
                    NODL_EXTENSION_BLOCKLIST='nodl.reporters.github')
    assert blocked.returncode == 2 and "invalid choice: 'github'" in blocked.stderr
    assert 'Traceback' not in blocked.stderr


def test_what_a_format_does_not_show_is_never_made() -> None:
    def never() -> object:
        raise AssertionError('made for a format that does not show it')

    report = Report('nodl x', [ERROR], summary='s', payload=never, cases=never)  # type: ignore[arg-type]
    assert TextReporter().report(report) == f'{ERROR}\ns\n'
    lazy = Report('nodl x', [ERROR], text=never, payload=lambda: {'a': 1})  # type: ignore[arg-type]
    assert json.loads(JsonReporter().report(lazy)) == {'a': 1}
