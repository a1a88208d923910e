"""A node with every entity kind, several QoS profiles, parameters with ranges."""

import rclpy
from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor
from rclpy.duration import Duration
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, HistoryPolicy, LivelinessPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Bool, Float64, String
from std_srvs.srv import SetBool, Trigger

from _common import arguments, ready, spin

args = arguments(__doc__)
rclpy.init(args=['--ros-args', *args.ros_args] if args.ros_args else None)
node = Node(args.name, namespace=args.namespace)

node.declare_parameter('rate', 10, ParameterDescriptor(
    description='Publishing rate in Hz.', integer_range=[IntegerRange(from_value=1, to_value=100, step=1)]))
node.declare_parameter('gain', 0.5, ParameterDescriptor(
    description='Controller gain.',
    floating_point_range=[FloatingPointRange(from_value=0.0, to_value=1.0, step=0.0)]))
node.declare_parameter('frame_id', 'base_link', ParameterDescriptor(
    description='Frame of the outputs.', read_only=True))
node.declare_parameter('joints', ['left', 'right'], ParameterDescriptor(description='Joint names.'))
node.declare_parameter('verbose', False)

latched = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)
sensor = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=5, reliability=ReliabilityPolicy.BEST_EFFORT,
                    durability=DurabilityPolicy.VOLATILE)
timed = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=10, reliability=ReliabilityPolicy.RELIABLE,
                   deadline=Duration(seconds=1), lifespan=Duration(seconds=2),
                   liveliness=LivelinessPolicy.AUTOMATIC,
                   liveliness_lease_duration=Duration(seconds=3))

node.create_publisher(String, '~/status', latched)
node.create_publisher(Float64, 'measurement', sensor)
node.create_publisher(String, '/global_chatter', timed)
node.create_subscription(Bool, '/emergency_stop', lambda m: None, 10)
node.create_subscription(String, 'commands', lambda m: None, sensor)
node.create_service(Trigger, '~/reset', lambda req, res: res)
node.create_client(SetBool, '/motor/enable')
ready()
spin(node)
