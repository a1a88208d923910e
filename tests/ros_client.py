"""A client node for tests that talk to a node under test in another process.

It has a context of its own (so it never disturbs another rclpy user of the test
process), and every wait has a timeout.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any


class Client:
    """A node of this process with its own context, to talk to the node under test."""

    def __init__(self) -> None:
        import rclpy
        from rclpy.context import Context

        self.context = Context()
        rclpy.init(context=self.context)
        from rclpy.executors import SingleThreadedExecutor

        self.node = rclpy.create_node('gp_test_client', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)

    def spin_until(self, done: Callable[[], bool], timeout: float = 10.0) -> bool:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if done():
                return True
            self.executor.spin_once(timeout_sec=0.05)
        return done()

    def call(self, srv_type: Any, name: str, request: Any, timeout: float = 10.0) -> Any:
        client = self.node.create_client(srv_type, name)
        assert self.spin_until(lambda: client.service_is_ready(), timeout), f'{name} never appeared'
        future = client.call_async(request)
        assert self.spin_until(future.done, timeout), f'{name} did not answer'
        self.node.destroy_client(client)
        return future.result()

    def set_parameter(self, fqn: str, name: str, value: Any) -> Any:
        from rcl_interfaces.srv import SetParameters
        from rclpy.parameter import Parameter

        request = SetParameters.Request(parameters=[Parameter(name, value=value).to_parameter_msg()])
        return self.call(SetParameters, f'{fqn}/set_parameters', request).results[0]

    def get_parameter(self, fqn: str, name: str) -> Any:
        from rcl_interfaces.srv import GetParameters
        from rclpy.parameter import parameter_value_to_python

        reply = self.call(GetParameters, f'{fqn}/get_parameters', GetParameters.Request(names=[name]))
        return parameter_value_to_python(reply.values[0])

    def collect(self, msg_type: Any, topic: str, qos: int = 10) -> list[Any]:
        received: list[Any] = []
        self.node.create_subscription(msg_type, topic, received.append, qos)
        return received

    def close(self) -> None:
        import rclpy

        self.executor.shutdown()
        self.node.destroy_node()
        rclpy.shutdown(context=self.context)
