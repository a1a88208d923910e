"""An rclpy session of our own: a private context, an observer node, an executor."""

from __future__ import annotations

import os
from typing import Any, Iterator
from contextlib import contextmanager

__all__ = ['LiveError', 'NodeNotFound', 'require_rclpy', 'ros_session', 'split_node_name']


class LiveError(Exception):
    """A live feature cannot run (no ROS, node gone, ...); the message says why."""


class NodeNotFound(LiveError):
    """The node did not appear in the graph within the timeout."""


def require_rclpy() -> Any:
    """Import rclpy, or explain how to get it.

    Discovery settings (``ROS_AUTOMATIC_DISCOVERY_RANGE``, ``ROS_DOMAIN_ID``)
    are the user's: the toolkit observes whatever graph their environment
    reaches.  Our tests, demo and benchmarks confine themselves to loopback.
    """
    try:
        import rclpy
    except ImportError as exc:
        raise LiveError(f'this needs ROS 2 (rclpy could not be imported: {exc}); install the '
                        "toolkit's ros extra: pip install 'nodl-toolkit[ros]'") from None
    return rclpy


def split_node_name(name: str) -> tuple[str, str]:
    """``/ns/sub/name`` -> ``('/ns/sub', 'name')``; a bare name is in ``/``."""
    name = name.strip()
    if not name.startswith('/'):
        name = '/' + name
    namespace, _, base = name.rpartition('/')
    return namespace or '/', base


@contextmanager
def ros_session(name: str = 'nodl_observer') -> Iterator[Any]:
    """Yield an observer node in a private rclpy context; everything is shut down after."""
    rclpy = require_rclpy()
    from rclpy.executors import SingleThreadedExecutor

    context = rclpy.Context()
    rclpy.init(context=context, args=['--ros-args', '--disable-rosout-logs',
                                      '--log-level', 'fatal'])
    node = None
    try:
        node = rclpy.create_node(f'{name}_{os.getpid()}', context=context,
                                 start_parameter_services=False,
                                 enable_rosout=False)
        executor = SingleThreadedExecutor(context=context)
        executor.add_node(node)
        node.nodl_executor = executor
        yield node
    finally:
        if node is not None:
            node.destroy_node()
        if context.ok():
            rclpy.shutdown(context=context)
