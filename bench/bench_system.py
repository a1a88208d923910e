"""Benchmark of `nodl system`: each operation on a 100-node launch file vs `nodl analyse` of it.

The generated system of the analysis benchmark (:mod:`system_corpus`: 100 registered
definitions, one XML launch file of 100 nodes, each with a name, a namespace and a
parameter).  Every command runs as a user runs it, as a whole process of the same
interpreter on the source tree, with the prefix on ``AMENT_PREFIX_PATH``:

* ``nodl analyse system100.launch.xml`` (the baseline);
* ``nodl system show`` (the composition, its ports and connections, and the analysis);
* ``nodl system add`` (a node, checked against its definition, the file written);
* ``nodl system set`` (a parameter checked against its declaration, the file written);
* ``nodl system connect`` (the ports from the analysis, the rule computed, the file written);
* ``nodl system remove``;
* ``nodl system rename`` (a node's name and namespace checked as rcl checks them, the file
  written);
* ``nodl system remap`` (a node's own remapping rules replaced, the file written).

Each operation starts from the same launch file (copied back before every run, not timed).
Runs are interleaved, three rounds, the best of each compared.  The figure compared is each
process's CPU time (user + system; wall times are printed too).  Target (issue 20): every
operation at most 1.5x ``nodl analyse``.
"""

from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from system_corpus import make_system

TARGET = 1.5
ROUNDS = 3
NODES = 100
REPO = Path(__file__).resolve().parent.parent


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run(arguments: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall seconds, CPU seconds) of ``nodl ARGUMENTS``."""
    cpu, start = _cpu(), time.perf_counter()
    process = subprocess.Popen([sys.executable, '-m', 'nodl', *arguments], cwd=REPO, env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        _, stderr = process.communicate(timeout=600)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate(timeout=60)
        raise
    elapsed = time.perf_counter() - start
    if process.returncode not in (0, 1):  # analyse and show exit 1 when there are errors
        raise RuntimeError(f'nodl {" ".join(arguments)} exited {process.returncode}: {stderr[-2000:]}')
    return elapsed, _cpu() - cpu


def operations(launch: str) -> dict[str, list[str]]:
    """The commands timed, by label."""
    return {
        'nodl analyse LAUNCH': ['analyse', launch],
        'nodl system show': ['system', 'show', launch],
        'nodl system add': ['system', 'add', launch, 'pkg7', 'node7', '--name', 'extra',
                            '--namespace', 'added'],
        'nodl system set': ['system', 'set', launch, '/g0/n5', 'rate', '2.5'],
        'nodl system connect': ['system', 'connect', launch, '/g0/n5:out_5', '/g0/n10:out_9'],
        'nodl system remove': ['system', 'remove', launch, '/g0/n42'],
        'nodl system rename': ['system', 'rename', launch, '/g0/n5', '--name', 'renamed',
                               '--namespace', 'moved'],
        'nodl system remap': ['system', 'remap', launch, '/g0/n10', 'out_9:=out_5'],
    }


def main() -> bool:
    root = Path(tempfile.mkdtemp(prefix='nodl-bench-system-'))
    try:
        prefix, _ = make_system(root, NODES, NODES)
        launch = root / f'system{NODES}.launch.xml'
        pristine = launch.read_text(encoding='utf-8')
        env = dict(os.environ, AMENT_PREFIX_PATH=str(prefix))
        commands = operations(str(launch))
        times: dict[str, list[tuple[float, float]]] = {label: [] for label in commands}
        for _ in range(ROUNDS):
            for label, arguments in commands.items():
                launch.write_text(pristine, encoding='utf-8')
                times[label].append(_run(arguments, env))
        launch.write_text(pristine, encoding='utf-8')
        _run(commands['nodl system connect'], env)
        assert '<remap from="out_9" to="out_5"/>' in launch.read_text(encoding='utf-8')
        for label in ('nodl system rename', 'nodl system remap'):  # they did change the file
            launch.write_text(pristine, encoding='utf-8')
            _run(commands[label], env)
            assert launch.read_text(encoding='utf-8') != pristine, label
    finally:
        shutil.rmtree(root, ignore_errors=True)
    best = {label: (min(t[0] for t in runs), min(t[1] for t in runs))
            for label, runs in times.items()}
    analyse_wall, analyse = best['nodl analyse LAUNCH']
    print(f'nodl system ({NODES} launched nodes, {NODES} registered definitions; CPU time, '
          'wall in brackets)')
    ok = True
    for label, (wall, cpu) in best.items():
        if label == 'nodl analyse LAUNCH':
            print(f'  {label:24} {cpu * 1000:8.0f} ms  ({wall * 1000:.0f} ms)')
            continue
        ratio = cpu / analyse
        ok = ok and ratio <= TARGET
        print(f'  {label:24} {cpu * 1000:8.0f} ms  ({wall * 1000:.0f} ms)   ratio {ratio:.2f}x '
              f'(target <= {TARGET}x; wall {wall / analyse_wall:.2f}x)')
    return ok


if __name__ == '__main__':
    sys.exit(0 if main() else 1)
