"""`nodl describe --all --launch` of a 20-node system against the discovery floor.

A launch file starting 20 nodes (10 talkers, 10 listeners, each in a namespace of its own,
with a remap) is started as 20 real processes (tests/nodes/system_node.py plays each
executable, given the rules launch would give it).  The floor is the time a bare rclpy
process needs, from its start, to see all the endpoints of those 20 nodes (it is told how
many each has); the tool is `nodl describe --all --launch LAUNCH -o DIR`, parameters read,
as a whole process.  Both are measured in the same run, interleaved, 9 rounds; medians
compared.  Target (issue 17): at most 2x.
"""

from __future__ import annotations

import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGET = 2.0
NODES = 20
REPO = Path(__file__).resolve().parent.parent
NODE_SCRIPT = REPO / 'tests' / 'nodes' / 'system_node.py'

FLOOR = r'''
import json, sys, time
import rclpy
expected = json.loads(sys.argv[1])
rclpy.init()
node = rclpy.create_node('floor_probe', start_parameter_services=False, enable_rosout=False)
deadline = time.monotonic() + 60
pending = dict(expected)
while pending and time.monotonic() < deadline:
    for fqn, count in list(pending.items()):
        namespace, _, name = fqn.rpartition('/')
        try:
            seen = sum(len(f(name, namespace or '/')) for f in (
                node.get_publisher_names_and_types_by_node, node.get_subscriber_names_and_types_by_node,
                node.get_service_names_and_types_by_node, node.get_client_names_and_types_by_node))
        except Exception:
            seen = 0
        if seen >= count:
            del pending[fqn]
    rclpy.spin_once(node, timeout_sec=0.01)
node.destroy_node()
rclpy.shutdown()
'''


def _launch_file(folder: Path) -> Path:
    lines = ['<launch>']
    for i in range(NODES):
        exe = 'talker' if i % 2 == 0 else 'listener'
        lines.append(f'  <node pkg="demo_robot" exec="{exe}" name="{exe}_{i}" namespace="bench_{i}">')
        lines.append('    <remap from="chatter" to="/bench/chatter"/>')
        lines.append('  </node>')
    lines.append('</launch>')
    path = folder / 'bench.launch.xml'
    path.write_text('\n'.join(lines) + '\n', encoding='utf-8')
    return path


def _start(launch: Path) -> list[subprocess.Popen[str]]:
    from nodl.analysis import analyse_launch

    processes = []
    for node in analyse_launch(launch, {}, checks={}).nodes:
        exe = node.entry.executable
        assert exe is not None
        args = ['-r', f'__node:={node.created_name}', '-r', f'__ns:={node.entry.namespace}']
        for a, b in node.entry.remaps:
            args += ['-r', f'{a}:={b}']
        processes.append(subprocess.Popen(
            [sys.executable, str(NODE_SCRIPT), '--role', exe, '--name', exe, '--ros-args', *args],
            stdout=subprocess.PIPE, text=True, cwd=NODE_SCRIPT.parent))
    for process in processes:
        assert process.stdout is not None and process.stdout.readline().strip() == 'ready'
    return processes


def _timed(cmd: list[str]) -> float:
    start = time.perf_counter()
    done = subprocess.run(cmd, check=False, cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True, timeout=120)
    took = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f'{cmd[:3]} failed ({done.returncode}): {done.stderr[-2000:]}')
    return took


def run(rounds: int = 9) -> dict[str, float]:
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    os.environ.setdefault('ROS_DOMAIN_ID', str(10 + os.getpid() % 90))
    with tempfile.TemporaryDirectory() as tmp:
        launch = _launch_file(Path(tmp))
        processes = _start(launch)
        try:
            from nodl.live.observe import settle_nodes
            from nodl.live.session import ros_session

            fqns = [f'/bench_{i}/{"talker" if i % 2 == 0 else "listener"}_{i}' for i in range(NODES)]
            with ros_session() as session:
                raw, _ = settle_nodes(session, {f: 1 for f in fqns}, 30, quiet=1.0)
            expected = {f: sum(len(v) for v in raw[f].values()) for f in fqns}
            floor_cmd = [sys.executable, '-c', FLOOR, json.dumps(expected)]
            # the working tree's toolkit (python -m from the repository), as the tests run it
            nodl_cmd = [sys.executable, '-m', 'nodl', 'describe', '--all', '--launch',
                        str(launch), '-o', str(Path(tmp) / 'out'), '--timeout', '30', '--force']
            floors, tools = [], []
            for _ in range(rounds):
                floors.append(_timed(floor_cmd))
                tools.append(_timed(nodl_cmd))
        finally:
            for process in processes:
                process.send_signal(signal.SIGINT)
            for process in processes:
                try:
                    process.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    process.kill()
    f, t = statistics.median(floors), statistics.median(tools)
    return {'nodes': NODES, 'endpoints': sum(expected.values()), 'floor_s': f, 'describe_s': t,
            'ratio': t / f}


def main() -> bool:
    r = run()
    print(f'nodl describe --all --launch vs discovery floor ({r["nodes"]:.0f} nodes, '
          f'{r["endpoints"]:.0f} endpoints)')
    print(f'  bare rclpy process until all endpoints seen: {r["floor_s"]:.2f} s (median)')
    print(f'  nodl describe --all --launch (process, parameters included): '
          f'{r["describe_s"]:.2f} s (median)')
    print(f'  ratio: {r["ratio"]:.2f}x  (target <= {TARGET}x)  '
          f'{"OK" if r["ratio"] <= TARGET else "ABOVE TARGET"}')
    return r['ratio'] <= TARGET


if __name__ == '__main__':
    sys.path.insert(0, str(REPO))
    raise SystemExit(0 if main() else 1)
