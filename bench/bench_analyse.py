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

import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

INDEX = os.path.join('share', 'ament_index', 'resource_index')
DEFINITION = """nodl_version: 2
base: node
main:
  nodl_version: 2
  description: Generated node {i}.
  parameters:
    rate: {{type: double, default_value: 10.0, description: Rate.}}
  publishers:
    - {{name: out_{i}, type: std_msgs/msg/String, description: Out., qos: {{history: KEEP_LAST, depth: 10, reliability: RELIABLE, durability: VOLATILE, liveliness: AUTOMATIC}}}}
  subscriptions:
    - {{name: out_{j}, type: std_msgs/msg/String, description: In., qos: {{history: KEEP_LAST, depth: 10, reliability: RELIABLE, durability: VOLATILE, liveliness: AUTOMATIC}}}}
"""


def make_system(root: Path, definitions: int, nodes: int) -> tuple[Path, list[Path]]:
    """A prefix with ``definitions`` registered nodes and a launch file of ``nodes`` nodes."""
    prefix = root / 'prefix'
    for kind in ('packages', 'nodl_nodes'):
        (prefix / INDEX / kind).mkdir(parents=True, exist_ok=True)
    files = []
    for i in range(definitions):
        package = f'pkg{i}'
        (prefix / INDEX / 'packages' / package).write_text('')
        share = prefix / 'share' / package / 'nodl'
        share.mkdir(parents=True)
        file = share / f'node{i}.nodl.yaml'
        file.write_text(DEFINITION.format(i=i, j=(i - 1) % definitions))
        files.append(file)
        (prefix / INDEX / 'nodl_nodes' / f'{package}__node{i}').write_text(f'nodl/node{i}.nodl.yaml')
    lines = ['<launch>']
    for n in range(nodes):
        i = n % definitions
        lines.append(f'  <node pkg="pkg{i}" exec="node{i}" name="n{n}" namespace="/g{n // definitions}">'
                     f'<param name="rate" value="5.0"/></node>')
    lines.append('</launch>')
    launch = root / f'system{nodes}.launch.xml'
    launch.write_text('\n'.join(lines) + '\n')
    return prefix, files


def best(fn, repeat: int = 3) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> bool:
    from nodl_schema import load_nodl
    from nodl_schema.analysis import analyse_launch

    root = Path(tempfile.mkdtemp(prefix='nodl-bench-analyse-'))
    try:
        prefix, files = make_system(root, 1000, 1000)
        make_system(root / 'big', 1000, 10000)
        big = root / 'big' / 'system10000.launch.xml'
        small = root / 'system1000.launch.xml'
        load = best(lambda: [load_nodl(f) for f in files])
        analyse_small = best(lambda: analyse_launch(small, prefixes=[str(prefix)]))
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
