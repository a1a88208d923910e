"""Benchmark of `nodl doc`: 100 node definitions documented, against loading them.

The corpus is :func:`corpus.corpus` (realistic node definitions naming std_msgs,
sensor_msgs, geometry_msgs types and std_srvs services, every one installed), 100
files in one folder.  Both commands run as a user runs them, as whole processes of the same
interpreter on the source tree, with the environment's prefix on ``AMENT_PREFIX_PATH``:

* ``nodl validate FILE...`` (the baseline, loading the definitions; measured in the same run);
* ``nodl doc FILE... -o DIR`` (the same definitions resolved, every field table read from
  the installed interface packages, 101 MyST pages rendered and written).

Runs are interleaved (validate, doc, validate, doc...), after one warm-up run of each
that is not counted, seven rounds, the best CPU time (user + system) of each compared.
Python's bytecode is cached in a private folder (``PYTHONPYCACHEPREFIX``), as an
installed toolkit has its ``.pyc`` files: otherwise compiling the modules each command
imports would be measured (``PYTHONDONTWRITEBYTECODE``), not the commands.
``--no-bytecode-cache`` measures that case too.  Target (issue 18): at most 3x.
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

TARGET = 3.0
ROUNDS = 7
FILES = 100
REPO = Path(__file__).resolve().parent.parent


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run(verb: str, arguments: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall seconds, CPU seconds) of ``nodl VERB ARGUMENTS``."""
    cpu, start = _cpu(), time.perf_counter()
    result = subprocess.run([sys.executable, '-m', 'nodl', verb, *arguments],
                            cwd=REPO, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True, timeout=600)
    elapsed = time.perf_counter() - start
    if result.returncode != 0:
        raise RuntimeError(f'nodl {verb} exited {result.returncode}: {result.stderr[-2000:]}')
    return elapsed, _cpu() - cpu


def main() -> bool:
    root = Path(tempfile.mkdtemp(prefix='nodl-bench-doc-'))
    try:
        files = []
        for number, text in enumerate(corpus(FILES)):
            # every type installed (the wheels ship no nav_msgs): each field table is read in full
            text = text.replace('nav_msgs/msg/Odometry', 'geometry_msgs/msg/PoseStamped')
            path = root / 'defs' / f'node{number:03}.nodl.yaml'
            path.parent.mkdir(exist_ok=True)
            path.write_text(text, encoding='utf-8')
            files.append(str(path))
        env = dict(os.environ, AMENT_PREFIX_PATH=os.environ.get('AMENT_PREFIX_PATH') or sys.prefix)
        if '--no-bytecode-cache' not in sys.argv:
            env.pop('PYTHONDONTWRITEBYTECODE', None)
            env['PYTHONPYCACHEPREFIX'] = str(root / 'pycache')
        _run('validate', ['-q', *files], env)  # warm-up: caches filled, not counted
        _run('doc', [*files, '-o', str(root / 'warm-up')], env)
        loads, docs = [], []
        for round_ in range(ROUNDS):
            loads.append(_run('validate', ['-q', *files], env))
            docs.append(_run('doc', [*files, '-o', str(root / f'out{round_}')], env))
        base, doc = min(c for _, c in loads), min(c for _, c in docs)
        ratio = doc / base
        print(f'validate of {FILES} definitions: {base:.3f} s CPU (wall {min(w for w, _ in loads):.3f} s)')
        print(f'doc of the same definitions:    {doc:.3f} s CPU (wall {min(w for w, _ in docs):.3f} s)')
        print(f'ratio: {ratio:.2f}x (target: at most {TARGET}x)')
        return ratio <= TARGET
    finally:
        shutil.rmtree(root, ignore_errors=True)


if __name__ == '__main__':
    sys.exit(0 if main() else 1)
