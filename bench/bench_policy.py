"""Benchmark of `nodl policy`: the policy of a launched system vs the analysis of that system.

The 1,000-node generated system of the analysis benchmark
(:mod:`system_corpus`: 1,000 registered definitions, one XML launch file).
Both commands run as a user runs them, as whole processes of the same
interpreter on the source tree, with the prefix on ``AMENT_PREFIX_PATH``:

* ``nodl policy system1000.launch.xml -o FILE`` (read the launch file as
  ``nodl analyse`` does, grant every node its entities, write and check the
  document);
* ``nodl analyse system1000.launch.xml`` (the same reading, then every check).

Runs are interleaved, three rounds, the best of each compared.  The figure
compared is each process's CPU time (user + system): both commands are
single-threaded and compute-bound, and CPU time does not count the time a
busy machine keeps them waiting (wall times are printed too).  Target
(issue 10): at most 1.5x.
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

from system_corpus import make_system  # noqa: E402

TARGET = 1.5
ROUNDS = 3
NODES = 1000
REPO = Path(__file__).resolve().parent.parent


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run(arguments: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall seconds, CPU seconds) of ``nodl ARGUMENTS`` (CPU: user + system of the process)."""
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
    if process.returncode != 0:
        raise RuntimeError(f'nodl {" ".join(arguments)} exited {process.returncode}: {stderr[-2000:]}')
    return elapsed, _cpu() - cpu


def main() -> bool:
    root = Path(tempfile.mkdtemp(prefix='nodl-bench-policy-'))
    try:
        prefix, _ = make_system(root, NODES, NODES)
        launch = str(root / f'system{NODES}.launch.xml')
        output = root / 'system.policy.xml'
        env = dict(os.environ, AMENT_PREFIX_PATH=str(prefix))
        policy_times, analyse_times = [], []
        for _ in range(ROUNDS):
            analyse_times.append(_run(['analyse', launch], env))
            policy_times.append(_run(['policy', launch, '-o', str(output)], env))
        text = output.read_text(encoding='utf-8')
        profiles = text.count('<profile ns=')
        assert profiles == NODES, f'{profiles} profiles written for {NODES} nodes'
    finally:
        shutil.rmtree(root, ignore_errors=True)
    (policy_wall, policy), (analyse_wall, analyse) = (
        (min(t[0] for t in times), min(t[1] for t in times)) for times in (policy_times, analyse_times))
    ratio = policy / analyse
    print(f'nodl policy ({NODES:,} launched nodes, {NODES:,} registered definitions; CPU time, '
          'wall in brackets)')
    print(f'  nodl analyse LAUNCH:            {analyse * 1000:8.0f} ms  ({analyse_wall * 1000:.0f} ms)')
    print(f'  nodl policy LAUNCH -o FILE:     {policy * 1000:8.0f} ms  ({policy_wall * 1000:.0f} ms)   '
          f'ratio {ratio:.2f}x (target <= {TARGET}x; wall {policy_wall / analyse_wall:.2f}x)')
    return ratio <= TARGET


if __name__ == '__main__':
    sys.exit(0 if main() else 1)
