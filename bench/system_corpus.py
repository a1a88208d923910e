"""The generated launched system the analysis and policy benchmarks share.

A prefix with N packages of one registered node each (every one its own
definition, publishing one topic and subscribing to the previous node's) and
one XML launch file starting a number of instances of them, each with a name,
a namespace and a parameter.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ['make_system']

INDEX = os.path.join('share', 'ament_index', 'resource_index')
DEFINITION = """nodl_version: 2
base: node
main:
  nodl_version: 2
  description: Generated node {i}.
  parameters:
    rate: {{type: double, default_value: 10.0, description: Rate.}}
  publishers:
    - {{name: out_{i}, type: std_msgs/msg/String, description: Out.,
       qos: {{history: KEEP_LAST, depth: 10, reliability: RELIABLE, durability: VOLATILE, liveliness: AUTOMATIC}}}}
  subscriptions:
    - {{name: out_{j}, type: std_msgs/msg/String, description: In.,
       qos: {{history: KEEP_LAST, depth: 10, reliability: RELIABLE, durability: VOLATILE, liveliness: AUTOMATIC}}}}
"""


def make_system(root: Path, definitions: int, nodes: int) -> tuple[Path, list[Path]]:
    """A prefix with ``definitions`` registered nodes and a launch file of ``nodes`` nodes.

    The launch file is ``root / f'system{nodes}.launch.xml'``; returns the
    prefix (for ``AMENT_PREFIX_PATH``) and the definition files.
    """
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
