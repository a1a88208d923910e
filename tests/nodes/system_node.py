"""The executables of the demo_robot system of tests/fixtures/describe_launch/, started as
launch would start them: ``--role ROLE --name NAME [--ros-args ...]``.  The node is created
with the name its executable gives it (``--name``); launch's ``-r __node:=``, ``-r __ns:=``,
``-r from:=to`` and ``-p name:=value`` rules then apply, as for a real executable.

Roles (what each executable declares):

* ``talker``: publishes ``chatter`` (std_msgs/String), ``/diagnostics`` (std_msgs/String),
  serves ``~/reset`` (std_srvs/Trigger), parameter ``rate`` (int, 10); with ``debug:=true``
  it also publishes ``~/debug`` (its interface depends on a parameter);
* ``listener``: subscribes ``chatter`` and ``/cmd_vel`` (std_msgs/String), and
  ``/diagnostics`` as diagnostic_msgs/DiagnosticArray;
* ``lidar_driver``: a lifecycle node that creates ``scan`` (std_msgs/String) when configured;
* ``container``: a container process; ``--load JSON`` gives the composable nodes to load,
  as launch_ros's load_node requests carry them:
  ``[{"plugin": "demo_robot::CameraDriver", "name": ..., "namespace": ..., "rules": [...]}]``.
  ``demo_robot::CameraDriver`` publishes ``image`` (std_msgs/String).
"""

import argparse
import json

import rclpy
from rclpy.node import Node
from std_msgs.msg import Bool, String
from std_srvs.srv import Trigger

from _common import ready

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument('--role', required=True)
parser.add_argument('--name', required=True)
parser.add_argument('--namespace', default='/')
parser.add_argument('--load', default='[]')
parser.add_argument('--ros-args', nargs=argparse.REMAINDER, default=[])
args = parser.parse_args()
rclpy.init(args=['--ros-args', *args.ros_args] if args.ros_args else None)


def talker(node: Node) -> None:
    node.declare_parameter('rate', 10)
    node.declare_parameter('debug', False)
    node.create_publisher(String, 'chatter', 10)
    node.create_publisher(String, '/diagnostics', 10)
    node.create_service(Trigger, '~/reset', lambda request, response: response)
    if node.get_parameter('debug').value:
        node.create_publisher(Bool, '~/debug', 10)


def listener(node: Node) -> None:
    from diagnostic_msgs.msg import DiagnosticArray

    node.create_subscription(String, 'chatter', lambda m: None, 10)
    node.create_subscription(String, '/cmd_vel', lambda m: None, 10)
    node.create_subscription(DiagnosticArray, '/diagnostics', lambda m: None, 10)


nodes = []
if args.role == 'lidar_driver':
    from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn

    class LidarDriver(LifecycleNode):  # type: ignore[misc]
        def on_configure(self, state):  # type: ignore[no-untyped-def]
            self.create_lifecycle_publisher(String, 'scan', 10)
            return TransitionCallbackReturn.SUCCESS

    nodes.append(LidarDriver(args.name, namespace=args.namespace))
else:
    main = Node(args.name, namespace=args.namespace)
    nodes.append(main)
    if args.role == 'talker':
        talker(main)
    elif args.role == 'listener':
        listener(main)
    elif args.role == 'container':
        for load in json.loads(args.load):
            # as rclcpp_components does: a node of the plugin's class, named and remapped by
            # the request's rules only (not the container's own command line)
            cli = ['--ros-args', '-r', f'__node:={load["name"]}', '-r', f'__ns:={load["namespace"]}']
            for rule in load.get('rules', []):
                cli += ['-r', rule]
            composable = Node('camera_driver', cli_args=cli, use_global_arguments=False)
            assert load['plugin'] == 'demo_robot::CameraDriver', load['plugin']
            composable.create_publisher(String, 'image', 10)
            nodes.append(composable)

executor = rclpy.executors.SingleThreadedExecutor()
for node in nodes:
    executor.add_node(node)
ready()
try:
    executor.spin()
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
finally:
    for node in nodes:
        node.destroy_node()
    if rclpy.ok():
        rclpy.shutdown()
