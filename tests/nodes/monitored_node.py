"""A node built at run time from a definition (nodl.runtime) for nodl monitor's tests.

Usage: monitored_node.py --name NAME [--namespace NS] --definition FILE [--rate HZ] [--lax]
[--more N --more-definition FILE] [--publishers N] [--storm N] [--churn HZ] [--ros-args ...].
It publishes a String on every declared publisher at HZ (default 10); --lax: it does not
enforce its validators (a bad value set through the parameter service is accepted, for the
monitor to find).  On SIGUSR1 it recreates its publishers BEST_EFFORT (a QoS change at run
time).  Bad input for the monitor: --more N builds N more nodes in the same process from
--more-definition, named NAME_1 ... NAME_N (they do not publish); --publishers N gives the
node N publishers its definition does not declare (~/extra_<i>); --storm N: on SIGUSR2 it
sets its parameter 'mode' N times in a burst (alternately 'turbo', which breaks its
validator, and 'fast'; the last one is 'fast'), printing 'stormed' when done; --churn HZ:
it creates and destroys an undeclared publisher (~/churn) HZ times a second.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
from pathlib import Path

from _common import ready, spin

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # the toolkit's source tree

os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--name', required=True)
    parser.add_argument('--namespace', default='/')
    parser.add_argument('--definition', required=True)
    parser.add_argument('--rate', type=float, default=10.0)
    parser.add_argument('--lax', action='store_true')
    parser.add_argument('--more', type=int, default=0)
    parser.add_argument('--more-definition')
    parser.add_argument('--publishers', type=int, default=0)
    parser.add_argument('--storm', type=int, default=0)
    parser.add_argument('--churn', type=float, default=0.0)
    parser.add_argument('--ros-args', nargs=argparse.REMAINDER, default=[])
    args = parser.parse_args()
    import rclpy
    import std_msgs.msg
    from rcl_interfaces.msg import SetParametersResult
    from rclpy.qos import QoSProfile, ReliabilityPolicy

    from nodl.runtime import NodlNode
    from nodl.system import EntityKind

    class Monitored(NodlNode):
        def _nodl_validate(self, parameters):  # type: ignore[no-untyped-def]
            if args.lax:
                return SetParametersResult(successful=True)
            return super()._nodl_validate(parameters)

    rclpy.init(args=['node', '--ros-args', *args.ros_args])
    node = Monitored(args.definition, args.name, namespace=args.namespace,
                     callbacks={'~/command': lambda _m: None})
    publishers = {name: h for (kind, name), h in node.nodl_handles.items()
                  if kind is EntityKind.PUBLISHER}

    def tick() -> None:
        for handle in publishers.values():
            handle.publish(std_msgs.msg.String(data='reading'))

    node.create_timer(1.0 / args.rate, tick)
    changes: list[int] = []
    signal.signal(signal.SIGUSR1, lambda *_: changes.append(1))

    def change_qos() -> None:
        if not changes:
            return
        changes.clear()
        for name, handle in list(publishers.items()):
            node.destroy_publisher(handle)
            publishers[name] = node.create_publisher(
                std_msgs.msg.String, name, QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))

    node.create_timer(0.05, change_qos)
    others = [Monitored(args.more_definition, f'{args.name}_{i}', namespace=args.namespace,
                        callbacks={'~/command': lambda _m: None})
              for i in range(1, args.more + 1)]
    extra = [node.create_publisher(std_msgs.msg.String, f'~/extra_{i}', 10)
             for i in range(args.publishers)]
    storms: list[int] = []
    signal.signal(signal.SIGUSR2, lambda *_: storms.append(1))

    def storm() -> None:
        if not storms:
            return
        storms.clear()
        from rclpy.parameter import Parameter

        for i in range(args.storm):
            value = 'turbo' if (args.storm - i) % 2 == 0 else 'fast'
            node.set_parameters([Parameter('mode', Parameter.Type.STRING, value)])
        print('stormed', flush=True)

    node.create_timer(0.05, storm)
    churning: list[object] = []

    def churn() -> None:
        if churning:
            node.destroy_publisher(churning.pop())
        else:
            churning.append(node.create_publisher(std_msgs.msg.String, '~/churn', 10))

    if args.churn > 0:
        node.create_timer(1.0 / args.churn, churn)
    ready()
    if not others:
        spin(node)
        return
    from rclpy.executors import SingleThreadedExecutor

    executor = SingleThreadedExecutor()
    for one in [node, *others]:
        executor.add_node(one)
    try:
        executor.spin()
    except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
        pass
    finally:
        del extra
        for one in [node, *others]:
            one.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()


if __name__ == '__main__':
    main()
