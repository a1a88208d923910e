"""`nodl check` as users run it: exit codes, text, JSON and JUnit output, real processes."""

from __future__ import annotations

import copy
import json
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from conftest import REPO, NodeProcess
from nodl import dump_nodl
from nodl.live.describe import describe_node, render_description


def nodl(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """Run `python -m nodl` (it inherits ROS_DOMAIN_ID and the loopback-only discovery)."""
    result = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                            capture_output=True, timeout=timeout)
    assert 'Traceback' not in result.stdout + result.stderr, result.stderr
    return result


@pytest.fixture(scope='module')
def full() -> Iterator[NodeProcess]:
    node = NodeProcess('full_node.py', 'full', '/cli_c')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def files(full: NodeProcess, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The node's own description, and a copy that drifts from it."""
    folder = tmp_path_factory.mktemp('cli_check')
    description = describe_node(full.fqn, timeout=15)
    good = folder / 'full.nodl.yaml'
    good.write_text(render_description(description), encoding='utf-8')
    definition: dict[str, Any] = copy.deepcopy(description.definition)
    main = definition['main']
    main['publishers'] = [e for e in main['publishers'] if e['name'] != 'measurement']
    next(e for e in main['subscriptions'] if e['name'] == 'commands')['type'] = 'std_msgs/msg/Int32'
    next(e for e in main['publishers'] if e['name'] == '~/status')['qos']['durability'] = 'VOLATILE'
    drifting = folder / 'drifting.nodl.yaml'
    drifting.write_text(dump_nodl(definition, 'yaml'), encoding='utf-8')
    # conforms, with one warning: the current gain (0.5) breaks a validator
    valued: dict[str, Any] = copy.deepcopy(description.definition)
    valued['main']['parameters']['gain'].update(default_value=0.7,
                                                validation={'bounds<>': [0.6, 1.0]})
    value = folder / 'value.nodl.yaml'
    value.write_text(dump_nodl(valued, 'yaml'), encoding='utf-8')
    return {'good': good, 'drifting': drifting, 'value': value}


def test_conforming_node_exits_0(files: dict[str, Path]) -> None:
    result = nodl('check', '/cli_c/full', str(files['good']), '--timeout', '15')
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.splitlines()[-1].startswith(f'/cli_c/full conforms to {files["good"]} (')
    assert 'listed with -v' in result.stdout
    assert result.stderr == ''


def test_drift_exits_1_with_text_and_junit(files: dict[str, Path], tmp_path: Path) -> None:
    junit = tmp_path / 'report.xml'
    result = nodl('check', '/cli_c/full', str(files['drifting']), '--timeout', '15', '-v',
                  '--junit', str(junit))
    assert result.returncode == 1, result.stderr
    lines = result.stdout.splitlines()
    assert "/cli_c/full: error: extra: publisher '/cli_c/measurement' (std_msgs/msg/Float64) is " \
           'observed but not declared [NODL402]' in lines
    assert "/cli_c/full: error: type: subscription '/cli_c/commands': declared type " \
           'std_msgs/msg/Int32, observed std_msgs/msg/String (declared in main) [NODL403]' in lines
    assert any(line.startswith("/cli_c/full: error: qos: publisher '/cli_c/full/status' durability: "
                               'declared VOLATILE, observed TRANSIENT_LOCAL') for line in lines)
    assert any(': info: unverifiable: ' in line for line in lines)  # -v
    assert re.fullmatch(r'/cli_c/full drifts from .*drifting\.nodl\.yaml: 3 differences '
                        r'\(\d+ unverifiable\)', lines[-1])

    suite = ET.parse(junit).getroot()
    assert suite.tag == 'testsuite' and suite.get('name') == 'nodl check /cli_c/full'
    assert suite.get('failures') == '3' and suite.get('errors') == '0'
    failed = {(c.get('classname'), c.get('name')): [f.get('type') for f in c.iter('failure')]
              for c in suite.iter('testcase')}
    assert failed[('publishers', '~/status')] == ['qos']
    assert failed[('subscriptions', 'commands')] == ['type']
    assert failed[('publishers', '/cli_c/measurement')] == ['extra']
    assert failed[('subscriptions', '/emergency_stop')] == []
    assert int(suite.get('tests')) == len(failed)


def test_drift_as_json(files: dict[str, Path]) -> None:
    result = nodl('check', '/cli_c/full', str(files['drifting']), '--format', 'json',
                  '--timeout', '15')
    assert result.returncode == 1, result.stderr
    data = json.loads(result.stdout)
    assert data['node'] == '/cli_c/full'
    assert data['definition'] == str(files['drifting'])
    assert data['conforms'] is False
    errors = sorted((d['kind'], d['name']) for d in data['differences'] if d['severity'] == 'error')
    assert errors == [('extra', '/cli_c/measurement'), ('qos', '/cli_c/full/status'),
                      ('type', '/cli_c/commands')]
    assert {d['severity'] for d in data['differences']} == {'error', 'info'}
    assert set(data['differences'][0]) == {'kind', 'code', 'severity', 'section', 'name',
                                           'declared', 'observed', 'layer', 'message',
                                           'file', 'line', 'column', 'related'}
    assert data['ignored'] == 0
    commands = next(d for d in data['differences'] if d['kind'] == 'type')
    assert (commands['code'], commands['file'], commands['line']) == (
        'NODL403', str(files['drifting']), _line_of(files['drifting'], 'name: commands'))
    assert result.stderr.splitlines()[-1].startswith('/cli_c/full drifts from ')  # the verdict


def test_node_not_found_exits_2_within_the_timeout(files: dict[str, Path]) -> None:
    start = time.monotonic()
    result = nodl('check', '/cli_c/nobody', str(files['good']), '--timeout', '1.5')
    elapsed = time.monotonic() - start
    assert result.returncode == 2
    assert result.stdout == ''
    assert result.stderr.startswith("nodl check: error: node '/cli_c/nobody' was not found within "
                                    '1.5 s')
    assert elapsed < 1.5 + 5


def test_invalid_definition_exits_2_with_file_line_col(tmp_path: Path) -> None:
    bad = tmp_path / 'bad.nodl.yaml'
    bad.write_text('nodl_version: 2\nmain:\n  nodl_version: 2\n  publishers:\n'
                   '    - name: ~/x\n      type: std_msgs/msg/String\n      qos: {depth: 1}\n',
                   encoding='utf-8')
    result = nodl('check', '/cli_c/full', str(bad), '--timeout', '30')
    assert result.returncode == 2
    assert result.stdout == ''
    errors = [line for line in result.stderr.splitlines() if ': error: ' in line]
    assert errors
    assert all(re.match(re.escape(str(bad)) + r':\d+:\d+: error: ', line) for line in errors), errors


def test_unregistered_package_exits_2(tmp_path: Path) -> None:
    result = nodl('check', '/cli_c/full', 'no_such_pkg_xyz', 'some_exe', '--timeout', '30')
    assert result.returncode == 2
    assert 'no_such_pkg_xyz' in result.stderr
    assert result.stdout == ''


@pytest.mark.parametrize('args, message', [
    (['/cli_c/full', 'a', 'b', 'c'], 'expected FILE or PACKAGE EXECUTABLE'),
    (['/cli_c/full', str(REPO / 'tests' / 'fixtures' / 'live' / 'drive_node.nodl.yaml'),
      '--remap', 'commands'], "invalid remapping 'commands'"),
])
def test_usage_errors_exit_2(args: list[str], message: str) -> None:
    result = nodl('check', *args, '--timeout', '30')
    assert result.returncode == 2
    assert message in result.stderr


def test_missing_definition_file_is_an_io_error_not_a_crash(tmp_path: Path) -> None:
    result = nodl('check', '/whatever', str(tmp_path / 'missing.nodl.yaml'), '--timeout', '1')
    assert result.returncode == 2
    assert 'cannot read the definition' in result.stderr
    assert 'missing.nodl.yaml' in result.stderr
    assert 'internal error' not in result.stderr and 'Traceback' not in result.stderr


def test_client_library_option_and_statement(files: dict[str, Path]) -> None:
    default = nodl('check', '/cli_c/full', str(files['good']), '--timeout', '15')
    assert default.stdout.splitlines()[0] == (
        '/cli_c/full: client library: rclpy (the default; choose with --client-library)')
    # full_node is an rclpy node: as rclcpp it lacks the time source's subscription
    cpp = nodl('check', '/cli_c/full', str(files['good']), '--timeout', '15',
               '--client-library', 'rclcpp', '--format', 'json')
    assert cpp.returncode == 1, cpp.stdout + cpp.stderr
    data = json.loads(cpp.stdout)
    assert data['client_library'] == {'name': 'rclcpp', 'reason': 'as requested'}
    assert [(d['kind'], d['name'], d['layer']) for d in data['differences']
            if d['severity'] == 'error'] == [('missing', '/parameter_events', 'base:node')]


# -- coded diagnostics: SARIF, --ignore / --error, nodl.toml and [tool.nodl] -------------------


def _line_of(path: Path, text: str) -> int:
    """The 1-based number of the only line of ``path`` that contains ``text``."""
    found = [n for n, line in enumerate(path.read_text(encoding='utf-8').splitlines(), 1)
             if text in line]
    assert len(found) == 1, (text, found)
    return found[0]


def test_drift_as_sarif(files: dict[str, Path]) -> None:
    result = nodl('check', '/cli_c/full', str(files['drifting']), '--format', 'sarif',
                  '--timeout', '15')
    assert result.returncode == 1, result.stderr
    log = json.loads(result.stdout)
    assert log['version'] == '2.1.0' and log['$schema'].endswith('sarif-2.1.0.json')
    from sarif_shape import assert_sarif_2_1_0

    assert_sarif_2_1_0(log)
    run, = log['runs']
    rules = [r['id'] for r in run['tool']['driver']['rules']]
    assert len(rules) == len(set(rules))  # one rule per code
    errors = {r['ruleId']: r for r in run['results'] if r['level'] == 'error'}
    assert sorted(errors) == ['NODL402', 'NODL403', 'NODL404']
    assert {r['level'] for r in run['results']} == {'error', 'note'}  # unverifiable: notes
    for found in run['results']:
        assert rules[found['ruleIndex']] == found['ruleId']
        assert found['message']['text'].startswith('/cli_c/full: ')
        region = found['locations'][0]['physicalLocation']['region']
        assert region['startLine'] > 0 and region['startColumn'] > 0
    where = {code: (r['locations'][0]['physicalLocation']['artifactLocation']['uri'],
                    r['locations'][0]['physicalLocation']['region']['startLine'])
             for code, r in errors.items()}
    drifting = files['drifting']
    assert where == {
        'NODL403': (drifting.as_uri(), _line_of(drifting, 'name: commands')),
        'NODL404': (drifting.as_uri(), _line_of(drifting, 'name: ~/status')),
        'NODL402': (drifting.as_uri(), _line_of(drifting, '  publishers:')),  # extra: the section
    }
    assert 'subscription' in errors['NODL403']['message']['text']
    assert result.stderr.startswith('/cli_c/full drifts from ')


def test_format_junit_on_stdout(files: dict[str, Path]) -> None:
    result = nodl('check', '/cli_c/full', str(files['drifting']), '--format', 'junit',
                  '--timeout', '15')
    assert result.returncode == 1, result.stderr
    suite = ET.fromstring(result.stdout)
    assert suite.get('name') == 'nodl check /cli_c/full' and suite.get('failures') == '3'


def test_ignore_makes_a_drifting_check_pass(files: dict[str, Path]) -> None:
    result = nodl('check', '/cli_c/full', str(files['drifting']), '--timeout', '15',
                  '--ignore', 'NODL402', '--ignore', 'nodl403,NODL404')
    assert result.returncode == 0, result.stdout + result.stderr
    assert ': error: ' not in result.stdout
    assert re.fullmatch(r'/cli_c/full conforms to .*drifting\.nodl\.yaml \(\d+ unverifiable, '
                        r'listed with -v; 3 ignored\)', result.stdout.splitlines()[-1])
    # ignoring two of the three codes is not enough
    partly = nodl('check', '/cli_c/full', str(files['drifting']), '--timeout', '15',
                  '--ignore', 'NODL402,NODL403')
    assert partly.returncode == 1
    assert re.fullmatch(r'/cli_c/full drifts from .*: 1 difference \(\d+ unverifiable, '
                        r'listed with -v; 2 ignored\)', partly.stdout.splitlines()[-1])


def test_error_promotes_a_value_warning(files: dict[str, Path]) -> None:
    warned = nodl('check', '/cli_c/full', str(files['value']), '--timeout', '15')
    assert warned.returncode == 0, warned.stdout + warned.stderr
    assert any(line.startswith("/cli_c/full: warning: value: parameter 'gain'") and
               line.endswith('[NODL407]') for line in warned.stdout.splitlines())
    promoted = nodl('check', '/cli_c/full', str(files['value']), '--timeout', '15',
                    '--error', 'NODL407', '--format', 'json')
    assert promoted.returncode == 1, promoted.stdout + promoted.stderr
    data = json.loads(promoted.stdout)
    assert data['conforms'] is False
    assert [(d['kind'], d['severity'], d['name']) for d in data['differences']
            if d['severity'] != 'info'] == [('value', 'error', 'gain')]


def test_configuration_next_to_the_definition(files: dict[str, Path], tmp_path: Path) -> None:
    strict = tmp_path / 'strict'
    strict.mkdir()
    value = strict / 'value.nodl.yaml'
    value.write_text(files['value'].read_text(encoding='utf-8'), encoding='utf-8')
    (strict / 'nodl.toml').write_text('error = ["NODL407"]\n', encoding='utf-8')
    result = nodl('check', '/cli_c/full', str(value), '--timeout', '15')
    assert result.returncode == 1, result.stdout + result.stderr
    assert "/cli_c/full: error: value: parameter 'gain'" in result.stdout
    # the command line wins over the configuration
    assert nodl('check', '/cli_c/full', str(value), '--timeout', '15',
                '--ignore', 'NODL407').returncode == 0

    # [tool.nodl] of a pyproject.toml found upward (the definition one folder down)
    project = tmp_path / 'project'
    (project / 'nodl').mkdir(parents=True)
    (project / 'pyproject.toml').write_text(
        '[project]\nname = "x"\n\n[tool.nodl]\nignore = ["NODL402", "NODL403", "NODL404"]\n',
        encoding='utf-8')
    drifting = project / 'nodl' / 'drifting.nodl.yaml'
    drifting.write_text(files['drifting'].read_text(encoding='utf-8'), encoding='utf-8')
    quiet = nodl('check', '/cli_c/full', str(drifting), '--timeout', '15')
    assert quiet.returncode == 0, quiet.stdout + quiet.stderr
    assert '3 ignored' in quiet.stdout.splitlines()[-1]


def test_bad_codes_and_configurations_are_usage_errors(files: dict[str, Path],
                                                       tmp_path: Path) -> None:
    unknown = nodl('check', '/cli_c/full', str(files['good']), '--timeout', '30',
                   '--ignore', 'NODL4O2')
    assert unknown.returncode == 2 and unknown.stdout == ''
    assert unknown.stderr.startswith("nodl check: error: unknown code 'NODL4O2' for --ignore")
    both = nodl('check', '/cli_c/full', str(files['good']), '--timeout', '30',
                '--ignore', 'NODL407', '--error', 'NODL407')
    assert both.returncode == 2 and 'both --ignore and --error' in both.stderr
    # a broken configuration fails before the node is looked for
    (tmp_path / 'nodl.toml').write_text('ignroe = ["NODL402"]\n', encoding='utf-8')
    definition = tmp_path / 'good.nodl.yaml'
    definition.write_text(files['good'].read_text(encoding='utf-8'), encoding='utf-8')
    start = time.monotonic()
    broken = nodl('check', '/cli_c/nobody', str(definition), '--timeout', '30')
    assert time.monotonic() - start < 20
    assert broken.returncode == 2 and broken.stdout == ''
    assert broken.stderr == f"{tmp_path / 'nodl.toml'}: error: unknown key 'ignroe'; " \
                            "did you mean 'ignore'?\n"


LIMITED = '''
import resource, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails (EFBIG), not the process
resource.setrlimit(resource.RLIMIT_FSIZE, (256, 256))
from nodl.cli.main import main
sys.exit(main(sys.argv[1:]))
'''


def test_junit_is_replaced_atomically(files: dict[str, Path], tmp_path: Path) -> None:
    """A --junit report that cannot be written whole leaves the previous one; a link planted
    where it goes is replaced, its target untouched."""
    junit = tmp_path / 'report.xml'
    junit.write_text('<testsuites name="the last run"/>\n', encoding='utf-8')
    junit.chmod(0o640)
    limited = subprocess.run([sys.executable, '-c', LIMITED, 'check', '/cli_c/full', str(files['good']),
                              '--timeout', '15', '--junit', str(junit)],
                             cwd=REPO, text=True, capture_output=True, timeout=60)
    assert limited.returncode == 2, limited.stdout + limited.stderr
    assert limited.stderr.splitlines()[-1] == (
        f'{junit}: error: cannot write the file: File too large (the file size limit); the '
        'previous file is unchanged [NODL030]')
    assert 'Traceback' not in limited.stderr and '[Errno' not in limited.stderr
    assert junit.read_text(encoding='utf-8') == '<testsuites name="the last run"/>\n'
    assert sorted(p.name for p in tmp_path.iterdir()) == ['report.xml']  # no temporary left
    # written whole: the old report replaced (its mode kept)
    result = nodl('check', '/cli_c/full', str(files['good']), '--timeout', '15', '--junit', str(junit))
    assert result.returncode == 0, result.stderr
    assert ET.parse(junit).getroot().tag in ('testsuites', 'testsuite')
    assert junit.stat().st_mode & 0o777 == 0o640
    victim = tmp_path / 'victim.txt'
    victim.write_text('precious\n', encoding='utf-8')
    planted = tmp_path / 'planted.xml'
    planted.symlink_to(victim)
    result = nodl('check', '/cli_c/full', str(files['good']), '--timeout', '15', '--junit', str(planted))
    assert result.returncode == 0, result.stderr
    assert victim.read_text(encoding='utf-8') == 'precious\n'
    assert not planted.is_symlink() and ET.parse(planted).getroot().tag in ('testsuites', 'testsuite')


def test_junit_never_replaces_a_mixin_of_the_definition(files: dict[str, Path], tmp_path: Path) -> None:
    """The definition's mixins are inputs too (known once it is found): refused, nothing written."""
    import yaml

    definition: dict[str, Any] = yaml.safe_load(files['good'].read_text(encoding='utf-8'))
    definition['mixins'] = ['extra.nodl.yaml']
    wrapper = tmp_path / 'wrapper.nodl.yaml'
    wrapper.write_text(dump_nodl(definition, 'yaml'), encoding='utf-8')
    mixin = tmp_path / 'extra.nodl.yaml'
    mixin.write_text('nodl_version: 2\nparameters:\n  extra_gain:\n    type: double\n'
                     '    default_value: 1.0\n', encoding='utf-8')
    before = mixin.read_bytes()
    result = nodl('check', '/cli_c/full', str(wrapper), '--timeout', '15', '--junit', str(mixin))
    assert result.returncode == 2, result.stdout + result.stderr
    assert result.stderr.splitlines() == [
        f'{mixin}: error: --junit names an input of the command ({mixin}): '
        'writing it would destroy the input; give another output path [NODL033]']
    assert result.stdout == '' and mixin.read_bytes() == before
