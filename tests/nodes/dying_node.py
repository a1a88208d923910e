"""A node that exits on its own after a short while (--lifetime seconds)."""

import sys

import rclpy
from rclpy.node import Node
from std_msgs.msg import String

from _common import ready, spin

argv = sys.argv[1:]
lifetime = float(argv[argv.index('--lifetime') + 1]) if '--lifetime' in argv else 0.5
name = argv[argv.index('--name') + 1]
namespace = argv[argv.index('--namespace') + 1] if '--namespace' in argv else '/'
rclpy.init()
node = Node(name, namespace=namespace)
node.create_publisher(String, '~/last_words', 10)
ready()
spin(node, seconds=lifetime)
