"""`nodl params check --format`: the check's report through any registered reporter.

The checks themselves are tested in test_params_check.py; here, that the report goes through
the reporters as every verb's does (JSON, SARIF, JUnit; the summary apart, on standard error),
and that --format belongs to the check.
"""

from __future__ import annotations

import json
import subprocess
import sys
import xml.etree.ElementTree as ET

from conftest import FIXTURES, REPO

EVERYTHING = str(FIXTURES / 'generate' / 'everything.nodl.yaml')
BAD = str(FIXTURES / 'params' / 'bad.params.yaml')
GOOD = str(FIXTURES / 'params' / 'fixed_size' / 'good.yaml')
ARM = str(FIXTURES / 'params' / 'fixed_size' / 'prefix' / 'share' / 'robot' / 'nodl' / 'arm.nodl.yaml')


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    done = subprocess.run([sys.executable, '-m', 'nodl', 'params', *args], cwd=REPO, text=True,
                          capture_output=True, timeout=60)
    assert 'Traceback' not in done.stdout + done.stderr, done.stderr
    return done


def test_json_is_the_diagnostics_and_the_summary_is_apart() -> None:
    done = nodl('check', BAD, '--definition', EVERYTHING, '--format', 'json')
    assert done.returncode == 1
    found = json.loads(done.stdout)
    assert BAD in {d['file'] for d in found}
    assert any(d['code'] == 'NODL702' and d['line'] == 8 for d in found)
    # the summary for the person, apart (after what the definition itself says)
    assert done.stderr.splitlines()[-1] == \
        'nodl params check: 1 parameter file checked: 8 errors, 1 warning'


def test_junit_has_a_test_case_per_parameter_file_clean_ones_too() -> None:
    done = nodl('check', GOOD, '--definition', ARM, '--name', '/arm', '--format', 'junit')
    assert done.returncode == 0, done.stderr
    suite = ET.fromstring(done.stdout)
    assert (suite.get('name'), suite.get('tests'), suite.get('failures')) == \
        ('nodl params check', '1', '0')
    assert [case.get('name') for case in suite.iter('testcase')] == [GOOD]
    assert done.stderr == 'nodl params check: 1 parameter file checked: no errors\n'


def test_sarif_has_a_result_per_diagnostic() -> None:
    done = nodl('check', BAD, '--definition', EVERYTHING, '--format', 'sarif')
    results = json.loads(done.stdout)['runs'][0]['results']
    assert 'NODL702' in {r['ruleId'] for r in results}


def test_format_belongs_to_the_check() -> None:
    done = nodl(EVERYTHING, '--format', 'json')
    assert done.returncode == 2 and done.stdout == ''
    assert done.stderr == 'nodl params: error: --format belongs to "nodl params check"\n'
