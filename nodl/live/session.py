"""An rclpy session of our own: a private context, an observer node, an executor."""

from __future__ import annotations

import itertools
import os
import time
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from typing import Any

__all__ = ['LiveError', 'NodeNotFound', 'DuplicateNode', 'require_rclpy', 'ros_session',
           'open_session', 'close_session', 'count_node_names',
           'split_node_name', 'OBSERVER_PREFIX',
           'HIDDEN_NODE_PREFIX', 'is_hidden_node', 'is_toolkit_node', 'without_toolkit_nodes',
           'MONITOR_NODE_NAME']

#: A node whose name starts with this is hidden, as ROS hides nodes (``ros2 node list``
#: leaves them out without ``--all``): tools and daemons.
HIDDEN_NODE_PREFIX = '_'
#: The toolkit's own observer nodes are named ``_nodl_observer_<pid>_<n>``: hidden, and
#: unique per process and per session, so that two sessions (in one process or in two)
#: are never namesakes of each other.
OBSERVER_PREFIX = '_nodl_observer_'
#: The name of ``nodl monitor``'s node: hidden, and left out by every live verb as the
#: observers are (any node whose name starts with it).
MONITOR_NODE_NAME = '_nodl_monitor'
_TOOLKIT_PREFIXES = (OBSERVER_PREFIX, MONITOR_NODE_NAME)
_SESSIONS = itertools.count(1)


def is_hidden_node(fqn: str) -> bool:
    """Whether the node ``/namespace/name`` is hidden (its name starts with ``_``)."""
    return fqn.rpartition('/')[2].startswith(HIDDEN_NODE_PREFIX)


def is_toolkit_node(fqn: str) -> bool:
    """Whether ``/namespace/name`` is one of the toolkit's own observer nodes (any process's),
    or a ``nodl monitor`` node."""
    return fqn.rpartition('/')[2].startswith(_TOOLKIT_PREFIXES)


def count_node_names(names: Iterable[tuple[str, str]]) -> dict[str, int]:
    """How many nodes of each fully qualified name ``names`` holds (``(name, namespace)``
    pairs, as ``get_node_names_and_namespaces`` lists them), the toolkit's own left out."""
    from nodl.naming import join_name

    counts: dict[str, int] = {}
    for name, namespace in names:
        fqn = join_name(namespace, name)
        if not is_toolkit_node(fqn):
            counts[fqn] = counts.get(fqn, 0) + 1
    return counts


def without_toolkit_nodes(infos: Iterable[Any]) -> list[Any]:
    """Topic endpoint infos (``get_publishers_info_by_topic``...) less the toolkit's own.

    Every observer node publishes ``/parameter_events`` and serves
    ``~/get_type_description``, as every rclpy node does; they are not the user's.
    """
    return [i for i in infos
            if not i.node_name.startswith(_TOOLKIT_PREFIXES)]


class LiveError(Exception):
    """A live feature cannot run (no ROS, node gone, ...); the message says why."""


class NodeNotFound(LiveError):
    """The node did not appear in the graph within the timeout."""


class DuplicateNode(LiveError):
    """Several nodes in the graph share the name; which one is meant cannot be told."""


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
    from nodl.naming import split_name

    return split_name(name)


def open_session(name: str, args: list[str], *, parameter_services: bool = False) -> Any:
    """A node ``name`` in a private rclpy context started with ``args`` (as ``sys.argv``:
    ``--ros-args`` and what follows), with what every live wait needs: its executor
    (``nodl_executor``, the node added) and when its discovery started (``nodl_started``);
    its graph follower (:func:`~nodl.live.graph_events.follower`) is made on first use.
    rclpy installs no signal handlers (Ctrl-C and SIGTERM are the caller's).  End it with
    :func:`close_session`.  Raises :class:`LiveError` when rclpy refuses ``args``.
    """
    rclpy = require_rclpy()
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.signals import SignalHandlerOptions

    context = rclpy.Context()
    try:
        rclpy.init(context=context, args=args, signal_handler_options=SignalHandlerOptions.NO)
    except Exception as exc:  # noqa: BLE001 - rcl's words for bad --ros-args
        raise LiveError(f'cannot start the node {name}: {exc}') from None
    try:
        node = rclpy.create_node(name, context=context,
                                 start_parameter_services=parameter_services,
                                 enable_rosout=False)
        executor = SingleThreadedExecutor(context=context)
        executor.add_node(node)
    except BaseException:
        if context.ok():
            rclpy.shutdown(context=context)
        raise
    node.nodl_executor = executor
    #: When its discovery started (see nodl.live.observe.DISCOVERY_WINDOW).
    node.nodl_started = time.monotonic()
    return node


def close_session(node: Any) -> None:
    """Stop a session of :func:`open_session`: its graph follower's thread, the node, the
    context (the other nodes made in it go with it)."""
    import rclpy

    graph = getattr(node, 'nodl_graph', None)
    if graph is not None:
        graph.unwatch()
    context = node.context
    node.destroy_node()
    if context.ok():
        rclpy.shutdown(context=context)


@contextmanager
def ros_session() -> Iterator[Any]:
    """Yield an observer node in a private rclpy context; everything is shut down after.

    The node is hidden and unique (see :data:`OBSERVER_PREFIX`); the live features
    leave it, and every other session's, out of what they report.
    """
    node = open_session(f'{OBSERVER_PREFIX}{os.getpid()}_{next(_SESSIONS)}',
                        ['--ros-args', '--disable-rosout-logs', '--log-level', 'fatal'])
    try:
        yield node
    finally:
        close_session(node)
