"""Benchmark of `nodl validate --types`: 100 node definitions with and without the type check.

The corpus is :func:`corpus.corpus` (realistic node definitions naming std_msgs,
sensor_msgs, geometry_msgs types and std_srvs services, every one installed), 100
files in one folder.  Both commands run as a user runs them, as whole processes of the same
interpreter on the source tree, with the environment's prefix on
``AMENT_PREFIX_PATH``:

* ``nodl validate DIR`` (the baseline, measured in the same run);
* ``nodl validate --types DIR`` (the same, then every endpoint type resolved
  against the index: one index snapshot and type cache for the run).

Runs are interleaved, five rounds, the best CPU time (user + system) of each
compared.  Target (issue 18): at most 1.5x.
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

from corpus import corpus  # noqa: E402

TARGET = 1.5
ROUNDS = 5
FILES = 100
REPO = Path(__file__).resolve().parent.parent


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run(arguments: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall seconds, CPU seconds) of ``nodl validate ARGUMENTS``."""
    cpu, start = _cpu(), time.perf_counter()
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '-q', *arguments],
                            cwd=REPO, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True, timeout=600)
    elapsed = time.perf_counter() - start
    if result.returncode not in (0, 1):
        raise RuntimeError(f'nodl validate {" ".join(arguments)} exited {result.returncode}: '
                           f'{result.stderr[-2000:]}')
    return elapsed, _cpu() - cpu


def main() -> bool:
    root = Path(tempfile.mkdtemp(prefix='nodl-bench-types-'))
    try:
        texts = corpus(FILES)
        for number, text in enumerate(texts):
            # every type installed (the wheels ship no nav_msgs): each name is resolved in full
            text = text.replace('nav_msgs/msg/Odometry', 'geometry_msgs/msg/PoseStamped')
            (root / f'node{number:03}.nodl.yaml').write_text(text, encoding='utf-8')
        env = dict(os.environ, AMENT_PREFIX_PATH=os.environ.get('AMENT_PREFIX_PATH') or sys.prefix)
        plain, typed = [], []
        for _ in range(ROUNDS):
            plain.append(_run([str(root)], env))
            typed.append(_run(['--types', str(root)], env))
        base, with_types = min(c for _, c in plain), min(c for _, c in typed)
        ratio = with_types / base
        print(f'validate of {FILES} definitions: {base:.3f} s CPU '
              f'(wall {min(w for w, _ in plain):.3f} s)')
        print(f'validate --types:               {with_types:.3f} s CPU '
              f'(wall {min(w for w, _ in typed):.3f} s)')
        print(f'ratio: {ratio:.2f}x (target: at most {TARGET}x)')
        return ratio <= TARGET
    finally:
        shutil.rmtree(root, ignore_errors=True)


if __name__ == '__main__':
    sys.exit(0 if main() else 1)
