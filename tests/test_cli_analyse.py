"""``nodl analyse`` / ``nodl analyze`` on the command line: formats, exit statuses, options,
the log file and the graph files."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

REPO = Path(__file__).resolve().parent.parent
FIXTURES = REPO / 'tests' / 'fixtures' / 'analysis'
LAUNCH = FIXTURES / 'launch'


def run(*args: str, cwd: Path = REPO) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, AMENT_PREFIX_PATH=str(FIXTURES / 'prefix'), NO_COLOR='1')
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=120)


def test_text_report_and_exit_status_1_on_errors() -> None:
    done = run('analyse', str(LAUNCH / 'checks.launch.xml'))
    assert done.returncode == 1, done.stderr
    assert re.search(r'checks\.launch\.xml:10:3: error: /planner is launched twice .*\[NODL550\]',
                     done.stdout)
    assert 'orphan-publisher' not in done.stdout and '[NODL558]' not in done.stdout  # info: -v
    assert done.stdout.rstrip().splitlines()[-1].startswith('8 nodes, ')
    assert 'Traceback' not in done.stderr


def test_analyze_spelling_and_exit_0_without_errors() -> None:
    done = run('analyze', str(LAUNCH / 'system.launch.xml'))
    assert done.returncode == 0, done.stdout + done.stderr


def test_launch_arguments() -> None:
    done = run('analyse', str(LAUNCH / 'system.launch.xml'), 'robot:=other', '--format', 'json')
    names = [n['name'] for n in json.loads(done.stdout)['nodes']]
    assert names == ['/other/imu', '/other/planner']
    bad = run('analyse', str(LAUNCH / 'system.launch.xml'), 'robot=other')
    assert bad.returncode == 2 and "'robot=other' is not NAME:=VALUE" in bad.stderr



@pytest.mark.parametrize('target', [LAUNCH / 'system.launch.xml', REPO / 'examples' / 'laser_driver.nodl.yaml'])
def test_the_graph_file_name_picks_its_format(tmp_path: Path, target: Path) -> None:
    done = run('analyse', str(target), '--graph', str(tmp_path / 'system.png'))
    assert done.returncode == 2 and done.stdout == ''
    assert done.stderr == (f"nodl analyse: error: --graph {tmp_path / 'system.png'}: the name must end in "
                           '.dot, .svg or .html (it picks the format)\n')
    assert not (tmp_path / 'system.png').exists()

@pytest.mark.parametrize('fmt', ['json', 'sarif', 'junit'])
def test_formats_to_a_file(tmp_path: Path, fmt: str) -> None:
    out = tmp_path / f'report.{fmt}'
    done = run('analyse', str(LAUNCH / 'checks.launch.xml'), '--format', fmt, '-o', str(out))
    assert done.returncode == 1 and done.stdout == ''
    text = out.read_text()
    if fmt == 'junit':
        import xml.etree.ElementTree as ET

        ET.fromstring(text)
    elif fmt == 'sarif':
        from sarif_shape import assert_sarif_2_1_0

        assert_sarif_2_1_0(json.loads(text))
    else:
        json.loads(text)


def test_ignore_and_error_options_and_the_configuration(tmp_path: Path) -> None:
    done = run('analyse', str(LAUNCH / 'checks.launch.xml'), '--ignore', 'NODL550,NODL552',
               '--ignore', 'NODL553,NODL561,NODL562,NODL563', '--format', 'json')
    report = json.loads(done.stdout)
    assert done.returncode == 0, done.stdout
    assert not [f for f in report['findings'] if f['severity'] == 'error']
    promoted = run('analyse', str(LAUNCH / 'system.launch.xml'), '--error', 'NODL554')
    assert promoted.returncode == 1
    # nodl.toml next to the launch file: ignore + the allow list
    (tmp_path / 'nodl.toml').write_text('ignore = ["NODL550"]\n[analyse]\n'
                                        'multiple_publishers_allow = ["/scan"]\n')
    copy = tmp_path / 'checks.launch.xml'
    copy.write_text((LAUNCH / 'checks.launch.xml').read_text())
    report = json.loads(run('analyse', str(copy), '--format', 'json').stdout)
    kinds = {f['kind'] for f in report['findings']}
    assert 'duplicate-node' not in kinds and 'multiple-publishers' not in kinds
    (tmp_path / 'nodl.toml').write_text('[analyse]\nmultiple_publisher_allow = ["/scan"]\n')
    bad = run('analyse', str(copy))
    assert bad.returncode == 2 and "did you mean 'multiple_publishers_allow'" in bad.stderr


def test_unreadable_launch_files_exit_2(tmp_path: Path) -> None:
    missing = run('analyse', str(tmp_path / 'nothing.launch.xml'))
    assert missing.returncode == 2 and 'no such file' in missing.stderr
    broken = tmp_path / 'broken.launch.xml'
    broken.write_text('<launch><node pkg="a"')
    done = run('analyse', str(broken))
    assert done.returncode == 2, done.stdout + done.stderr
    assert 'Traceback' not in done.stderr + done.stdout


def test_log_file(tmp_path: Path) -> None:
    log = tmp_path / 'analysis.log'
    run('analyse', str(LAUNCH / 'checks.launch.xml'), '--log', str(log))
    text = log.read_text()
    assert '== System' in text and '== Findings' in text and '[NODL558]' in text  # info too


@pytest.mark.parametrize('name', ['checks.launch.xml', 'renames.launch.xml'])
def test_log_file_is_the_whole_report_and_deterministic(tmp_path: Path, name: str, golden: Any) -> None:
    """The log holds every node (final name and how it came about, source, definition,
    remapping rules with their places, parameters with their origin, final endpoint names)
    then every finding with its place; two runs give the same bytes."""
    from nodl import __version__

    logs = [tmp_path / 'one.log', tmp_path / 'two.log']
    for log in logs:
        run('analyse', str(LAUNCH / name), '--log', str(log))
    text = logs[0].read_text(encoding='utf-8')
    assert text == logs[1].read_text(encoding='utf-8')
    portable = text.replace(f'{REPO}/', '').replace(f'nodl-toolkit {__version__}', 'nodl-toolkit VERSION')
    golden.check(portable, FIXTURES / 'expected' / name.replace('.launch.xml', '.log'))


def test_graph_dot_svg_html(tmp_path: Path) -> None:
    for ext in ('dot', 'svg', 'html'):
        out = tmp_path / f'system.{ext}'
        done = run('analyse', str(LAUNCH / 'checks.launch.xml'), '--graph', str(out))
        assert done.returncode == 1, done.stderr
        assert out.stat().st_size > 0
    dot = (tmp_path / 'system.dot').read_text()
    assert 'shape=ellipse' in dot and 'shape=box' in dot and 'shape=hexagon' in dot \
        and 'shape=doubleoctagon' in dot
    bad = run('analyse', str(LAUNCH / 'checks.launch.xml'), '--graph', str(tmp_path / 'x.png'))
    assert bad.returncode == 2 and '.dot, .svg or .html' in bad.stderr


def test_json_output_stays_json_when_a_python_launch_file_prints(tmp_path: Path) -> None:
    launch = tmp_path / 'talkative.launch.py'
    launch.write_text('from launch import LaunchDescription\nprint("starting up")\n'
                      'def generate_launch_description():\n    return LaunchDescription([])\n')
    done = run('analyse', str(launch), '--format', 'json')
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)['nodes'] == []
    assert 'starting up' in done.stderr


def test_a_system_of_nodes_registered_by_the_references_ament_nodl_register() -> None:
    prefix = REPO / 'tests' / 'fixtures' / 'index' / 'reference'
    launch = REPO / 'tests' / 'fixtures' / 'index' / 'reference_launch' / 'robot.launch.xml'
    env = dict(os.environ, AMENT_PREFIX_PATH=str(prefix), NO_COLOR='1')
    result = subprocess.run([sys.executable, '-m', 'nodl', 'analyse', str(launch),
                             '--format', 'json'], cwd=REPO, env=env, capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    nodes = {n['name']: n for n in report['nodes']}
    assert set(nodes) == {'/talker', '/listener', '/front/lidar'}, report['nodes']
    assert all('definition' in n and 'ref_robot__' in str(n['definition']) for n in nodes.values())
    # The talker's and the listener's definitions meet on /chatter; the lidar's rewritten
    # include (nodl://ref_robot/sensor_common) gives it /clock, which nothing publishes.
    codes = {f['code'] for f in report['findings']}
    assert 'NODL555' in codes and not {'NODL306', 'NODL301'} & codes, report['findings']


SANDBOX = REPO / 'tests' / 'fixtures' / 'launch' / 'sandbox'


def test_no_exec_runs_no_python_launch_file_and_exits_2() -> None:
    done = run('analyse', '--no-exec', str(SANDBOX / 'good.launch.py'))
    assert done.returncode == 2, done.stdout + done.stderr
    assert re.search(r'good\.launch\.py:1:1: error: .*is not run: --no-exec is set.*\[NODL525\]', done.stdout)


def test_a_crashing_launch_file_is_a_located_error_not_a_dead_analyser() -> None:
    done = run('analyse', '--launch-memory', '256', str(SANDBOX / 'segfault.launch.py'))
    assert done.returncode == 2, done.stdout + done.stderr
    assert re.search(r'segfault\.launch\.py:1:1: error: .*killed by SIGSEGV.*\[NODL527\]', done.stdout)
    assert 'Traceback' not in done.stderr and 'Fatal Python error' not in done.stderr
    done = run('analyse', '--launch-timeout', '1', str(SANDBOX / 'mixed.launch.xml'), '--format', 'json')
    assert done.returncode == 1, done.stdout + done.stderr  # the rest is read: errors, not unreadable
    report = json.loads(done.stdout)
    assert [n['name'] for n in report['nodes']] == ['/talker', '/listener']
    assert [(f['code'], f['line']) for f in report['findings'] if f['code'] == 'NODL527'] == [('NODL527', 5)]


def test_help_says_what_runs() -> None:
    text = ' '.join(run('analyse', '--help').stdout.split())
    assert 'Reading a Python launch file runs its code, and $(eval ...) runs Python' in text
    assert '$(command ...) is never run' in text and '--no-exec' in text
    assert '(default: 30)' in text and '(default: 2048)' in text


def test_a_file_that_is_not_a_launch_file_is_named_with_exit_2() -> None:
    """A file that is neither a launch file nor a node definition given to analyse: what it
    is, exit 2, no launch-syntax error about its first line.  (A node definition is analysed
    as a system of one node: see test_explicit_definitions_are_analysed_without_a_launch_file.)"""
    definition = FIXTURES / 'prefix' / 'share' / 'nav' / 'nodl' / 'planner.nodl.yaml'
    done = run('analyse', str(definition))
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-2:] == ['1 node: 1 from files', '1 node, 0 errors, 4 warnings, 1 info']
    assert 'NODL501' not in done.stderr + done.stdout
    interface = REPO / 'tests' / 'fixtures' / 'overlays' / 'defs' / 'upstream_drv' / 'interfaces'
    done = run('analyse', str(interface / 'status.nodl.yaml'))
    assert done.returncode == 2 and '[NODL531]' in done.stderr
    assert 'this is a NoDL interface definition, not a launch file' in done.stderr
    notes = REPO / 'tests' / 'fixtures' / 'launch' / 'not_launch' / 'notes.md'
    done = run('analyse', str(notes))
    assert done.returncode == 2 and 'neither an XML, a YAML nor a Python launch file' in done.stderr


OVERLAYS = REPO / 'tests' / 'fixtures' / 'overlays'


def test_definitions_folders_serve_nodes_with_their_source_in_json_and_a_coverage_line() -> None:
    launch = str(OVERLAYS / 'launch' / 'system.launch.xml')
    done = run('analyse', launch, '--definitions', str(OVERLAYS / 'defs'), '--format', 'json')
    assert done.returncode == 0, done.stderr
    nodes = {n['name']: (n['definition_source'], n['definition_folder'], n['definition_provenance'])
             for n in json.loads(done.stdout)['nodes']}
    folder = str(OVERLAYS / 'defs')
    assert nodes == {'/planner': ('index', None, None), '/controller': ('overlay', folder, 'extracted'),
                     '/drv': ('overlay', folder, None), '/thing': (None, None, None)}
    assert '4 nodes: 1 registered, 2 overlay (1 extracted), 1 without definition' in done.stderr
    text = run('analyse', launch, '--definitions', str(OVERLAYS / 'defs'), '-v').stdout.splitlines()
    assert text[-2:] == ['4 nodes: 1 registered, 2 overlay (1 extracted), 1 without definition',
                         '4 nodes, 0 errors, 6 warnings, 1 info']
    assert f'/drv: {folder}/upstream_drv/driver.nodl.yaml (overlay {folder})' in text
    # without the folder: the index alone (nav controller from the index, upstream_drv unknown)
    alone = run('analyse', launch).stdout.splitlines()
    assert alone[-2] == '4 nodes: 2 registered, 0 overlay, 2 without definition'


def test_a_project_configuration_and_nodl_path_give_folders(tmp_path: Path) -> None:
    done = run('analyse', str(OVERLAYS / 'project' / 'launch' / 'system.launch.xml'))
    assert done.stdout.splitlines()[-2] == '4 nodes: 1 registered, 2 overlay (1 extracted), 1 without definition'
    env = dict(os.environ, AMENT_PREFIX_PATH=str(FIXTURES / 'prefix'),
               NODL_PATH=str(OVERLAYS / 'defs'))
    via_env = subprocess.run([sys.executable, '-m', 'nodl', 'analyse',
                              str(OVERLAYS / 'launch' / 'system.launch.xml')], cwd=REPO, env=env,
                             capture_output=True, text=True, timeout=120)
    assert via_env.stdout.splitlines()[-2] == \
        '4 nodes: 1 registered, 2 overlay (1 extracted), 1 without definition'


def test_a_bad_definitions_folder_is_located_findings_and_exit_1() -> None:
    done = run('analyse', str(OVERLAYS / 'launch' / 'system.launch.xml'),
               '--definitions', str(OVERLAYS / 'bad'))
    assert done.returncode == 1
    assert re.search(r'bad/my_pkg/nodes\.yaml:2:11: error: .*other_pkg.*\[NODL242\]', done.stdout)
    assert done.stdout.count('[NODL240]') == 4 and 'Traceback' not in done.stderr
    missing = run('analyse', str(OVERLAYS / 'launch' / 'system.launch.xml'),
                  '--definitions', 'no_such_dir')
    assert missing.returncode == 2 and 'no such folder [NODL246]' in missing.stderr


def test_explicit_definitions_are_analysed_without_a_launch_file() -> None:
    driver = str(OVERLAYS / 'defs' / 'upstream_drv' / 'driver.nodl.yaml')
    # (its nodl://upstream_drv/status mixin is served by the definitions folder alone)
    failed = run('analyse', driver, 'nav', 'planner', '--format', 'json')
    assert failed.returncode == 1 and '1 node: 1 registered' in failed.stderr
    assert 'NODL301' in {f['code'] for f in json.loads(failed.stdout)['findings']}
    defs = ('--definitions', str(OVERLAYS / 'defs'))
    done = run('analyse', driver, 'nav', 'planner', '--name', '/robot/drv', '--format', 'json', *defs)
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert [(n['name'], n['definition_source']) for n in data['nodes']] == [
        ('/robot/drv', 'file'), ('/planner', 'index')]
    # the driver's /scan reaches the planner only through a remapping rule
    codes = {(f['code'], f.get('endpoint')) for f in data['findings']}
    assert ('NODL555', '/scan') in codes
    remapped = run('analyse', driver, 'nav', 'planner', '--remap', 'drv:scan:=/scan',
                   '--name', '/robot/drv', '--format', 'json', *defs)
    assert ('NODL555', '/scan') not in {(f['code'], f.get('endpoint'))
                                        for f in json.loads(remapped.stdout)['findings']}
    assert '2 nodes: 1 registered, 0 overlay, 1 from files, 0 without definition' in done.stderr
    # an invalid definition: its errors, exit 1; a package without it: NODL306, exit 1
    ghost = run('analyse', 'nav', 'ghost')
    assert ghost.returncode == 1 and '[NODL306]' in ghost.stdout


def test_a_file_neither_launch_file_nor_definition_stays_exit_2(tmp_path: Path) -> None:
    params = tmp_path / 'params.yaml'
    params.write_text('node:\n  ros__parameters: {a: 1}\n')
    driver = str(OVERLAYS / 'defs' / 'upstream_drv' / 'driver.nodl.yaml')
    for args in ((str(params),), (driver, str(params)), (driver, str(tmp_path / 'none.nodl.yaml'))):
        done = run('analyse', *args)
        assert done.returncode == 2 and 'Traceback' not in done.stderr, done.stderr
    assert '[NODL531]' in run('analyse', driver, str(params)).stderr
    mixed = run('analyse', driver, str(OVERLAYS / 'launch' / 'system.launch.xml'))
    assert mixed.returncode == 2 and 'not both' in mixed.stderr
    assert run('analyse', str(OVERLAYS / 'launch' / 'system.launch.xml'), '--name', 'x').returncode == 2


GAPS = OVERLAYS / 'gaps'


def test_an_extracted_draft_with_gaps_is_one_warning_and_orphans_it_could_answer_say_so(
        tmp_path: Path) -> None:
    draft = GAPS / 'defs' / 'relay_pkg' / 'relay.nodl.yaml'
    done = run('analyse', str(GAPS / 'launch' / 'system.launch.xml'),
               '--definitions', str(GAPS / 'defs'), '--format', 'json', '-v')
    assert done.returncode == 0, done.stderr
    findings = json.loads(done.stdout)['findings']
    gaps = [f for f in findings if f['code'] == 'NODL568']
    assert len(gaps) == 1 and gaps[0]['nodes'] == ['/relay'] and gaps[0]['severity'] == 'warning'
    assert gaps[0]['line'] == 3  # the relay's launch entry
    assert 'with 3 entities still unknown (1 publisher, 1 subscription and 1 service client' \
        in gaps[0]['message'] and 'cannot be judged' in gaps[0]['message']
    lines = draft.read_text().split('\n')
    related = [(r['file'], r['line'], r['column']) for r in gaps[0]['related']]
    assert related == [(str(draft), i + 1, line.index('#') + 1)
                       for i, line in enumerate(lines) if line.lstrip().startswith('# GAP ')]
    orphans = {(f['endpoint'], f['code']): f['message'] for f in findings if f['code'] in ('NODL555', 'NODL558')}
    unless = "(unless /relay's unresolved entities, under # GAP in its extracted draft, do)"
    assert orphans[('/status', 'NODL555')].endswith(unless)  # the draft's status publisher, QoS unknown
    assert orphans[('/image', 'NODL558')].endswith(unless)  # its subscription of an unknown name
    assert 'unless' not in orphans[('/settings', 'NODL555')]  # no publisher of it is a gap
    assert 'unless' not in orphans[('/relayed', 'NODL558')]  # (not the draft's own endpoint)
    # filled in and uncommented (the GAP comments may stay): resolved, no finding about it
    filled = tmp_path / 'defs'
    (filled / 'relay_pkg').mkdir(parents=True)
    (filled / 'camera_pkg').mkdir()
    (filled / 'camera_pkg' / 'camera.nodl.yaml').write_text(
        (GAPS / 'defs' / 'camera_pkg' / 'camera.nodl.yaml').read_text())
    text = draft.read_text().replace(
        '    # - name: status\n    #   type: std_msgs/msg/String\n',
        '    - name: status\n      type: std_msgs/msg/String\n'
        '      qos: {history: KEEP_LAST, depth: 10, reliability: RELIABLE}\n')
    (filled / 'relay_pkg' / 'relay.nodl.yaml').write_text(text)
    again = run('analyse', str(GAPS / 'launch' / 'system.launch.xml'),
                '--definitions', str(filled), '--format', 'json')
    found = json.loads(again.stdout)['findings']
    assert [f['message'] for f in found if f['code'] == 'NODL568'][0].count('2 entities still unknown')
    assert not any(f.get('endpoint') == '/status' and f['code'] == 'NODL555' for f in found)  # published
