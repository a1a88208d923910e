"""`make demo`: the toolkit's main jobs on the bundled examples, narrated.

Every step runs the real `nodl` command (or colcon), as a user would; every
process the demo starts is stopped before it ends.
"""

from __future__ import annotations

import os
import shlex
import shutil
import signal
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
OUT = REPO / 'demo-out'
NODL = [sys.executable, '-m', 'nodl']
SYSTEM = HERE / 'system'
SYSTEM_PACKAGES = ('rover_base', 'rover_sensors', 'rover_navigation', 'rover_tools')
SYSTEM_LAUNCH = 'examples/system/launch/rover.launch.xml'


def step(title: str, args: list[str], expect: int = 0, head: int | None = None,
         env: dict[str, str] | None = None) -> str:
    """Run one `nodl` command and show what it printed."""
    print(f'\n=== {title}')
    print('$ nodl ' + ' '.join(shlex.quote(a) for a in args))
    result = subprocess.run(NODL + args, cwd=REPO, text=True, capture_output=True, timeout=120,
                            env=env)
    lines = (result.stdout + result.stderr).splitlines()
    shown = lines if head is None or len(lines) <= head else lines[:head] + ['  ...']
    print('\n'.join(shown))
    print(f'(exit code {result.returncode})')
    if result.returncode != expect:
        sys.exit(f'demo: expected exit code {expect}, got {result.returncode}')
    return result.stdout


def validate_and_compose() -> None:
    step('Validate every bundled example (node, lifecycle node, interface, parameter)',
         ['validate', 'examples/'])
    step('A file full of typical mistakes: every problem at once, with FILE:LINE:COL',
         ['validate', 'examples/mistakes/typos.yaml'], expect=1)
    step('The same diagnostics as JSON, for tools',
         ['validate', '--format', 'json', '-q', 'examples/mistakes/typos.yaml'], expect=1, head=9)
    step('Compose a node: base + mixins + main, each entity with its layer',
         ['show', '--layers', 'examples/laser_driver.nodl.yaml'], head=24)
    step('Convert a legacy (XML) file: one v2 node definition per <node>',
         ['convert', 'examples/legacy/talkers.nodl.xml', '-o', str(OUT / 'converted')], head=12)


def build_workspace() -> dict[str, str]:
    """Build examples/workspace with colcon; return an environment that sees its install."""
    ws = OUT / 'ws'
    shutil.rmtree(ws, ignore_errors=True)
    shutil.copytree(HERE / 'workspace' / 'src', ws / 'src')
    for package in SYSTEM_PACKAGES:   # the example system's packages, built in the same run
        shutil.copytree(SYSTEM / package, ws / 'src' / package)
    print('\n=== Build a workspace whose packages register definitions (ament_nodl_register_*,')
    print('    nodl_data_files): examples/workspace and the example system of examples/system')
    print(f'$ cd {ws.relative_to(REPO)} && colcon build')
    colcon = Path(sys.executable).parent / 'colcon'
    result = subprocess.run([str(colcon), 'build', '--event-handlers', 'console_cohesion-'],
                            cwd=ws, text=True, capture_output=True, timeout=600)
    print('\n'.join(line for line in result.stdout.splitlines() if line.startswith(('Finished', 'Summary'))))
    if result.returncode != 0:
        print(result.stdout + result.stderr)
        sys.exit('demo: colcon build failed')
    env = dict(os.environ)
    prefixes = [str(p) for p in sorted((ws / 'install').iterdir()) if p.is_dir()]
    env['AMENT_PREFIX_PATH'] = os.pathsep.join(prefixes + [env.get('AMENT_PREFIX_PATH', '')])
    step('List the registered definitions', ['list'], env=env)
    step('Show an installed node, composed from two packages, with its layers',
         ['show', '--layers', 'laser_driver', 'laser_driver_node'], head=30, env=env)
    return env


def widen_policy(policy: str) -> str:
    """The policy with one grant more than the system needs: teleop may also publish
    cmd_vel_nav (the path follower's commands, which the safety controller trusts)."""
    profile = policy.index('<profile ns="/rover" node="teleop">')
    publish = policy.index('<topics publish="ALLOW">', profile) + len('<topics publish="ALLOW">')
    indent = '\n' + ' ' * 12
    return policy[:publish] + indent + '<topic>cmd_vel_nav</topic>' + policy[publish:]


def analyse_system(env: dict[str, str]) -> None:
    """Analyse the example system before launch, write its policy, check a widened copy."""
    out = OUT / 'system'
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    shown = out.relative_to(REPO)
    step('Analyse the example system before launch (XML including YAML and Python, 18 nodes);\n'
         '    one problem of every kind is planted, so errors are expected (exit code 1)',
         ['analyse', SYSTEM_LAUNCH, '-v', '--log', f'{shown}/rover.log',
          '--graph', f'{shown}/rover.html'], expect=1, env=env)
    step('The same analysis as JSON for tools, and the picture as SVG',
         ['analyse', SYSTEM_LAUNCH, '--format', 'json', '-o', f'{shown}/rover.json',
          '--graph', f'{shown}/rover.svg'], expect=1, env=env)
    for name in ('rover.log', 'rover.html', 'rover.svg', 'rover.json'):
        print(f'wrote {shown}/{name}' + ('   (open it in a browser: click a node)'
                                         if name.endswith('.html') else ''))
    # the planted duplicate aggregator would share one identity: leave it out for the policy;
    # web_bridge and the container have no definition: --allow-missing marks their gaps
    policy = out / 'rover.policy.xml'
    step('Write the SROS 2 policy of the system (least privilege, before it ever runs)',
         ['policy', SYSTEM_LAUNCH, 'with_aggregator:=false', '--allow-missing',
          '-o', f'{shown}/rover.policy.xml'], env=env)
    print(f'wrote {shown}/rover.policy.xml; its teleop profile (without the comments):')
    text = policy.read_text(encoding='utf-8')
    start = text.index('        <profile ns="/rover" node="teleop">')
    end = text.index('</profile>', start) + len('</profile>')
    print('\n'.join(line.split(' <!--')[0] for line in text[start:end].splitlines()))
    widened = out / 'rover.widened.policy.xml'
    widened.write_text(widen_policy(text), encoding='utf-8')
    step('Check a deliberately widened copy (teleop may also publish cmd_vel_nav): over-privilege',
         ['policy', '--check', f'{shown}/{widened.name}', SYSTEM_LAUNCH, 'with_aggregator:=false',
          '--allow-missing'], expect=1, env=env)


def live(env: dict[str, str]) -> None:
    """Start the example node, describe it, check it, and show drift."""
    print('\n=== Start the example node: examples/nodes/laser_driver_node.py in /robot')
    node = subprocess.Popen([sys.executable, str(HERE / 'nodes' / 'laser_driver_node.py'),
                             '--ros-args', '-r', '__ns:=/robot'],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        assert node.stdout is not None
        if node.stdout.readline().strip() != 'ready':
            sys.exit('demo: the example node did not start')
        step('Describe the running node (backward): what it really exposes',
             ['describe', '/robot/laser_driver_node', '--timeout', '20'], head=30, env=env)
        # the package is built with ament_cmake (whose nodes are rclcpp by default), but the
        # example node is a Python script: say which client library's base it has
        step('Check the running node against its registered definition: conforms',
             ['check', '/robot/laser_driver_node', 'laser_driver', 'laser_driver_node',
              '--client-library', 'rclpy', '--timeout', '20'], env=env)
        edited = OUT / 'edited_laser_driver_node.nodl.yaml'
        source = REPO / 'examples' / 'workspace' / 'src' / 'laser_driver' / 'nodl' / 'laser_driver_node.nodl.yaml'
        text = source.read_text().replace('sensor_msgs/msg/LaserScan', 'sensor_msgs/msg/PointCloud2')
        text = text.replace('reliability: BEST_EFFORT', 'reliability: RELIABLE')
        text = text.replace('  - nodl://laser_driver/motor_control          '
                            "# this package's own registered interface\n", '')
        edited.write_text(text)
        step('Check against a deliberately edited copy: drift, with its kind and layer',
             ['check', '/robot/laser_driver_node', str(edited), '--client-library', 'rclpy',
              '--timeout', '20'], expect=1,
             env=env)
    finally:
        node.send_signal(signal.SIGINT)
        try:
            node.wait(timeout=10)
        except subprocess.TimeoutExpired:
            node.kill()
            node.wait(timeout=10)
        print('\n(stopped the example node)')


def main() -> None:
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    os.environ.setdefault('ROS_DOMAIN_ID', '57')
    OUT.mkdir(exist_ok=True)
    validate_and_compose()
    env = build_workspace()
    analyse_system(env)
    live(env)
    print('\nDemo finished. Generated files are in demo-out/.')


if __name__ == '__main__':
    main()
