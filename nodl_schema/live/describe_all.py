"""``describe --all``: one node definition file per node in the graph."""

from __future__ import annotations

import os

from nodl_schema.live.describe import describe_node, render_description
from nodl_schema.live.observe import list_nodes
from nodl_schema.live.session import LiveError, ros_session

__all__ = ['describe_all', 'file_name_for']


def file_name_for(fqn: str, format: str = 'yaml') -> str:
    """``/robot/driver`` -> ``robot.driver.nodl.yaml``."""
    return fqn.strip('/').replace('/', '.') + ('.nodl.json' if format == 'json' else '.nodl.yaml')


def describe_all(directory: str, *, timeout: float = 5.0, parameters: bool = True,
                 format: str = 'yaml', settle: float = 1.0) -> list[tuple[str, str, list[str]]]:
    """Describe every node in the graph into ``directory``; returns (node, file, notes) per node.

    A node that vanishes while it is described is reported in its notes and skipped.
    """
    import time

    with ros_session() as node:
        deadline = time.monotonic() + settle
        while time.monotonic() < deadline:
            node.nodl_executor.spin_once(timeout_sec=0.05)
        names = list_nodes(node)
    os.makedirs(directory, exist_ok=True)
    written = []
    for fqn in names:
        try:
            description = describe_node(fqn, timeout=timeout, parameters=parameters)
        except LiveError as exc:
            written.append((fqn, '(skipped)', [str(exc)]))
            continue
        path = os.path.join(directory, file_name_for(fqn, format))
        with open(path, 'w', encoding='utf-8') as f:
            f.write(render_description(description, format))
        written.append((fqn, path, description.notes))
    return written
