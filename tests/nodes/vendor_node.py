"""The vendors' executables of the cart in tests/fixtures/integration_definitions, whose
source the integrator does not have (so their definitions are described from the running
system): ``--role ROLE --name NAME [--ros-args ...]``, started as launch would start them
(launch's ``-r __node:=``, ``-r __ns:=``, ``-r from:=to`` and ``-p name:=value`` rules apply).

* ``camera_node``: publishes ``image_raw`` (sensor_msgs/Image, sensor-data QoS);
  parameters ``fps`` (int, 30) and ``device`` (string, ``/dev/video0``);
* ``cloud_bridge``: subscribes ``image`` (sensor_msgs/Image, sensor-data QoS) and
  ``/diagnostics`` (diagnostic_msgs/DiagnosticArray); parameter ``url`` (string).
"""

import argparse

import rclpy
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data

from _common import ready

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument('--role', required=True, choices=('camera_node', 'cloud_bridge'))
parser.add_argument('--name', required=True)
parser.add_argument('--namespace', default='/')
parser.add_argument('--ros-args', nargs=argparse.REMAINDER, default=[])
args = parser.parse_args()
rclpy.init(args=['--ros-args', *args.ros_args] if args.ros_args else None)

node = Node(args.name, namespace=args.namespace)
if args.role == 'camera_node':
    from sensor_msgs.msg import Image

    node.declare_parameter('fps', 30)
    node.declare_parameter('device', '/dev/video0')
    node.create_publisher(Image, 'image_raw', qos_profile_sensor_data)
else:
    from diagnostic_msgs.msg import DiagnosticArray
    from sensor_msgs.msg import Image

    node.declare_parameter('url', 'wss://fleet.example.com/cart')
    node.create_subscription(Image, 'image', lambda m: None, qos_profile_sensor_data)
    node.create_subscription(DiagnosticArray, '/diagnostics', lambda m: None, 10)

ready()
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
finally:
    node.destroy_node()
    if rclpy.ok():
        rclpy.shutdown()
