"""The laser driver of examples/workspace/src/laser_driver, implemented with rclpy.

It exposes exactly what its node definition declares (nodl://laser_driver's
`laser_driver_node`): the `node` base, the shared diagnostics interface, the
motor control interface, and its own port parameter and scan publisher.
Run: python laser_driver_node.py [--ros-args -r __ns:=/robot]
"""

import sys

import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Trigger


class LaserDriver(Node):
    def __init__(self) -> None:
        super().__init__('laser_driver_node')
        self.declare_parameter('port', '/dev/ttyUSB0', ParameterDescriptor(
            description='Serial device the scanner is connected to.', read_only=True))
        self.declare_parameter('diagnostics.period', 0.5, ParameterDescriptor(
            description='This driver reports twice a second.'))
        self.scan = self.create_publisher(LaserScan, '~/scan', QoSProfile(
            history=HistoryPolicy.KEEP_LAST, depth=5, reliability=ReliabilityPolicy.BEST_EFFORT))
        self.diagnostics = self.create_publisher(DiagnosticArray, '/diagnostics', 10)
        self.create_service(Trigger, '~/self_test', self.answer)
        self.create_service(Trigger, '~/start_motor', self.answer)
        self.create_service(Trigger, '~/stop_motor', self.answer)

    def answer(self, request: Trigger.Request, response: Trigger.Response) -> Trigger.Response:
        response.success = True
        return response


def main() -> None:
    rclpy.init(args=sys.argv)
    node = LaserDriver()
    print('ready', flush=True)
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()


if __name__ == '__main__':
    main()
