"""`nodl policy` as users run it: definitions, -o, --check, usage errors, exit statuses."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from conftest import REPO

POLICY = 'tests/fixtures/policy'


def nodl(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    result = subprocess.run([sys.executable, '-m', 'nodl', 'policy', *args], cwd=REPO, text=True,
                            capture_output=True, timeout=timeout)
    assert 'Traceback' not in result.stdout + result.stderr, result.stderr
    return result


def test_definitions_to_stdout_match_the_library_golden():
    result = nodl(f'{POLICY}/talker.nodl.yaml', f'{POLICY}/listener.nodl.yaml')
    assert result.returncode == 0, result.stderr
    expected = (REPO / POLICY / 'expected' / 'talker_listener.policy.xml').read_text()
    body = lambda text: text.split('<policy', 1)[1]  # noqa: E731 (the header note differs)
    assert body(result.stdout) == body(expected)


def test_parameters_names_remaps_and_output_file(tmp_path: Path):
    out = tmp_path / 'p.xml'
    result = nodl(f'{POLICY}/relay.nodl.yaml', 'use_sim_time:=true', '--name', '/robot/relay',
                  '--remap', 'input:=/sensors/raw', '-o', str(out), '--distro', 'humble')
    assert result.returncode == 0 and result.stdout == '', result.stderr
    text = out.read_text()
    assert '<topic>/clock</topic>' in text and '<topic>/sensors/raw</topic>' in text
    assert 'get_type_description' not in text  # humble
    assert '<profile ns="/robot" node="relay">' in text


def test_check_reports_missing_and_extra_with_exit_status(tmp_path: Path):
    good = tmp_path / 'good.xml'
    assert nodl(f'{POLICY}/talker.nodl.yaml', '-o', str(good)).returncode == 0
    result = nodl('--check', str(good), f'{POLICY}/talker.nodl.yaml')
    assert result.returncode == 0 and 'grants exactly what the system needs' in result.stderr
    widened = tmp_path / 'widened.xml'
    widened.write_text(good.read_text().replace(
        '<topics publish="ALLOW">', '<topics publish="ALLOW">\n            <topic>/cmd_vel</topic>'))
    result = nodl('--check', str(widened), f'{POLICY}/talker.nodl.yaml', f'{POLICY}/listener.nodl.yaml')
    assert result.returncode == 1
    lines = result.stdout.splitlines()
    assert [line.rsplit(' ', 1)[-1] for line in lines] == ['[NODL607]', '[NODL605]']
    assert lines[1].startswith(f'{widened}:') and '/cmd_vel' in lines[1]
    assert 'no profile for /listener' in lines[0]
    assert '1 missing, 1 extra' in result.stderr


def test_usage_errors_exit_2():
    assert nodl().returncode == 2
    assert nodl('no_such.nodl.yaml').returncode == 2
    assert nodl('--live', f'{POLICY}/talker.nodl.yaml').returncode == 2
    result = nodl(f'{POLICY}/talker.nodl.yaml', '--distro', 'foxy')
    assert result.returncode == 2 and "unknown distribution 'foxy'" in result.stderr
    assert "expected one of: humble, iron, jazzy, kilted, rolling" in result.stderr
    result = nodl(f'{POLICY}/talker.nodl.yaml', '--distro', '')  # not the default in disguise
    assert result.returncode == 2 and "unknown distribution ''" in result.stderr
    result = nodl(f'{POLICY}/talker.nodl.yaml', '--name', '/a', '--name', '/b')
    assert result.returncode == 2 and '2 --name options for 1 definitions' in result.stderr
    result = nodl(f'{POLICY}/talker.nodl.yaml', '--name', '/bad name')
    assert result.returncode == 2 and result.stderr.count('\n') == 1


def test_invalid_definition_exits_1_without_writing(tmp_path: Path):
    bad = tmp_path / 'bad.nodl.yaml'
    bad.write_text('nodl_version: 2\nbase: node\nmain: {nodl_version: 2, publishers: [{name: x}]}\n')
    result = nodl(str(bad))
    assert result.returncode == 1 and result.stdout == ''
    assert f'{bad}:3:' in result.stderr and 'no policy written' in result.stderr


def test_a_policy_for_nodes_registered_by_the_references_ament_nodl_register(tmp_path: Path):
    import os

    fixtures = REPO / 'tests' / 'fixtures' / 'index'
    env = dict(os.environ, AMENT_PREFIX_PATH=str(fixtures / 'reference'))
    out = tmp_path / 'robot.policy.xml'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'policy',
                             str(fixtures / 'reference_launch' / 'robot.launch.xml'), '-o', str(out)],
                            cwd=REPO, env=env, text=True, capture_output=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    policy = out.read_text()
    for enclave in ('/talker', '/listener', '/front/lidar'):
        assert f'<enclave path="{enclave}">' in policy
    # From the flat documents, and through the lidar's rewritten include.
    assert '<topic>chatter</topic>' in policy
    assert "subscription '/clock' (nodl://ref_robot/sensor_common)" in policy
    # A definition given as PACKAGE EXECUTABLE (here the PACKAGE override's) is found too.
    named = subprocess.run([sys.executable, '-m', 'nodl', 'policy', 'custom_pkg', 'custom_exe',
                            '--name', '/reset_node'], cwd=REPO, env=env, text=True,
                           capture_output=True, timeout=60)
    assert named.returncode == 0, named.stdout + named.stderr
    assert '<service>~/reset</service>' in named.stdout


def test_a_python_launch_file_runs_in_the_sandbox_and_no_exec_refuses_it() -> None:
    launch = 'tests/fixtures/launch/sandbox/good.launch.py'
    result = nodl(launch, '--allow-missing')
    assert result.returncode == 0, result.stderr
    assert '<enclave path="/talker">' in result.stdout
    result = nodl(launch, '--no-exec')
    assert result.returncode == 2 and 'is not run: --no-exec is set' in result.stderr
    assert '[NODL525]' in result.stderr


def test_name_options_may_come_between_the_targets():
    """--name interleaved with the targets (talker --name /a listener --name /b): every target
    is read, the i-th --name places the i-th definition (argparse refused the second target)."""
    result = nodl(f'{POLICY}/talker.nodl.yaml', '--name', '/robot/a', f'{POLICY}/listener.nodl.yaml',
                  '--name', '/robot/b')
    assert result.returncode == 0, result.stderr
    assert '<profile ns="/robot" node="a">' in result.stdout
    assert '<profile ns="/robot" node="b">' in result.stdout


def test_a_duplicate_name_says_no_policy_is_written_unless_ignored():
    """NODL611 says what happens: no policy, unless it is ignored (then one profile)."""
    result = nodl(f'{POLICY}/talker.nodl.yaml', '--name', '/x', f'{POLICY}/listener.nodl.yaml',
                  '--name', '/x')
    assert result.returncode == 1 and result.stdout == ''
    assert 'so no policy is written' in result.stderr and '--ignore NODL611' in result.stderr
    assert 'merged into one profile' not in result.stderr
    ignored = nodl(f'{POLICY}/talker.nodl.yaml', '--name', '/x', f'{POLICY}/listener.nodl.yaml',
                   '--name', '/x', '--ignore', 'NODL611')
    assert ignored.returncode == 0, ignored.stderr
    assert ignored.stdout.count('<profile ns="/" node="x">') == 1


def test_definitions_folders_serve_nodes_and_the_coverage_line_says_so() -> None:
    overlays = REPO / 'tests' / 'fixtures' / 'overlays'
    env = dict(os.environ, AMENT_PREFIX_PATH=str(REPO / 'tests' / 'fixtures' / 'analysis' / 'prefix'))
    env.pop('NODL_PATH', None)

    def policy(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([sys.executable, '-m', 'nodl', 'policy', *args], cwd=REPO,
                              env=env, text=True, capture_output=True, timeout=60)

    done = policy('upstream_drv', 'driver', 'nav', 'controller',
                  '--definitions', str(overlays / 'defs'))
    assert done.returncode == 0, done.stderr
    assert '<topic>status</topic>' in done.stdout  # from the folder's nodl:// mixin
    assert done.stderr == '2 nodes: 0 registered, 2 overlay (1 extracted), 0 without definition\n'
    launched = policy(str(overlays / 'launch' / 'system.launch.xml'),
                      '--definitions', str(overlays / 'defs'))
    assert launched.returncode == 1 and '[NODL601]' in launched.stderr
    assert '4 nodes: 1 registered, 2 overlay (1 extracted), 1 without definition' in launched.stderr
    bad = policy('nav', 'planner', '--definitions', str(overlays / 'bad'))
    assert bad.returncode == 1 and '[NODL242]' in bad.stderr and 'no policy written' in bad.stderr


def test_an_extracted_draft_with_gaps_is_no_policy_unless_allow_gaps() -> None:
    """NODL617: a draft's unresolved entities would be denied at run time: an error (no policy)
    unless --allow-gaps, then a warning and a GAP comment in the profile for each entity."""
    gaps = REPO / 'tests' / 'fixtures' / 'overlays' / 'gaps'
    env = dict(os.environ, AMENT_PREFIX_PATH=str(REPO / 'tests' / 'fixtures' / 'analysis' / 'prefix'))
    env.pop('NODL_PATH', None)

    def policy(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([sys.executable, '-m', 'nodl', 'policy', *args], cwd=REPO,
                              env=env, text=True, capture_output=True, timeout=60)

    launch = str(gaps / 'launch' / 'system.launch.xml')
    refused = policy(launch, '--definitions', str(gaps / 'defs'))
    assert refused.returncode == 1 and refused.stdout == ''
    assert refused.stderr.count('[NODL617]') == 1 and 'system.launch.xml:3:3: error: /relay' in refused.stderr
    assert '3 unresolved entities' in refused.stderr and '--allow-gaps' in refused.stderr
    allowed = policy(launch, '--definitions', str(gaps / 'defs'), '--allow-gaps')
    assert allowed.returncode == 0, allowed.stderr
    assert allowed.stderr.count('warning: /relay') == 1 and '[NODL617]' in allowed.stderr
    assert allowed.stdout.count('<!-- GAP: ') == 3
    assert 'GAP: a subscription of the extracted draft is unresolved' in allowed.stdout
    # placed by name too (the draft's first GAP line is the place); the complete camera: none
    placed = policy('relay_pkg', 'relay', '--definitions', str(gaps / 'defs'))
    assert placed.returncode == 1 and 'relay.nodl.yaml:22:5: error: /relay' in placed.stderr
    camera = policy('camera_pkg', 'camera', '--definitions', str(gaps / 'defs'))
    assert camera.returncode == 0 and 'NODL617' not in camera.stderr
