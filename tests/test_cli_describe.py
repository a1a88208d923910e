"""`nodl describe` as users run it: a real process observing real node processes."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from conftest import REPO, NodeProcess
from nodl import load_node, validate_node
from nodl.writing import marker_state, unmark


def nodl(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """Run `python -m nodl` (it inherits ROS_DOMAIN_ID and the loopback-only discovery)."""
    result = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                            capture_output=True, timeout=timeout)
    assert 'Traceback' not in result.stdout + result.stderr, result.stderr
    return result


@pytest.fixture(scope='module')
def nodes() -> Iterator[dict[str, NodeProcess]]:
    started: dict[str, NodeProcess] = {}
    try:
        started['full'] = NodeProcess('full_node.py', 'full', '/cli_d')
        started['managed'] = NodeProcess('lifecycle_node.py', 'managed', '/cli_d')
        yield started
    finally:
        for node in started.values():
            node.stop()


def test_describe_node_to_a_file(nodes, tmp_path: Path) -> None:
    out = tmp_path / 'new' / 'dir' / 'full.nodl.yaml'
    result = nodl('describe', '/cli_d/full', '-o', str(out), '--timeout', '15')
    assert result.returncode == 0, result.stderr
    assert result.stdout == f'/cli_d/full -> {out}\n'
    text = out.read_text(encoding='utf-8')
    assert marker_state(text) == 'valid'
    text = unmark(text)
    assert text.startswith('# Described from the running node /cli_d/full by `nodl describe`.\n')
    # every note is a warning on stderr and a line of the header comment
    warnings = [line for line in result.stderr.splitlines() if line.startswith('nodl describe: warning: ')]
    assert any('service QoS' in w for w in warnings)
    for warning in warnings:
        assert '#   - ' + warning[len('nodl describe: warning: '):] in text
    node = load_node(text)
    assert node.base == 'node'
    assert set(node.main.parameters) == {'frame_id', 'gain', 'joints', 'rate', 'verbose'}
    assert {p.name for p in node.main.publishers} == {'~/status', 'measurement', '/global_chatter'}
    # A described file passes even --strict: its header silences 'has no description'.
    check = nodl('validate', '--strict', str(out))
    assert check.returncode == 0, check.stdout
    assert check.stdout.endswith('1 file, 0 errors, 0 warnings\n'), check.stdout
    # the user's edits are never described over without --force
    edited = out.read_text(encoding='utf-8') + '# reviewed by me\n'
    out.write_text(edited, encoding='utf-8')
    again = nodl('describe', '/cli_d/full', '-o', str(out), '--timeout', '15')
    assert again.returncode == 2 and again.stderr.splitlines()[-1].endswith('[NODL032]'), again.stderr
    assert out.read_text(encoding='utf-8') == edited


def test_describe_to_stdout_as_json_without_parameters(nodes) -> None:
    result = nodl('describe', '/cli_d/full', '--no-parameters', '--format', 'json',
                  '--timeout', '15')
    assert result.returncode == 0, result.stderr
    definition = json.loads(result.stdout)
    validate_node(definition)
    assert definition['base'] == 'node'
    assert 'parameters' not in definition['main']
    assert {e['name'] for e in definition['main']['subscriptions']} == {'/emergency_stop', 'commands'}


def test_describe_says_how_long_namesakes_were_watched(nodes, tmp_path: Path) -> None:
    """No fixed window: namesakes are watched for while the node is read, at least 0.3 s of
    discovery by default and longer with --watch; the output says how long."""
    import re

    out = tmp_path / 'full.nodl.yaml'
    result = nodl('describe', '/cli_d/full', '-o', str(out), '--timeout', '15')
    assert result.returncode == 0, result.stderr
    line = next(text for text in out.read_text(encoding='utf-8').splitlines()
                if text.startswith('# Namesakes watched for '))
    found = re.match(r'# Namesakes watched for ([0-9.]+) s of discovery', line)
    assert found is not None and float(found.group(1)) >= 0.3
    if float(found.group(1)) < 3.5:
        assert '--watch 3.5' in line
    longer = nodl('describe', '/cli_d/full', '--watch', '2', '--format', 'json', '--timeout', '15')
    assert longer.returncode == 0, longer.stderr
    notes = [line for line in longer.stderr.splitlines()
             if line.startswith('nodl describe: note: namesakes watched for ')]
    assert len(notes) == 1
    assert float(notes[0].split('watched for ')[1].split(' s')[0]) >= 2.0


def test_describe_all_writes_one_file_per_node(nodes, tmp_path: Path) -> None:
    out = tmp_path / 'all'
    result = nodl('describe', '--all', '-o', str(out), '--timeout', '10')
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    # (a node of someone else's that vanished meanwhile would be listed as '(skipped)')
    written = {fqn: path for fqn, path in (line.split(' -> ') for line in lines)
               if path != '(skipped)'}
    assert {'/cli_d/full', '/cli_d/managed'} <= set(written)
    assert written['/cli_d/full'] == str(out / 'cli_d.full.nodl.yaml')
    assert written['/cli_d/managed'] == str(out / 'cli_d.managed.nodl.yaml')
    # one file per node, and the observer did not describe itself
    files = sorted(p.name for p in out.iterdir())
    assert files == sorted(Path(p).name for p in written.values())
    assert not [f for f in files if 'nodl_observer' in f]
    assert not [n for n in written if 'nodl_observer' in n]
    managed = load_node((out / 'cli_d.managed.nodl.yaml').read_text(encoding='utf-8'))
    assert managed.base == 'lifecycle_node'
    for path in written.values():
        load_node(Path(path).read_text(encoding='utf-8'))


def test_node_not_found_exits_2_within_the_timeout() -> None:
    start = time.monotonic()
    result = nodl('describe', '/cli_d/nobody', '--timeout', '1')
    elapsed = time.monotonic() - start
    assert result.returncode == 2
    assert result.stdout == ''
    assert result.stderr.startswith("nodl describe: error: node '/cli_d/nobody' was not found "
                                    'within 1 s')
    assert elapsed < 1 + 5


@pytest.mark.parametrize('args, message', [
    ([], 'give a NODE, or --all with -o DIR'),
    (['/x', '--all', '-o', 'd'], 'give a NODE, or --all with -o DIR'),
    (['--all'], '--all needs -o DIR'),
])
def test_usage_errors_exit_2(args: list[str], message: str) -> None:
    result = nodl('describe', *args)
    assert result.returncode == 2
    assert message in result.stderr


def test_describe_states_the_client_library_and_takes_the_option(nodes) -> None:
    deduced = nodl('describe', '/cli_d/full', '--no-parameters', '--timeout', '15')
    assert deduced.returncode == 0, deduced.stderr
    assert deduced.stdout.splitlines()[1] == (
        '# Left out: what the base gives an rclpy node (the node does not subscribe to '
        '/parameter_events, as rclcpp nodes do).')
    # as rclcpp, nothing is left out that the node has not got: the same main
    asked = nodl('describe', '/cli_d/full', '--no-parameters', '--timeout', '15', '--format', 'json',
                 '--client-library', 'rclcpp')
    assert asked.returncode == 0, asked.stderr
    assert 'nodl describe: note: client library rclcpp (as requested)\n' in asked.stderr
    assert json.loads(asked.stdout)['main'] == load_node(deduced.stdout).main.to_dict()
    bad = nodl('describe', '/cli_d/full', '--client-library', 'rclc')
    assert bad.returncode == 2


def test_describe_warns_of_version_skew(tmp_path: Path) -> None:
    import os

    from skewed_prefix import STRING_WITH_REVISION, VENV, skewed_prefix

    prefix = skewed_prefix(tmp_path, {'std_msgs/msg/String': STRING_WITH_REVISION})
    node = NodeProcess('typed_node.py', 'typed', '/cli_skew')
    out = tmp_path / 'typed.nodl.yaml'
    old = os.environ.get('AMENT_PREFIX_PATH')
    os.environ['AMENT_PREFIX_PATH'] = f'{prefix}:{VENV}'
    try:
        result = nodl('describe', '/cli_skew/typed', '-o', str(out), '--timeout', '15')
    finally:
        node.stop()
        if old is None:
            del os.environ['AMENT_PREFIX_PATH']
        else:
            os.environ['AMENT_PREFIX_PATH'] = old
    assert result.returncode == 0, result.stderr
    [warning] = [line for line in result.stderr.splitlines() if 'version skew' in line]
    assert warning.startswith('nodl describe: warning: version skew: /cli_skew/chatter: the node '
                              "uses another definition of 'std_msgs/msg/String'")
    assert "field 'revision' (int32)" in warning and warning.endswith('[NODL423]')
    text = unmark(out.read_text(encoding='utf-8'))
    assert "  # Version skew: /cli_skew/chatter: the node uses another definition" in text
    assert text.index('# Version skew') < text.index('- name: chatter')


# -- start-up: the arguments of describe are checked without the launch reader or the validator --


@pytest.mark.parametrize('name, problem', [
    ('/robot/driver', None), ('talker', None), ('/a/b_2/c', None),
    ('/robot/1driver', "token '1driver' starts with a digit"),
    ('/a b', "contains ' '"), ('/ns/x-y', "contains '-'"), ('a//b', "contains a repeated '/'"),
    ('/a/', "ends with '/'"), ('~/x', "holds no '~' or '{}'"), ('{ns}/x', "holds no '~' or '{}'"),
    ('/', 'is a namespace'), ('', 'must not be empty'), ('/' + 'a' * 300, 'is too long (301 characters)'),
])
def test_node_names_follow_rcl_s_rules_from_nodl_naming(name: str, problem: str | None) -> None:
    from nodl.cli.arguments import node_name_problem

    found = node_name_problem(name)
    assert (found is None) if problem is None else (found is not None and problem in found), found


def test_describe_s_parser_imports_neither_the_launch_reader_nor_the_validator() -> None:
    code = ('import sys, argparse\n'
            'from nodl.cli.verbs.describe import DescribeVerb\n'
            'parser = argparse.ArgumentParser()\n'
            'DescribeVerb().add_arguments(parser)\n'
            "args = parser.parse_args(['/robot/driver'])\n"
            "assert args.launch_timeout == 30 and args.launch_memory == 2048, args\n"
            "print(sorted(m for m in sys.modules if m.startswith(('nodl.launch', 'nodl.validation'))))\n")
    result = subprocess.run([sys.executable, '-c', code], cwd=REPO, text=True, capture_output=True,
                            timeout=30)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == '[]'


def test_launch_code_defaults_are_the_sandbox_s() -> None:
    from nodl.launch.sandbox import DEFAULT_MEMORY_MIB, DEFAULT_TIMEOUT, LaunchLimits
    from nodl.vocabulary import LAUNCH_CODE_MEMORY_MIB, LAUNCH_CODE_TIMEOUT

    assert (DEFAULT_TIMEOUT, DEFAULT_MEMORY_MIB) == (LAUNCH_CODE_TIMEOUT, LAUNCH_CODE_MEMORY_MIB)
    assert LaunchLimits() == LaunchLimits(True, LAUNCH_CODE_TIMEOUT, LAUNCH_CODE_MEMORY_MIB)
