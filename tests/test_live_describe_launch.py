"""`nodl describe --all --launch`: a running system described into a definitions folder.

The system of tests/fixtures/describe_launch/system.launch.xml is started as real processes
from the analysis's own records (``ros2 launch`` is not installable here): each launched
node's executable is played by tests/nodes/system_node.py, given the name its executable
declares and, after ``--ros-args``, the ``__node``/``__ns``/``from:=to`` rules and ``-p``
values launch would give it; the container process loads its composable nodes as
launch_ros's load requests describe them.
"""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from conftest import FIXTURES, REPO, NodeProcess
from nodl import load_node
from nodl.analysis import analyse_launch
from nodl.writing import unmark

HERE = FIXTURES / 'describe_launch'
SYSTEM = HERE / 'system.launch.xml'


def nodl(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """Run `python -m nodl` (it inherits ROS_DOMAIN_ID and the loopback-only discovery)."""
    result = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                            capture_output=True, timeout=timeout)
    assert 'Traceback' not in result.stdout + result.stderr, result.stderr
    return result


def _value(value: Any) -> str:
    return json.dumps(value) if not isinstance(value, str) else value


def start_launched(launch: Path, arguments: dict[str, str] | None = None) -> list[NodeProcess]:
    """Start every process the analysis of ``launch`` records, as launch would."""
    analysis = analyse_launch(launch, arguments or {}, checks={})
    composables: dict[str, list[dict[str, Any]]] = {}
    for node in analysis.nodes:
        if node.entry.role == 'composable':
            assert node.entry.container is not None
            composables.setdefault(node.entry.container, []).append({
                'plugin': node.entry.plugin, 'name': node.created_name,
                'namespace': node.entry.namespace,
                'rules': [f'{a}:={b}' for a, b in node.entry.remaps]})
    started: list[NodeProcess] = []
    try:
        for node in analysis.nodes:
            if node.entry.role == 'composable':
                continue
            executable = node.entry.executable
            assert executable is not None
            ros_args = ['-r', f'__node:={node.created_name}', '-r', f'__ns:={node.entry.namespace}']
            for a, b in node.entry.remaps:
                ros_args += ['-r', f'{a}:={b}']
            for name, value in node.parameter_values().items():
                ros_args += ['-p', f'{name}:={_value(value)}']
            load = json.dumps(composables.get(node.fqn, []))
            started.append(NodeProcess('system_node.py', executable, '/', '--role', executable,
                                       '--load', load, '--ros-args', *ros_args))
    except BaseException:
        for process in started:
            process.stop()
        raise
    return started


@pytest.fixture(scope='module')
def system() -> Iterator[list[NodeProcess]]:
    started = start_launched(SYSTEM)
    try:
        yield started
    finally:
        for process in started:
            process.stop()


@pytest.fixture(scope='module')
def described(system: list[NodeProcess], tmp_path_factory: pytest.TempPathFactory
              ) -> tuple[Path, subprocess.CompletedProcess[str]]:
    out = tmp_path_factory.mktemp('overlay')
    result = nodl('describe', '--all', '--launch', str(SYSTEM), 'rate:=5', '-o', str(out),
                  '--timeout', '15')
    return out, result


def _definition(path: Path) -> tuple[str, Any]:
    text = unmark(path.read_text(encoding='utf-8'))
    return text, load_node(text)


def test_the_overlay_is_laid_out_by_package_and_executable(described) -> None:
    out, result = described
    assert result.returncode == 0, result.stdout + result.stderr
    files = sorted(str(p.relative_to(out)) for p in out.rglob('*') if p.is_file())
    assert files == ['demo_robot/camera_driver.nodl.yaml', 'demo_robot/container.nodl.yaml',
                     'demo_robot/lidar_driver.nodl.yaml', 'demo_robot/listener.nodl.yaml',
                     'demo_robot/nodes.yaml', 'demo_robot/talker.nodl.yaml']
    # both talkers are one definition, listed with where they are launched
    assert f'{out}/demo_robot/talker.nodl.yaml <- /left/talker, /right/talker' in result.stdout


def test_names_are_the_declared_ones(described) -> None:
    out, _ = described
    text, talker = _definition(out / 'demo_robot' / 'talker.nodl.yaml')
    # chatter:=/shared/chatter undone; ~/reset private; /diagnostics stays absolute
    assert {p.name for p in talker.main.publishers} == {'chatter', '/diagnostics'}
    assert [s.name for s in talker.main.service_servers] == ['~/reset']
    _, listener = _definition(out / 'demo_robot' / 'listener.nodl.yaml')
    # a root node's own names are relative: the same declaration in any namespace
    assert {s.name for s in listener.main.subscriptions} == {'chatter', 'cmd_vel', 'diagnostics'}
    _, camera = _definition(out / 'demo_robot' / 'camera_driver.nodl.yaml')
    assert [p.name for p in camera.main.publishers] == ['image']


def test_the_header_says_where_it_comes_from(described) -> None:
    out, _ = described
    text, talker = _definition(out / 'demo_robot' / 'talker.nodl.yaml')
    assert text.startswith('# Described by `nodl describe --all --launch` from the running system '
                           f'{SYSTEM} rate:=5 started.\n# Provenance: described; demo_robot '
                           'executable talker, 2 instances:\n')
    assert f'#   - /left/talker (launched at {SYSTEM}:12:5)' in text
    assert 'Namesakes watched for ' in text
    # rate is set by the launch on both instances: its default is not observable
    assert talker.main.parameters['rate'].default_value is None
    assert 'parameter rate: its default is not observable' in text
    assert talker.main.parameters['debug'].default_value is False


def test_a_lifecycle_node_observed_before_configure(described) -> None:
    out, result = described
    text, lidar = _definition(out / 'demo_robot' / 'lidar_driver.nodl.yaml')
    assert lidar.base == 'lifecycle_node'
    assert 'lifecycle state unconfigured' in text
    assert not lidar.main.publishers  # scan is created at configure
    assert (f"{SYSTEM}:27:3: warning: /sensors/lidar is a lifecycle node observed before "
            "'configure'") in result.stderr
    assert '[NODL413]' in result.stderr


def test_composable_nodes_are_recorded_in_nodes_yaml(described) -> None:
    out, _ = described
    text = unmark((out / 'demo_robot' / 'nodes.yaml').read_text(encoding='utf-8'))
    assert yaml.safe_load(text) == {'camera_driver': {'plugin': 'demo_robot::CameraDriver'}}
    assert text.startswith('# What registrations would record for demo_robot')


def test_the_overlay_is_a_valid_definitions_folder(described) -> None:
    from nodl.registry.overlay import read_folder

    out, _ = described
    folder = read_folder(str(out))
    assert folder.diagnostics == []
    assert sorted(folder.nodes) == [('demo_robot', k) for k in
                                    ('camera_driver', 'container', 'lidar_driver', 'listener',
                                     'talker')]
    assert folder.info[('demo_robot', 'camera_driver')].plugin == 'demo_robot::CameraDriver'


def test_nodes_not_launched_are_left_out(system, tmp_path: Path) -> None:
    """A hidden tool's node and a node the launch file does not start are not described."""
    extra = NodeProcess('plain_node.py', '_tool', '/')
    other = NodeProcess('plain_node.py', 'stranger', '/')
    try:
        result = nodl('describe', '--all', '--launch', str(SYSTEM), '-o', str(tmp_path),
                      '--timeout', '15', '--no-parameters')
    finally:
        extra.stop()
        other.stop()
    assert result.returncode == 0, result.stderr
    # (the run ends once the launched nodes are stable: the others are listed if seen by then)
    left_out = [line for line in result.stderr.splitlines() if line.startswith('  left out: ')]
    assert set(left_out) <= {'  left out: /_tool: a hidden node (its name starts with _)',
                             f'  left out: /stranger: not started by {SYSTEM}'}, left_out
    assert not list(tmp_path.rglob('stranger*')) and not list(tmp_path.rglob('plain*'))
    assert 'stranger' not in result.stdout and '_tool' not in result.stdout


def test_a_node_not_running_is_an_error(tmp_path: Path) -> None:
    result = nodl('describe', '--all', '--launch', str(HERE / 'hidden.launch.xml'), '-o',
                  str(tmp_path), '--timeout', '1', '--no-parameters')
    assert result.returncode == 1, result.stderr
    assert (f'{HERE / "hidden.launch.xml"}:4:3: error: /lonely_listener (demo_robot listener) was not '
            'seen in the graph within 1 s') in result.stderr
    assert '[NODL409]' in result.stderr
    # the hidden node is left out, not waited for
    assert '  left out: /_probe: a hidden node (its name starts with _)' in result.stderr


def test_instances_that_differ_by_their_parameters(tmp_path: Path) -> None:
    launch = HERE / 'params_differ.launch.xml'
    started = start_launched(launch)
    try:
        result = nodl('describe', '--all', '--launch', str(launch), '-o', str(tmp_path),
                      '--timeout', '15')
    finally:
        for process in started:
            process.stop()
    assert result.returncode == 0, result.stderr
    text, talker = _definition(tmp_path / 'demo_robot' / 'talker.nodl.yaml')
    # ~/debug exists on one instance only, because of its parameters: left out, and said
    assert {p.name for p in talker.main.publishers} == {'chatter', 'diagnostics'}
    assert ('# Not in the definition: publisher ~/debug (std_msgs/msg/Bool): seen on '
            '/debug_talker, not on /quiet_talker; their parameters differ (debug), which a '
            'definition cannot express.') in text
    assert '[NODL411]' in result.stderr and '/debug_talker' in result.stderr
    # the default of debug is read from the instance the launch does not set it on
    assert talker.main.parameters['debug'].default_value is False


def test_no_exec_applies_to_the_launch_file(tmp_path: Path) -> None:
    launch = tmp_path / 'system.launch.py'
    launch.write_text('def generate_launch_description():\n    raise SystemExit(3)\n',
                      encoding='utf-8')
    result = nodl('describe', '--all', '--launch', str(launch), '-o', str(tmp_path / 'out'),
                  '--no-exec')
    assert result.returncode == 2, result.stderr
    assert '[NODL525]' in result.stderr
    assert not (tmp_path / 'out').exists() or not list((tmp_path / 'out').iterdir())


@pytest.mark.parametrize('args, message', [
    (['--launch', 'x.launch.xml', '-o', 'out'], '--launch describes a whole system: give --all'),
    (['--all', '-o', 'out', '--no-exec'], '--no-exec is about the launch file: it needs --launch'),
    (['--all', '--launch', 'missing.launch.xml', '-o', 'out'],
     'missing.launch.xml: error: cannot read the launch file: no such file [NODL020]'),
    (['--all', '--launch', str(SYSTEM), 'rate', '-o', 'out'],
     "launch argument 'rate' is not NAME:=VALUE"),
    (['--all', '-o', 'out', '--missing'],
     '--missing is about the nodes a launch file starts: it needs --all --launch'),
    (['/talker', '--definitions', 'defs'],
     '--definitions is about the nodes a launch file starts: it needs --all --launch'),
    (['--all', '--launch', str(SYSTEM), '--definitions', 'no/such/defs', '-o', 'out'],
     'nodl describe: error: --definitions no/such/defs: no such folder [NODL246]'),
])
def test_usage_errors(args: list[str], message: str) -> None:
    result = nodl('describe', *args)
    assert result.returncode == 2
    assert message in result.stderr


# -- the round trip: the overlay analysed against the same running system ------------------


def _live_endpoints(fqns: list[str]) -> dict[str, set[tuple[str, str]]]:
    """What the live graph shows of each node: ``(section, final name)`` of its own endpoints."""
    from nodl.live.observe import observe_settled, settle_nodes
    from nodl.live.session import ros_session

    with ros_session() as session:
        raw, _ = settle_nodes(session, {fqn: 1 for fqn in fqns}, 15)
        out = {}
        for fqn in fqns:
            observed = observe_settled(session, fqn, raw[fqn])
            out[fqn] = {(section, e.name) for section in
                        ('publishers', 'subscriptions', 'service_servers', 'service_clients',
                         'action_servers', 'action_clients') for e in getattr(observed, section)}
    return out


def test_round_trip_the_overlay_serves_the_analysis_of_the_same_system(described) -> None:
    from nodl.registry.overlay import read_folders, using

    out, _ = described
    result = nodl('analyse', str(SYSTEM), 'rate:=5', '--definitions', str(out), '--format', 'json')
    report = json.loads(result.stdout)
    findings = [(f['code'], f['message']) for f in report['findings']
                if f['severity'] in ('error', 'warning')]
    # no node lacks a definition; the only findings are the system's real problems
    assert not [f for f in findings if f[0] == 'NODL564'], findings
    topics = sorted((code, message.split()[1]) for code, message in findings)
    assert topics == [('NODL551', '/diagnostics'), ('NODL551', '/shared/chatter'),
                      ('NODL552', '/diagnostics'), ('NODL555', 'subscription')], findings
    assert '/cmd_vel' in findings[-1][1]

    # every final endpoint name the analysis computes is one the live graph shows
    with using(read_folders([(str(out), '--definitions')])):
        analysis = analyse_launch(SYSTEM, {'rate': '5'}, checks={})
    computed = {}
    for node in analysis.nodes:
        assert node.instance is not None, node
        computed[node.fqn] = {e.name for e in node.instance.endpoints}
    live = _live_endpoints(sorted(computed))
    for fqn, finals in computed.items():
        assert finals == {name for _, name in live[fqn]}, fqn
    assert '/shared/chatter' in computed['/left/talker']
    assert '/sensors/front/image' in computed['/sensors/front_camera']


def test_the_readme_quotes_what_the_tool_prints(described) -> None:
    import re

    out, result = described
    from site_pages import docs_text

    readme = docs_text()
    block = re.search(r'```text\n\$ nodl describe --all --launch system\.launch\.xml rate:=5 -o '
                      r'overlay\n(.*?)```', readme, re.S)
    assert block, 'the docs lost their describe --all --launch example'
    assert result.stdout.replace(str(out), 'overlay') == block.group(1)
