"""`nodl monitor`: detection latency and steady-state cost (issue 19).

Three measurements, each against a baseline taken in the same run:

* a node killed with SIGKILL: the time from the kill to the monitor's ERROR for it (read
  from its `--format jsonl` stream) against the time a bare rclpy process, started
  beside it and watching the same node, takes to see the node gone from the graph (the
  participant lease).  Same node, same kill.  Target: at most 1.5x.
* a parameter set to a value that breaks its validator (the node does not enforce its
  validators): the time from the `/parameter_events` message to the `/diagnostics`
  array carrying the status with the finding (NODL407, WARN), both received by one bare
  rclpy subscriber.
  Target: at most 100 ms (median and worst of 10 changes); also given as a ratio to the
  publish period (1 s) and to the event's own delivery time (its stamp to its receipt).
* steady-state CPU: 50 nodes in 5 processes, built from definitions by the runtime
  (tests/nodes/monitored_node.py), 5 of them publishing a topic with a deadline at 10 Hz,
  nothing changing; the monitor's CPU time (/proc/<pid>/stat) over a 20 s window after it
  has settled.  Target: at most 2% of one core.
"""

from __future__ import annotations

import json
import os
import signal
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

LATENCY_TARGET = 1.5
PARAMETER_TARGET = 0.100
CPU_TARGET = 0.02
REPO = Path(__file__).resolve().parent.parent
NODE_SCRIPT = REPO / 'tests' / 'nodes' / 'monitored_node.py'
SENSOR = REPO / 'tests' / 'fixtures' / 'monitor' / 'sensor.nodl.yaml'
PLAIN = REPO / 'tests' / 'fixtures' / 'monitor' / 'plain.nodl.yaml'

FLOOR = r'''
import sys, time
import rclpy
fqn = sys.argv[1]
rclpy.init()
node = rclpy.create_node('_floor_probe', start_parameter_services=False, enable_rosout=False)
seen = False
deadline = time.monotonic() + 120
while time.monotonic() < deadline:
    names = {(ns.rstrip('/') + '/' + n) for n, ns in node.get_node_names_and_namespaces()}
    if fqn in names and not seen:
        seen = True
        print('seen', flush=True)
    elif seen and fqn not in names:
        print('gone', time.monotonic(), flush=True)
        break
    rclpy.spin_once(node, timeout_sec=0.01)
node.destroy_node()
rclpy.shutdown()
'''


class Lines:
    """A process's stdout lines, each with the time it was read."""

    def __init__(self, process: subprocess.Popen[str]) -> None:
        self.lines: list[tuple[float, str]] = []
        self.process = process
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self.lines.append((time.monotonic(), line.rstrip('\n')))

    def wait(self, test: Any, timeout: float, after: int = 0) -> tuple[float, str]:
        end = time.monotonic() + timeout
        seen = after
        while time.monotonic() < end:
            for when, line in self.lines[seen:]:
                if test(line):
                    return when, line
            seen = len(self.lines)
            time.sleep(0.005)
        raise RuntimeError(f'timed out; last lines: {self.lines[-5:]}')


class Processes:
    def __init__(self) -> None:
        self.started: list[subprocess.Popen[str]] = []

    def start(self, cmd: list[str], **kwargs: Any) -> subprocess.Popen[str]:
        process = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                   text=True, cwd=REPO, **kwargs)
        self.started.append(process)
        return process

    def node(self, name: str, *extra: str) -> subprocess.Popen[str]:
        process = self.start([sys.executable, str(NODE_SCRIPT), '--name', name, '--definition',
                              str(SENSOR), *extra])
        assert process.stdout is not None and process.stdout.readline().strip() == 'ready'
        return process

    def monitor(self, *arguments: str) -> subprocess.Popen[str]:
        return self.start([sys.executable, '-m', 'nodl', 'monitor', *arguments])

    def stop(self) -> None:
        for process in self.started:
            if process.poll() is None:
                process.send_signal(signal.SIGINT)
        for process in self.started:
            try:
                process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait(timeout=5)


def _jsonl(line: str) -> dict[str, Any]:
    try:
        value = json.loads(line)
    except ValueError:
        return {}
    return value if isinstance(value, dict) else {}


def kill_latency() -> dict[str, float]:
    """Kill to ERROR (monitor) and kill to gone (bare rclpy), one node, one kill."""
    processes = Processes()
    try:
        node = processes.node('bench_killed')
        monitor = Lines(processes.monitor(str(SENSOR), '--name', '/bench_killed', '--format',
                                          'jsonl'))
        monitor.wait(lambda line: _jsonl(line).get('status') == 'nodl: /bench_killed', 30)
        floor = Lines(processes.start([sys.executable, '-c', FLOOR, '/bench_killed']))
        floor.wait(lambda line: line == 'seen', 30)
        time.sleep(3.0)  # the monitor has seen it (10 Hz) and called it a few times
        killed = time.monotonic()
        node.send_signal(signal.SIGKILL)
        # its first ERROR after the kill (not answering NODL434, its deadline topic silent
        # NODL435, gone NODL430), not an ERROR for never having been seen
        seen = len(monitor.lines)
        error_at, _ = monitor.wait(lambda line: _jsonl(line).get('status') == 'nodl: /bench_killed'
                                   and _jsonl(line).get('level') == 'ERROR'
                                   and 'not seen within' not in _jsonl(line)['message'], 90,
                                   after=seen)
        _, gone = floor.wait(lambda line: line.startswith('gone '), 90)
        gone_at = float(gone.split()[1])
    finally:
        processes.stop()
    monitor_s, floor_s = error_at - killed, gone_at - killed
    return {'monitor_s': monitor_s, 'floor_s': floor_s, 'ratio': monitor_s / floor_s}


def parameter_latency(changes: int = 10) -> dict[str, float]:
    """Event receipt to /diagnostics receipt for parameter changes that change the level."""
    import rclpy
    from diagnostic_msgs.msg import DiagnosticArray
    from rcl_interfaces.msg import Parameter, ParameterEvent, ParameterValue
    from rcl_interfaces.srv import SetParameters
    from rclpy.qos import qos_profile_parameter_events

    processes = Processes()
    context = rclpy.Context()
    rclpy.init(context=context)
    try:
        processes.node('bench_param', '--lax')
        monitor = Lines(processes.monitor(str(SENSOR), '--name', '/bench_param', '--format',
                                          'jsonl'))
        node = rclpy.create_node('_bench_reader', context=context)
        executor = rclpy.executors.SingleThreadedExecutor(context=context)
        executor.add_node(node)
        arrays: list[tuple[float, Any]] = []
        events: list[tuple[float, float, Any]] = []
        node.create_subscription(DiagnosticArray, '/diagnostics',
                                 lambda m: arrays.append((time.monotonic(), m)), 50)
        node.create_subscription(ParameterEvent, '/parameter_events',
                                 lambda m: events.append((time.monotonic(), time.time(), m)),
                                 qos_profile_parameter_events)
        end = time.monotonic() + 30  # running (its first status is OK: waiting for it)
        while time.monotonic() < end and not any(
                kv.key == 'state' and kv.value == 'running' for _, array in arrays
                for status in array.status if status.name == 'nodl: /bench_param'
                for kv in status.values):
            executor.spin_once(timeout_sec=0.02)
        client = node.create_client(SetParameters, '/bench_param/set_parameters')
        assert client.wait_for_service(timeout_sec=10)
        end = time.monotonic() + 2.0  # its parameters read
        while time.monotonic() < end:
            executor.spin_once(timeout_sec=0.02)
        latencies, deliveries = [], []
        for i in range(changes):
            bad = i % 2 == 0
            before = len(arrays)
            future = client.call_async(SetParameters.Request(parameters=[Parameter(
                name='mode', value=ParameterValue(type=4, string_value='turbo' if bad else 'fast'))]))
            end = time.monotonic() + 5
            found = None
            while time.monotonic() < end and found is None:
                executor.spin_once(timeout_sec=0.01)
                for when, array in arrays[before:]:
                    status = next(s for s in array.status if s.name == 'nodl: /bench_param')
                    codes = next(kv.value for kv in status.values if kv.key == 'codes')
                    if ('NODL407' in codes) == bad:
                        found = when
                        break
            assert found is not None, 'no status change published'
            while not future.done() and time.monotonic() < end:
                executor.spin_once(timeout_sec=0.01)
            event = [e for e in events if e[2].node == '/bench_param'][-1]
            received, wall, message = event
            latencies.append(found - received)
            if os.environ.get('BENCH_VERBOSE'):
                print(f'  change {i}: {found - received:.4f} s', flush=True)
            stamp = message.stamp.sec + message.stamp.nanosec / 1e9
            deliveries.append(max(wall - stamp, 1e-6))
            time.sleep(0.3)
        node.destroy_node()
    finally:
        rclpy.shutdown(context=context)
        processes.stop()
        if os.environ.get('BENCH_VERBOSE'):
            print('\n'.join(line for _, line in monitor.lines))
    median = statistics.median(latencies)
    return {'median_s': median, 'max_s': max(latencies),
            'delivery_s': statistics.median(deliveries),
            'ratio_period': median / 1.0, 'ratio_delivery': median / statistics.median(deliveries)}


def _cpu_seconds(pid: int) -> float:
    fields = Path(f'/proc/{pid}/stat').read_text().rpartition(')')[2].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def steady_cpu(window: float = 20.0, processes_n: int = 5, per_process: int = 10) -> dict[str, float]:
    """The monitor's share of one core over ``window`` seconds, 50 nodes, nothing changing."""
    processes = Processes()
    try:
        files: list[str] = []
        names: list[str] = []
        for p in range(processes_n):
            processes.node(f'cpu_{p}', '--more', str(per_process - 1), '--more-definition',
                           str(PLAIN))
            files.append(str(SENSOR))
            names += ['--name', f'/cpu_{p}']
            for i in range(1, per_process):
                files.append(str(PLAIN))
                names += ['--name', f'/cpu_{p}_{i}']
        targets = files + names
        total = processes_n * per_process
        started = processes.monitor(*targets, '--format', 'jsonl')
        monitor = Lines(started)
        ok: set[str] = set()

        def settled(line: str) -> bool:
            value = _jsonl(line)
            if value.get('status', 'nodl: system') != 'nodl: system':
                if value.get('level') == 'OK':
                    ok.add(value['status'])
                else:
                    ok.discard(value['status'])
            return len(ok) == total

        monitor.wait(settled, 60)
        time.sleep(5.0)  # settled: parameters read, rates measured, liveness pings running
        before, start = _cpu_seconds(started.pid), time.monotonic()
        time.sleep(window)
        used, elapsed = _cpu_seconds(started.pid) - before, time.monotonic() - start
        changes = [line for when, line in monitor.lines if when >= start]
    finally:
        processes.stop()
    if os.environ.get('BENCH_VERBOSE'):
        print('\n'.join(changes))
    return {'nodes': total, 'share': used / elapsed, 'window_s': elapsed,
            'changes': len(changes)}


def main() -> bool:
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    os.environ.setdefault('ROS_DOMAIN_ID', str(10 + os.getpid() % 90))
    ok = True
    kill = kill_latency()
    print('nodl monitor: a node killed with SIGKILL, kill to ERROR vs kill to gone (bare rclpy)')
    print(f'  bare rclpy process sees it gone (participant lease): {kill["floor_s"]:.2f} s')
    print(f'  nodl monitor publishes its ERROR:                    {kill["monitor_s"]:.2f} s')
    good = kill['ratio'] <= LATENCY_TARGET
    ok = ok and good
    print(f'  ratio: {kill["ratio"]:.3f}x  (target <= {LATENCY_TARGET}x)  '
          f'{"OK" if good else "ABOVE TARGET"}')
    param = parameter_latency()
    print('nodl monitor: a parameter breaking its validator, /parameter_events to /diagnostics')
    print(f'  median {param["median_s"] * 1000:.1f} ms, worst {param["max_s"] * 1000:.1f} ms '
          f'(target <= {PARAMETER_TARGET * 1000:.0f} ms)')
    print(f'  ratio to the publish period (1 s): {param["ratio_period"]:.3f}x; to the event\'s own '
          f'delivery ({param["delivery_s"] * 1000:.1f} ms): {param["ratio_delivery"]:.2f}x')
    good = param['max_s'] <= PARAMETER_TARGET
    ok = ok and good
    print(f'  {"OK" if good else "ABOVE TARGET"}')
    cpu = steady_cpu()
    print(f'nodl monitor: steady state, {cpu["nodes"]:.0f} nodes in 5 processes, 5 deadline '
          'topics at 10 Hz, nothing changing')
    print(f'  CPU over {cpu["window_s"]:.0f} s: {cpu["share"] * 100:.2f}% of one core '
          f'(ratio to the 2% target: {cpu["share"] / CPU_TARGET:.2f}x; '
          f'{cpu["changes"]:.0f} status changes in the window)  '
          f'{"OK" if cpu["share"] <= CPU_TARGET else "ABOVE TARGET"}')
    ok = ok and cpu['share'] <= CPU_TARGET
    return ok


if __name__ == '__main__':
    raise SystemExit(0 if main() else 1)
