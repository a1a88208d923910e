"""The dynamic runtime: a definition's interface on a real rclpy node, without generating code.

``NodlNode(DEFINITION, node_name=None, callbacks=..., **kwargs)`` and
``NodlLifecycleNode`` build the main entities of a node definition (what the
implementation provides) on an rclpy node, with the parameter behaviour of
generated code: descriptors, required parameters, every validator at start-up
and at set time (the validator table's predicates), a typed snapshot
``node.params``, ``is_old``/``try_update`` and an on-change hook.

Callbacks are bound by a mapping (declared name -> callable; ``(kind, name)`` ->
callable when a subscription, service server or action server share the name) or
by decorating methods of a subclass with :func:`callback` (``kind=`` for such a
name); a declared subscription, service
server or action server without one is an error, and every interface type is
imported before the node is created.  Handles are reachable by declared name:
``node.endpoint('~/scan')`` (``kind=`` when two kinds share a name) and
``node.nodl_handles`` (``(EntityKind, name) -> handle``).

Importing this package does not import rclpy; using a class does.
"""

from __future__ import annotations

from typing import Any

from nodl.runtime.binding import callback
from nodl.runtime.errors import RuntimeDefinitionError

__all__ = ['NodlNode', 'NodlLifecycleNode', 'RuntimeDefinitionError', 'callback', 'ActionCallbacks']


def __getattr__(name: str) -> Any:
    # NodlNode needs rclpy, which `import nodl.runtime` must not (the decorators and errors
    # are used without ROS): the node module is loaded when one of its names is asked for.
    if name in ('NodlNode', 'NodlLifecycleNode'):
        from nodl.runtime import node

        return getattr(node, name)
    if name == 'ActionCallbacks':
        from nodl.runtime.binding import ActionCallbacks

        return ActionCallbacks
    raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
