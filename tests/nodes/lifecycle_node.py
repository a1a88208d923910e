"""A default rclpy lifecycle node with nothing of its own (for the `lifecycle_node` base)."""

import rclpy
from rclpy.lifecycle import LifecycleNode

from _common import arguments, ready, spin

args = arguments(__doc__)
rclpy.init()
node = LifecycleNode(args.name, namespace=args.namespace)
ready()
spin(node)
