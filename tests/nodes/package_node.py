"""A node class of a package's module, run from the package's sources (not installed).

Usage: package_node.py --name NAME [--namespace NS] --root DIR --module MODULE --class CLASS
[--ros-args ...].  DIR holds the package's Python packages (MODULE is ``my_pkg.talker``); the
class is made with no arguments, as the package's entry point makes it, and renamed NAME.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

from _common import ready, spin

os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--name', required=True)
    parser.add_argument('--namespace', default='/')
    parser.add_argument('--root', required=True)
    parser.add_argument('--module', required=True)
    parser.add_argument('--class', dest='cls', required=True)
    parser.add_argument('--ros-args', nargs=argparse.REMAINDER, default=[])
    args = parser.parse_args()
    sys.path.insert(0, args.root)
    import rclpy

    cls = getattr(importlib.import_module(args.module), args.cls)
    rclpy.init(args=['node', '--ros-args', '-r', f'__node:={args.name}', '-r', f'__ns:={args.namespace}',
                     *args.ros_args])
    node = cls()
    ready()
    spin(node)


if __name__ == '__main__':
    main()
