"""`nodl check` as users run it: exit codes, text, JSON and JUnit output, real processes."""

from __future__ import annotations

import copy
import json
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any, Iterator

import pytest

from conftest import REPO, NodeProcess
from nodl_schema import dump_nodl
from nodl_schema.live.describe import describe_node, render_description


def nodl(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """Run `python -m nodl_schema` (it inherits ROS_DOMAIN_ID and the loopback-only discovery)."""
    result = subprocess.run([sys.executable, '-m', 'nodl_schema', *args], cwd=REPO, text=True,
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
    return {'good': good, 'drifting': drifting}


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
           'observed but not declared' in lines
    assert "/cli_c/full: error: type: subscription '/cli_c/commands': declared type " \
           'std_msgs/msg/Int32, observed std_msgs/msg/String (declared in main)' in lines
    assert any(l.startswith("/cli_c/full: error: qos: publisher '/cli_c/full/status' durability: "
                            'declared VOLATILE, observed TRANSIENT_LOCAL') for l in lines)
    assert any(': info: unverifiable: ' in l for l in lines)  # -v
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
    assert set(data['differences'][0]) == {'kind', 'severity', 'section', 'name', 'declared',
                                           'observed', 'layer', 'message'}


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
    errors = [l for l in result.stderr.splitlines() if ': error: ' in l]
    assert errors
    assert all(re.match(re.escape(str(bad)) + r':\d+:\d+: error: ', l) for l in errors), errors


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
