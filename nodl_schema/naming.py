"""Expanding ROS names against a node, and the reverse (for describe).

``~/scan`` of node ``/robot/driver`` is ``/robot/driver/scan``; ``scan`` is
``/robot/scan``; ``/scan`` stays.  ``{node}``, ``{ns}`` and ``{namespace}``
are substituted first, as rcl does.
"""

from __future__ import annotations

__all__ = ['expand', 'relativize', 'fully_qualified']


def fully_qualified(namespace: str, name: str) -> str:
    """``/namespace/name`` for a node."""
    namespace = '/' + namespace.strip('/') if namespace.strip('/') else ''
    return f'{namespace}/{name}'


def expand(name: str, node_name: str, namespace: str) -> str:
    """The fully qualified form of topic/service/action ``name`` for the given node."""
    ns = '/' + namespace.strip('/') if namespace.strip('/') else '/'
    name = (name.replace('{node}', node_name).replace('{namespace}', ns).replace('{ns}', ns))
    if name == '~':
        return fully_qualified(namespace, node_name)
    if name.startswith('~/'):
        return fully_qualified(namespace, node_name) + name[1:]
    if name.startswith('/'):
        return name
    return (ns.rstrip('/') + '/' + name) if ns != '/' else '/' + name


def relativize(name: str, node_name: str, namespace: str) -> str:
    """The shortest faithful form of an absolute ``name`` for this node.

    Under the node: ``~/x``.  Under its namespace (not at the root): ``x``.
    Otherwise the absolute name.
    """
    own = fully_qualified(namespace, node_name)
    if name == own:
        return '~'
    if name.startswith(own + '/'):
        return '~' + name[len(own):]
    ns = '/' + namespace.strip('/') if namespace.strip('/') else ''
    if ns and name.startswith(ns + '/'):
        return name[len(ns) + 1:]
    return name
