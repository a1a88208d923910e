"""Benchmark of `nodl analyse`: a generated system analysed vs its definitions loaded alone.

A prefix with N packages of one registered node each (every one its own definition,
publishing one topic and subscribing to the previous node's) and one XML launch file
starting all N.  Figures:

* analysis of 1,000 nodes / loading (validating) the 1,000 definitions alone: target <= 2x;
* analysis of 10,000 nodes / analysis of 1,000 nodes: target <= 12x (linear).

Every definition is resolved once per analysis (composition included), and the
checks index the system by final name, so the analysis grows linearly.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from system_corpus import make_system  # noqa: E402


def best(fn, repeat: int = 3) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> bool:
    from nodl import load_nodl
    from nodl.analysis import analyse_launch

    root = Path(tempfile.mkdtemp(prefix='nodl-bench-analyse-'))
    try:
        prefix, files = make_system(root, 1000, 1000)
        make_system(root / 'big', 1000, 10000)
        big = root / 'big' / 'system10000.launch.xml'
        small = root / 'system1000.launch.xml'
        # Interleaved (load, analyse, load, analyse...), the best of each: a loaded machine
        # then slows both alike instead of whichever happened to run during a busy spell.
        loads, analyses = [], []
        for _ in range(5):
            loads.append(best(lambda: [load_nodl(f) for f in files], 1))
            analyses.append(best(lambda: analyse_launch(small, prefixes=[str(prefix)]), 1))
        load, analyse_small = min(loads), min(analyses)
        analyse_big = best(lambda: analyse_launch(big, prefixes=[str(root / 'big' / 'prefix')]), 1)
        check = analyse_launch(small, prefixes=[str(prefix)])
        assert len(check.nodes) == 1000 and not check.errors, check.findings[:3]
    finally:
        shutil.rmtree(root, ignore_errors=True)
    first, second = analyse_small / load, analyse_big / analyse_small
    print('nodl analyse (1,000 registered definitions)')
    print(f'  load the 1,000 definitions:  {load * 1000:8.0f} ms')
    print(f'  analyse 1,000 nodes:         {analyse_small * 1000:8.0f} ms   '
          f'ratio {first:.2f}x (target <= 2x)')
    print(f'  analyse 10,000 nodes:        {analyse_big * 1000:8.0f} ms   '
          f'ratio {second:.2f}x of 1,000 (target <= 12x)')
    return first <= 2.0 and second <= 12.0


if __name__ == '__main__':
    sys.exit(0 if main() else 1)
