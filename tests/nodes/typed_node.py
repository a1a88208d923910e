"""A node with endpoints of known types, for the interface-type tests.

Publishes std_msgs/msg/String on ``chatter`` and sensor_msgs/msg/LaserScan on
``scan``, serves std_srvs/srv/Trigger on ``trigger`` and the action
test_msgs/action/Fibonacci on ``fibonacci``.
"""

from __future__ import annotations

from _common import arguments, ready, spin


def main() -> None:
    args = arguments(__doc__.splitlines()[0])
    import rclpy
    from rclpy.action import ActionServer
    from sensor_msgs.msg import LaserScan
    from std_msgs.msg import String
    from std_srvs.srv import Trigger
    from test_msgs.action import Fibonacci

    rclpy.init(args=['--ros-args', *args.ros_args])
    node = rclpy.create_node(args.name, namespace=args.namespace)
    node.create_publisher(String, 'chatter', 10)
    node.create_publisher(LaserScan, 'scan', 10)
    node.create_service(Trigger, 'trigger', lambda request, response: response)
    ActionServer(node, Fibonacci, 'fibonacci', lambda goal: Fibonacci.Result())
    ready()
    spin(node)


if __name__ == '__main__':
    main()
