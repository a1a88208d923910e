"""A default rclpy node with nothing of its own (for the `node` base)."""

import rclpy
from rclpy.node import Node

from _common import arguments, ready, spin

args = arguments(__doc__)
rclpy.init(args=['--ros-args', *args.ros_args] if args.ros_args else None)
node = Node(args.name, namespace=args.namespace)
ready()
spin(node)
