"""Issue 17 end to end: a system whose definitions come from everywhere an integrator finds them.

The cart of tests/fixtures/integration_definitions/launch/cart.launch.xml starts eight nodes:

* two REGISTERED by their packages, built for real with colcon (module scope):
  ``cart_base`` (ament_cmake, ``ament_nodl_register_node ... NODE_NAME``) and
  ``cart_safety`` (ament_python, ``nodl_data_files(..., node_names=)``);
* two in a definitions folder written BY HAND (``hand/``: sick_lidar, joy_teleop with a
  ``nodes.yaml`` naming its node);
* two EXTRACTED by ``nodl extract`` from the rclpy sources of ``src/cart_autonomy`` (entry
  points in its setup.py; one draft holds a gap);
* two DESCRIBED by ``nodl describe --all --launch --missing`` from the running system: the
  vendors' nodes, started as real processes from the analysis's own records
  (tests/nodes/vendor_node.py plays them; ``ros2 launch`` is not installable here).

Then ``nodl analyse`` with the three folders (``--definitions``, ``NODL_PATH``, ``nodl.toml``)
covers every node, says where each definition came from, and finds exactly the planted
problems; ``nodl policy`` writes a profile for every node.  The system integrators'
guide (ros/nodl_toolkit/doc/guides/system-integrators.md), "From a launch file to a fully
covered system", quotes what these commands print.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from conftest import FIXTURES, REPO, NodeProcess

VENV = Path(sys.prefix)
HERE = FIXTURES / 'integration_definitions'
LAUNCH = HERE / 'launch' / 'cart.launch.xml'
HAND = HERE / 'hand'
SOURCES = HERE / 'src' / 'cart_autonomy'
#: The launched nodes by where their definitions come from.
REGISTERED = {'/cart/motor_driver': 'cart_base', '/cart/safety': 'cart_safety'}
BY_HAND = {'/cart/lidar': 'sick_lidar', '/cart/teleop': 'joy_teleop'}
EXTRACTED = {'/cart/planner': 'cart_autonomy', '/cart/mission': 'cart_autonomy'}
DESCRIBED = {'/cart/front_camera': 'vendor_camera', '/cart/bridge': 'vendor_bridge'}
#: Every planted problem (code, line of cart.launch.xml, endpoint, nodes) and nothing else.
PLANTED = [
    ('NODL552', 15, '/cart/cmd_vel', ['/cart/motor_driver', '/cart/planner']),
    ('NODL553', 19, '/cart/scan', ['/cart/lidar', '/cart/safety']),
    ('NODL559', 42, '/cart/telemetry', ['/cart/bridge']),
    # the draft's gap, filled in: its progress topic has no subscriber (an info)
    ('NODL558', 32, '/cart/mission/progress', ['/cart/mission']),
]
COVERED = '8 nodes: 2 registered, 6 overlay (2 extracted, 2 described), 0 without definition'


class Workspace:
    """The colcon-built workspace and the folders the integrator writes."""

    def __init__(self, root: Path) -> None:
        self.root = root
        self.install = root / 'install'
        self.extracted = root / 'extracted'
        self.described = root / 'described'

    def env(self, **extra: str) -> dict[str, str]:
        env = dict(os.environ, AMENT_PREFIX_PATH=os.pathsep.join([str(self.install), str(VENV)]),
                   **extra)
        if 'NODL_PATH' not in extra:
            env.pop('NODL_PATH', None)
        return env

    def nodl(self, *args: str, cwd: Path = REPO, timeout: float = 60,
             **extra: str) -> subprocess.CompletedProcess[str]:
        result = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=cwd,
                                env=self.env(**extra), text=True, capture_output=True,
                                timeout=timeout)
        assert 'Traceback' not in result.stdout + result.stderr, result.stderr
        return result

    def folders(self) -> list[str]:
        return ['--definitions', str(HAND), '--definitions', str(self.extracted),
                '--definitions', str(self.described)]


@pytest.fixture(scope='module')
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Workspace:
    root = tmp_path_factory.mktemp('cart_ws')
    for package in ('cart_base', 'cart_safety'):  # a copy: setup.py stages next to itself
        shutil.copytree(HERE / 'ws' / package, root / 'src' / package)
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)
    env.update(AMENT_PREFIX_PATH=str(VENV), CMAKE_PREFIX_PATH=str(VENV),
               PATH=os.pathsep.join([str(VENV / 'bin'), env.get('PATH', '')]))
    result = subprocess.run([str(VENV / 'bin' / 'colcon'), 'build', '--merge-install',
                             '--event-handlers', 'console_cohesion-'], cwd=root, env=env,
                            text=True, capture_output=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    return Workspace(root)


@pytest.fixture(scope='module')
def extracted(workspace: Workspace) -> subprocess.CompletedProcess[str]:
    done = workspace.nodl('extract', str(SOURCES), '-o', str(workspace.extracted))
    fill_the_gap(workspace.extracted / 'cart_autonomy' / 'mission.nodl.yaml')
    return done


def fill_the_gap(draft: Path) -> None:
    """What the integrator does with the draft's one gap (the guide's step): the progress
    topic is the parameter's value, '~/progress' by default and in this launch; write it in
    and uncomment the entity.  The GAP comment stays above it, as a reviewer would leave it."""
    lines = draft.read_text(encoding='utf-8').splitlines()
    start = next(i for i, line in enumerate(lines)
                 if line.strip() == '# fill in what is missing, then uncomment:')
    end = start + 1
    while end < len(lines) and lines[end].startswith('    # '):
        end += 1
    body = [line.replace('    # ', '    ', 1) for line in lines[start + 1:end]]
    assert body[0] == '    - type: std_msgs/msg/String', body
    lines[start + 1:end] = ['    - name: ~/progress', '      ' + body[0].lstrip('- ').lstrip(),
                            *body[1:]]
    draft.write_text('\n'.join(lines) + '\n', encoding='utf-8')


def _value(value: Any) -> str:
    return value if isinstance(value, str) else json.dumps(value)


def start_undefined(workspace: Workspace) -> list[NodeProcess]:
    """Start, as launch would, the launched nodes no definition covers yet (the vendors')."""
    from nodl.analysis import analyse_launch
    from nodl.targets.resolve import gather_definitions

    definitions = gather_definitions([str(HAND), str(workspace.extracted)], environ={},
                                     use_config=False)
    analysis = analyse_launch(LAUNCH, {}, checks={}, definitions=definitions,
                              prefixes=[str(workspace.install), str(VENV)])
    started: list[NodeProcess] = []
    try:
        for node in analysis.nodes:
            if node.match.file is not None:
                continue
            executable = node.entry.executable
            assert executable is not None
            ros_args = ['-r', f'__node:={node.created_name}', '-r', f'__ns:={node.entry.namespace}']
            for a, b in node.entry.remaps:
                ros_args += ['-r', f'{a}:={b}']
            for name, value in node.parameter_values().items():
                ros_args += ['-p', f'{name}:={_value(value)}']
            started.append(NodeProcess('vendor_node.py', executable, '/', '--role', executable,
                                       '--ros-args', *ros_args))
    except BaseException:
        for process in started:
            process.stop()
        raise
    return started


@pytest.fixture(scope='module')
def described(workspace: Workspace, extracted: subprocess.CompletedProcess[str]
              ) -> Iterator[subprocess.CompletedProcess[str]]:
    started = start_undefined(workspace)
    try:
        assert sorted(p.name for p in started) == ['camera_node', 'cloud_bridge']
        yield workspace.nodl('describe', '--all', '--launch', str(LAUNCH), '--missing',
                             '--definitions', str(HAND), '--definitions', str(workspace.extracted),
                             '-o', str(workspace.described), '--timeout', '15')
    finally:
        for process in started:
            process.stop()


@pytest.fixture(scope='module')
def report(workspace: Workspace, described: subprocess.CompletedProcess[str]) -> dict[str, Any]:
    result = workspace.nodl('analyse', str(LAUNCH), *workspace.folders(), '--format', 'json')
    assert result.returncode == 1, result.stdout + result.stderr  # the planted errors
    data: dict[str, Any] = json.loads(result.stdout)
    return data


# -- step by step: what the integrator sees -------------------------------------------------


def test_before_any_folder_only_the_packages_own_definitions_serve(workspace: Workspace) -> None:
    result = workspace.nodl('analyse', str(LAUNCH))
    lines = result.stdout.splitlines()
    assert lines[-2] == '8 nodes: 2 registered, 0 overlay, 6 without definition'
    missing = sorted(line.split(': ')[2].split()[0] for line in lines if '[NODL564]' in line)
    # (without its folder's nodes.yaml, the teleop's node name is the executable's, assumed)
    assert missing == sorted(['/cart/lidar', '/cart/teleop_node', *EXTRACTED, *DESCRIBED]), lines


def test_extract_drafts_the_sources_it_has_into_the_overlay_layout(
        workspace: Workspace, extracted: subprocess.CompletedProcess[str]) -> None:
    assert extracted.returncode == 0, extracted.stderr
    files = sorted(str(p.relative_to(workspace.extracted))
                   for p in workspace.extracted.rglob('*') if p.is_file())
    assert files == ['cart_autonomy/mission.nodl.yaml', 'cart_autonomy/nodes.yaml',
                     'cart_autonomy/planner.nodl.yaml']
    # the progress topic's name is a parameter's value: a located gap, never a guess
    assert (f'{SOURCES}/cart_autonomy/mission.py:25:55: warning: topic name is computed at run '
            "time (it comes from parameter 'progress_topic') [NODL901]") in extracted.stdout
    assert '# GAP ' in (workspace.extracted / 'cart_autonomy' / 'mission.nodl.yaml').read_text()


def test_describe_missing_describes_only_what_nothing_defines(
        workspace: Workspace, described: subprocess.CompletedProcess[str]) -> None:
    assert described.returncode == 0, described.stderr
    files = sorted(str(p.relative_to(workspace.described))
                   for p in workspace.described.rglob('*') if p.is_file())
    assert files == ['vendor_bridge/cloud_bridge.nodl.yaml', 'vendor_camera/camera_node.nodl.yaml']
    # the six covered nodes were not waited for (they are not running): left out, saying why
    left_out = [line for line in described.stderr.splitlines() if line.startswith('  left out: ')]
    assert len(left_out) == 6, described.stderr
    assert (f'  left out: /cart/teleop: has a definition: {HAND}/joy_teleop/teleop_node.nodl.yaml '
            f'(overlay {HAND})') in left_out
    assert (f'  left out: /cart/planner: has a definition: {workspace.extracted}/cart_autonomy/'
            f'planner.nodl.yaml (overlay {workspace.extracted}, extracted)') in left_out
    assert any(line.startswith('  left out: /cart/motor_driver: has a definition: ') and
               line.endswith('motor_driver.nodl.yaml (index)') for line in left_out)
    assert '[NODL409]' not in described.stderr
    # remaps undone: the camera declares image_raw, launched as front/image
    camera = (workspace.described / 'vendor_camera' / 'camera_node.nodl.yaml').read_text()
    assert '  - name: image_raw\n' in camera


def test_describe_missing_with_everything_defined_describes_nothing(workspace: Workspace,
                                                                    described, tmp_path) -> None:  # type: ignore[no-untyped-def]
    result = workspace.nodl('describe', '--all', '--launch', str(LAUNCH), '--missing',
                            *workspace.folders(), '-o', str(tmp_path / 'out'), '--timeout', '1')
    assert result.returncode == 0, result.stderr
    assert result.stdout == ''
    assert 'has a definition: nothing to describe' in result.stderr
    assert not (tmp_path / 'out').exists() or not list((tmp_path / 'out').rglob('*'))


def test_describe_refreshes_its_own_folder_even_when_it_is_in_force(workspace: Workspace,
                                                                     described) -> None:  # type: ignore[no-untyped-def]
    """-o DIR is what the run replaces: a folder in NODL_PATH that is also -o DIR does not
    count as covering the nodes it holds (else a second describe would skip them)."""
    started = start_undefined(workspace)
    try:
        again = workspace.nodl('describe', '--all', '--launch', str(LAUNCH), '--missing',
                               '--definitions', str(HAND), '--definitions', str(workspace.extracted),
                               '-o', str(workspace.described), '--timeout', '15',
                               NODL_PATH=str(workspace.described))
    finally:
        for process in started:
            process.stop()
    assert again.returncode == 0, again.stderr
    assert sorted(again.stdout.splitlines()) == [
        f'{workspace.described}/vendor_bridge/cloud_bridge.nodl.yaml <- /cart/bridge',
        f'{workspace.described}/vendor_camera/camera_node.nodl.yaml <- /cart/front_camera']


# -- the three together -----------------------------------------------------------------------


def test_every_node_is_covered_and_says_where_its_definition_came_from(
        workspace: Workspace, report: dict[str, Any]) -> None:
    sources = {n['name']: (n['definition_source'], n['definition_folder'],
                           n['definition_provenance']) for n in report['nodes']}
    expected = {name: ('index', None, None) for name in REGISTERED}
    expected.update({name: ('overlay', str(HAND), None) for name in BY_HAND})
    expected.update({name: ('overlay', str(workspace.extracted), 'extracted') for name in EXTRACTED})
    expected.update({name: ('overlay', str(workspace.described), 'described') for name in DESCRIBED})
    assert sources == expected
    for node in report['nodes']:
        package = {**REGISTERED, **BY_HAND, **EXTRACTED, **DESCRIBED}[node['name']]
        assert node['package'] == package
        if node['name'] in REGISTERED:
            assert node['definition'].startswith(str(workspace.install)), node
    assert not [f for f in report['findings'] if f['code'] == 'NODL564']


def test_the_findings_are_exactly_the_planted_problems(report: dict[str, Any]) -> None:
    found = sorted((f['code'], f['line'], f.get('endpoint'), sorted(f['nodes']))
                   for f in report['findings'])
    assert found == sorted(PLANTED), json.dumps(report['findings'], indent=1)
    for finding in report['findings']:
        assert finding['file'] == str(LAUNCH)
    # the values the launch gives reach the nodes, whatever served their definitions
    parameters = {n['name']: n['parameters'] for n in report['nodes']}
    assert parameters['/cart/motor_driver'] == {'wheel_radius': 0.12}
    assert parameters['/cart/planner'] == {'max_speed': 0.8}
    assert parameters['/cart/front_camera'] == {'fps': 15}
    endpoints = {n['name']: n['endpoints'] for n in report['nodes']}
    assert ['image_raw', '/cart/front/image'] in endpoints['/cart/front_camera']['publishers']
    assert ['image', '/cart/front/image'] in endpoints['/cart/bridge']['subscriptions']


def test_the_text_report_ends_with_the_coverage_line(workspace: Workspace, described) -> None:  # type: ignore[no-untyped-def]
    result = workspace.nodl('analyse', str(LAUNCH), *workspace.folders(), '-v')
    lines = result.stdout.splitlines()
    assert lines[-2:] == [COVERED, '8 nodes, 2 errors, 1 warning, 1 info']
    assert (f'/cart/front_camera: {workspace.described}/vendor_camera/camera_node.nodl.yaml '
            f'(overlay {workspace.described}, described)') in lines


def test_nodl_path_and_nodl_toml_give_the_same_folders(workspace: Workspace, described,
                                                       tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    via_env = workspace.nodl('analyse', str(LAUNCH), '--definitions', str(workspace.extracted),
                             '--definitions', str(workspace.described), '--format', 'json',
                             NODL_PATH=str(HAND))
    # a project folder holding the launch file and its nodl.toml, the hand folder beside it
    shutil.copytree(HERE / 'launch', tmp_path / 'launch')
    shutil.copytree(HERE / 'config', tmp_path / 'config')
    shutil.copytree(HAND, tmp_path / 'defs')
    (tmp_path / 'launch' / 'nodl.toml').write_text('definitions = ["../defs"]\n', encoding='utf-8')
    via_config = workspace.nodl('analyse', str(tmp_path / 'launch' / 'cart.launch.xml'),
                                '--definitions', str(workspace.extracted),
                                '--definitions', str(workspace.described), '--format', 'json')
    for result, folder in ((via_env, str(HAND)), (via_config, str(tmp_path / 'defs'))):
        assert result.returncode == 1, result.stderr
        data = json.loads(result.stdout)
        assert COVERED in result.stderr
        assert {n['name']: n['definition_folder'] for n in data['nodes']
                if n['name'] in BY_HAND} == {name: folder for name in BY_HAND}
        assert sorted((f['code'], f['line']) for f in data['findings']) == \
            sorted((code, line) for code, line, _, _ in PLANTED)


def test_the_first_folder_that_defines_a_node_wins(workspace: Workspace, described,
                                                   tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    """The integrator fixes the lidar's QoS in a folder of their own, given first: it shadows
    the hand folder (in NODL_PATH), and the incompatibility is gone; nothing else changes."""
    fixed = tmp_path / 'fixes' / 'sick_lidar'
    fixed.mkdir(parents=True)
    (fixed / 'lidar_node.nodl.yaml').write_text(
        (HAND / 'sick_lidar' / 'lidar_node.nodl.yaml').read_text().replace(
            'reliability: BEST_EFFORT', 'reliability: RELIABLE'), encoding='utf-8')
    result = workspace.nodl('analyse', str(LAUNCH), '--definitions', str(tmp_path / 'fixes'),
                            '--definitions', str(workspace.extracted),
                            '--definitions', str(workspace.described), '--format', 'json',
                            NODL_PATH=str(HAND))
    data = json.loads(result.stdout)
    folders = {n['name']: n['definition_folder'] for n in data['nodes']}
    assert folders['/cart/lidar'] == str(tmp_path / 'fixes')
    assert folders['/cart/teleop'] == str(HAND)
    assert sorted(f['code'] for f in data['findings']) == ['NODL552', 'NODL558', 'NODL559']


def test_policy_covers_every_node(workspace: Workspace, described, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / 'cart.policy.xml'
    result = workspace.nodl('policy', str(LAUNCH), *workspace.folders(), '-o', str(out))
    assert result.returncode == 0, result.stderr
    assert result.stderr.splitlines()[-1] == COVERED
    from xml.etree import ElementTree

    profiles = {(p.get('ns'), p.get('node')) for p in ElementTree.parse(out).iter('profile')}
    assert profiles == {('/cart', name.rsplit('/', 1)[1]) for name in
                        [*REGISTERED, *BY_HAND, *EXTRACTED, *DESCRIBED]}
    text = out.read_text()
    # each from its own definition: the extracted planner's, the described camera's topics
    assert '<topic>cmd_vel</topic>' in text and '<topic>front/image</topic>' in text


# -- the README quotes it -----------------------------------------------------------------------


def _quoted(section: str, command: str) -> list[str] | None:
    """The lines a ```text block of the section quotes after ``$ command`` (the blocks are
    indented in a list), or None."""
    block = re.search(r'```text\n( *)\$ ' + re.escape(command) + r'\n(.*?)\n *```', section, re.S)
    if block is None:
        return None
    indent = len(block.group(1))
    return [line[indent:] for line in block.group(2).splitlines()]


def test_the_readme_quotes_what_the_flow_prints(workspace: Workspace, described) -> None:  # type: ignore[no-untyped-def]
    from site_pages import page

    readme = page('guides/system-integrators')
    section = readme[readme.index('## From a launch file to a fully covered system'):]
    final = _quoted(section, 'nodl analyse cart.launch.xml --definitions hand --definitions '
                             'extracted --definitions described')
    assert final, "the docs lost the flow's final analysis"
    result = workspace.nodl('analyse', str(LAUNCH), *workspace.folders())
    assert result.stdout.replace(str(LAUNCH), 'cart.launch.xml').splitlines() == final
    first = _quoted(section, 'nodl analyse cart.launch.xml')
    assert first, "the docs lost the flow's first analysis"
    before = workspace.nodl('analyse', str(LAUNCH)).stdout.replace(str(LAUNCH), 'cart.launch.xml')
    quoted = [line for line in first if line != '...']
    assert before.splitlines()[-len(quoted):] == quoted
