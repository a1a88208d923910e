"""An action server node and an action client node (test_msgs/action/Fibonacci) in one process.

--name is the server's name; the client is called <name>_client.
"""

import rclpy
from rclpy.action import ActionClient, ActionServer
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from test_msgs.action import Fibonacci

from _common import arguments, ready

args = arguments(__doc__)
rclpy.init()
server = Node(args.name, namespace=args.namespace)
client = Node(args.name + '_client', namespace=args.namespace)


def execute(goal_handle):  # type: ignore[no-untyped-def]
    goal_handle.succeed()
    return Fibonacci.Result()


ActionServer(server, Fibonacci, '~/fibonacci', execute)
ActionClient(client, Fibonacci, f'{args.name}/fibonacci')
executor = SingleThreadedExecutor()
executor.add_node(server)
executor.add_node(client)
ready()
try:
    executor.spin()
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
finally:
    server.destroy_node()
    client.destroy_node()
    if rclpy.ok():
        rclpy.shutdown()
