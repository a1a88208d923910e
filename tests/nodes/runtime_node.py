"""A node built at run time from a definition (nodl.runtime), no generated code.

Usage: runtime_node.py --name NAME [--namespace NS] --definition FILE --kind
talker|managed_camera|everything [--ros-args ...].  talker binds callbacks by mapping,
everything by decorated methods, managed_camera is a NodlLifecycleNode.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from _common import ready, spin

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # the toolkit's source tree

os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'


def build(kind: str, definition: str, name: str, namespace: str):  # type: ignore[no-untyped-def]
    import std_msgs.msg
    from rclpy.action import CancelResponse, GoalResponse

    from nodl.runtime import NodlLifecycleNode, NodlNode, callback

    if kind == 'talker':
        holder: dict[str, object] = {}

        def on_command(msg):  # type: ignore[no-untyped-def]
            node = holder['node']
            node.endpoint('~/chatter').publish(  # type: ignore[attr-defined]
                std_msgs.msg.String(data=f'{node.params.greeting}:{msg.data}'))  # type: ignore[attr-defined]

        def changed(old, new):  # type: ignore[no-untyped-def]
            holder['node'].endpoint('~/chatter').publish(  # type: ignore[attr-defined]
                std_msgs.msg.String(data=f'rate:{old.rate}->{new.rate}'))

        node = NodlNode(definition, name, callbacks={'~/command': on_command},
                        on_parameters_changed=changed, namespace=namespace)
        holder['node'] = node
        return node

    if kind == 'managed_camera':
        class Camera(NodlLifecycleNode):
            def on_configure(self, state):  # type: ignore[no-untyped-def]
                result = super().on_configure(state)
                self.timer = self.create_timer(0.1, self.tick)
                return result

            def tick(self) -> None:
                self.endpoint('~/frames').publish(std_msgs.msg.String(data=f'frame at {self.params.fps} fps'))

            @callback('~/snapshot')
            def snapshot(self, request, response):  # type: ignore[no-untyped-def]
                response.success = True
                response.message = self.params.device
                return response

        return Camera(definition, name, namespace=namespace)

    class Everything(NodlNode):
        @callback('~/in')
        def on_in(self, msg):  # type: ignore[no-untyped-def]
            self.endpoint('~/out', 'publisher').publish(std_msgs.msg.String(data='got:' + msg.data))

        @callback('~/trigger')
        def on_trigger(self, request, response):  # type: ignore[no-untyped-def]
            response.success = True
            response.message = f'{self.params.mode} {self.params.group.inner.depth} {self.params.class_}'
            return response

        @callback('~/configure')
        def on_configure_service(self, request, response):  # type: ignore[no-untyped-def]
            response.success = request.data
            response.message = 'set'
            return response

        @callback('~/fibonacci', 'goal')
        def goal(self, goal):  # type: ignore[no-untyped-def]
            return GoalResponse.ACCEPT if goal.order < 50 else GoalResponse.REJECT

        @callback('~/fibonacci', 'cancel')
        def cancel(self, goal_handle):  # type: ignore[no-untyped-def]
            return CancelResponse.ACCEPT

        @callback('~/fibonacci', 'execute')
        def execute(self, goal_handle):  # type: ignore[no-untyped-def]
            import test_msgs.action

            sequence = [0, 1]
            for _ in range(goal_handle.request.order - 1):
                sequence.append(sequence[-1] + sequence[-2])
            goal_handle.succeed()
            return test_msgs.action.Fibonacci.Result(sequence=sequence[:goal_handle.request.order + 1])

    def is_even(value, arguments):  # type: ignore[no-untyped-def]
        return None if value % 2 == 0 else 'must be even'

    return Everything(definition, name, custom_validators={'my_pkg::is_even': is_even}, namespace=namespace)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--name', required=True)
    parser.add_argument('--namespace', default='/')
    parser.add_argument('--definition', required=True)
    parser.add_argument('--kind', required=True)
    parser.add_argument('--ros-args', nargs=argparse.REMAINDER, default=[])
    args = parser.parse_args()
    import rclpy

    from nodl.runtime import RuntimeDefinitionError

    rclpy.init(args=['node', '--ros-args', *args.ros_args])
    try:
        node = build(args.kind, args.definition, args.name, args.namespace)
    except RuntimeDefinitionError as exc:
        print(f'refused: {exc}', flush=True)
        rclpy.shutdown()
        sys.exit(1)
    ready()
    spin(node)


if __name__ == '__main__':
    main()
