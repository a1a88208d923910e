"""nodl analyse of nav2's bringup_launch.py against the real upstream launch running it.

Target (issue 16): ``nodl analyse`` of nav2's ``bringup_launch.py`` (navigation2 1.4.2, the
fixture ``tests/fixtures/launch/nav2_bringup``: 21 nodes, parameters through nav2_common's
``RewrittenYaml``), as a whole process, takes at most 0.3x the time the real upstream launch
(ros2/launch 3.7.1, ros2/launch_ros 0.28.0) needs merely to run the same launch description
in-process, with process execution stubbed out (``upstream_launch_run.py``).

The upstream sources are a benchmark baseline only, never a dependency of the toolkit, and
are not in this repository.  Give them with two environment variables:

- ``NODL_BENCH_UPSTREAM``: a folder holding ``launch`` (a checkout of ros2/launch at 3.7.1),
  ``launch_ros`` (ros2/launch_ros at 0.28.0) and ``nav2_common`` (navigation2's package of
  that name at 1.4.2);
- ``NODL_BENCH_UPSTREAM_PYTHON``: the interpreter of a virtual environment of its own with
  launch's dependencies (``osrf-pycommon``, ``lark``, ``PyYAML``); rclpy and the message
  packages are taken from the toolkit's environment (appended to that interpreter's path).

Without them the comparison is skipped (said so) and only nodl's own time is measured, on
the fixture as it is (nav2_common not installed: RewrittenYaml's values are run-time values).
With them, nav2_common is installed in the benchmark's ament prefix, so that both sides
evaluate the same RewrittenYaml.  The two are run in turns, several rounds, best of each;
nodl's bytecode is cached in a private folder, as in an installation.  The ratio is of
processor time (what other processes take of this shared machine is not counted: nodl's
process and its sandbox child, against the upstream run); wall-clock times are printed too.
"""

from __future__ import annotations

import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGET = 0.3
ROUNDS = 5
REPO = Path(__file__).resolve().parent.parent
FIXTURE = REPO / 'tests' / 'fixtures' / 'launch' / 'nav2_bringup' / 'prefix'
RUNNER = Path(__file__).resolve().parent / 'upstream_launch_run.py'
#: What the upstream run looks up in the ament index besides nav2_bringup.
_PACKAGES = ('launch', 'launch_ros', 'nav2_common', 'nav2_bt_navigator', 'nav2_route',
             'rclcpp_components')


def _upstream() -> tuple[Path, str] | str:
    """The upstream sources and interpreter, or why the comparison is skipped."""
    folder = os.environ.get('NODL_BENCH_UPSTREAM')
    python = os.environ.get('NODL_BENCH_UPSTREAM_PYTHON')
    if not folder or not python:
        return 'NODL_BENCH_UPSTREAM and NODL_BENCH_UPSTREAM_PYTHON are not set'
    root = Path(folder)
    for part in ('launch/launch/launch', 'launch_ros/launch_ros/launch_ros', 'nav2_common/nav2_common',
                 'launch/launch/share/launch/frontend/grammar.lark'):
        if not (root / part).exists():
            return f'{root / part} does not exist'
    if not os.access(python, os.X_OK):
        return f'{python} is not an interpreter'
    return root, python


def _prefix(where: Path, upstream: Path | None) -> Path:
    """The benchmark's ament prefix: the fixture, and with the upstream sources nav2_common
    (installed as a package's Python folder) and what the upstream run looks up."""
    prefix = where / 'prefix'
    shutil.copytree(FIXTURE, prefix)
    if upstream is None:
        return prefix
    index = prefix / 'share' / 'ament_index' / 'resource_index' / 'packages'
    for package in _PACKAGES:
        (index / package).touch()
        (prefix / 'share' / package).mkdir(parents=True, exist_ok=True)
    site = prefix / 'lib' / f'python{sys.version_info[0]}.{sys.version_info[1]}' / 'site-packages'
    shutil.copytree(upstream / 'nav2_common' / 'nav2_common', site / 'nav2_common')
    frontend = prefix / 'share' / 'launch' / 'frontend'
    frontend.mkdir(parents=True)
    shutil.copy(upstream / 'launch' / 'launch' / 'share' / 'launch' / 'frontend' / 'grammar.lark', frontend)
    container = prefix / 'lib' / 'rclcpp_components' / 'component_container_isolated'
    container.parent.mkdir(parents=True)
    container.write_text('#!/bin/sh\nexit 0\n')  # (never run: process execution is stubbed out)
    container.chmod(0o755)
    return prefix


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _nodl(prefix: Path, env: dict[str, str]) -> tuple[float, float, int]:
    """One ``nodl analyse``: wall seconds, processor seconds, nodes found."""
    launch = prefix / 'share' / 'nav2_bringup' / 'launch' / 'bringup_launch.py'
    cpu, start = _children_cpu(), time.perf_counter()
    done = subprocess.run([sys.executable, '-m', 'nodl', 'analyse', str(launch), '--format', 'json'],
                          env=env, cwd=REPO, capture_output=True, text=True, timeout=120)
    wall, cpu = time.perf_counter() - start, _children_cpu() - cpu
    if done.returncode not in (0, 1):
        raise RuntimeError(f'nodl analyse failed ({done.returncode}): {done.stderr[-2000:]}')
    return wall, cpu, len(json.loads(done.stdout)['nodes'])


def _ros_libraries() -> str:
    """The library folders of the ROS wheels of the toolkit's environment (what their
    bootstrapper puts on LD_LIBRARY_PATH), for the upstream interpreter."""
    site = Path(sys.prefix) / 'lib' / f'python{sys.version_info[0]}.{sys.version_info[1]}' / 'site-packages'
    folders = [str(p) for p in sorted(site.glob('ros_*.libs'))] + [str(Path(sys.prefix) / 'lib')]
    return os.pathsep.join(folders + [p for p in os.environ.get('LD_LIBRARY_PATH', '').split(os.pathsep) if p])


def _launch(upstream: Path, python: str, prefix: Path, env: dict[str, str]) -> dict[str, object]:
    """One upstream run of the launch description: its JSON line."""
    launch = prefix / 'share' / 'nav2_bringup' / 'launch' / 'bringup_launch.py'
    site = Path(sys.prefix) / 'lib' / f'python{sys.version_info[0]}.{sys.version_info[1]}' / 'site-packages'
    done = subprocess.run([python, str(RUNNER), str(upstream), str(launch), str(site)], env=env,
                          capture_output=True, text=True, timeout=300)
    lines = [line for line in done.stdout.splitlines() if line.startswith('{')]
    if done.returncode != 0 or not lines:
        raise RuntimeError(f'the upstream run failed ({done.returncode}): {done.stderr[-2000:]}')
    result: dict[str, object] = json.loads(lines[-1])
    if result['exit_code'] != 0:
        raise RuntimeError(f'the upstream launch failed: {done.stderr[-2000:]}')
    return result


def main() -> bool:
    found = _upstream()
    upstream = None if isinstance(found, str) else found
    print("nodl analyse of nav2's bringup_launch.py against upstream launch running it")
    with tempfile.TemporaryDirectory(prefix='nodl-bench-nav2-') as scratch:
        root = Path(scratch)
        prefix = _prefix(root, upstream[0] if upstream else None)
        env = dict(os.environ, AMENT_PREFIX_PATH=str(prefix), PYTHONPYCACHEPREFIX=str(root / 'pycache'),
                   ROS_LOG_DIR=str(root / 'log'), ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
        env.pop('PYTHONDONTWRITEBYTECODE', None)
        _nodl(prefix, env)  # (bytecode written once, uncounted)
        upstream_env = None
        if upstream is not None:
            upstream_env = dict(env, LD_LIBRARY_PATH=_ros_libraries(), TMPDIR=str(root))
            upstream_env.pop('_ROS_WHEELS_BOOTSTRAP_COMPLETE', None)
            _launch(upstream[0], upstream[1], prefix, upstream_env)
        nodl_wall = nodl_cpu = launch_wall = launch_cpu = float('inf')
        nodes = launched = 0
        for _ in range(ROUNDS):
            wall, cpu, nodes = _nodl(prefix, env)
            nodl_wall, nodl_cpu = min(nodl_wall, wall), min(nodl_cpu, cpu)
            if upstream is not None and upstream_env is not None:
                run = _launch(upstream[0], upstream[1], prefix, upstream_env)
                launch_wall = min(launch_wall, float(run['seconds']))  # type: ignore[arg-type]
                launch_cpu = min(launch_cpu, float(run['cpu_seconds']))  # type: ignore[arg-type]
                launched = len(run['processes']) + len(run['composable_nodes'])  # type: ignore[arg-type]
    print(f'  nodl analyse (whole process): {nodl_cpu:.2f} s processor, {nodl_wall:.2f} s wall '
          f'(best of {ROUNDS}), {nodes} nodes')
    if upstream is None:
        print(f'  upstream launch: SKIPPED ({found}); see this file\'s docstring to compare')
        return True
    ratio = nodl_cpu / launch_cpu
    print(f'  upstream launch, run of the description: {launch_cpu:.2f} s processor, '
          f'{launch_wall:.2f} s wall (best of {ROUNDS}), {launched} nodes')
    print(f'  ratio:       {ratio:.2f}x processor, {nodl_wall / launch_wall:.2f}x wall  '
          f'(target <= {TARGET}x)  {"OK" if ratio <= TARGET else "ABOVE TARGET"}')
    return ratio <= TARGET


if __name__ == '__main__':
    raise SystemExit(0 if main() else 1)
