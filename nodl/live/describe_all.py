"""``describe --all``: one node definition file per node in the graph."""

from __future__ import annotations

import os
import time
from typing import Any

from nodl.live.describe import describe_node, render_description
from nodl.live.observe import DISCOVERY_WINDOW, list_nodes
from nodl.live.session import LiveError, is_hidden_node, ros_session
from nodl.writing import write_marked

__all__ = ['describe_all', 'file_name_for']


def file_name_for(fqn: str, format: str = 'yaml') -> str:
    """``/robot/driver`` -> ``robot.driver.nodl.yaml``."""
    return fqn.strip('/').replace('/', '.') + ('.nodl.json' if format == 'json' else '.nodl.yaml')


def _discover(node: Any, timeout: float, settle: float, quiet: float = 0.5) -> list[str]:
    """The nodes of the graph once discovery has had its time.

    Remote participants are discovered one by one, each up to one announcement
    period after we start (Fast DDS: 3 s; from milliseconds to 3 s in practice),
    so the node list is followed (:mod:`~nodl.live.graph_events`) and taken
    as soon as discovery has run ``settle`` seconds and the list has not changed
    for ``quiet`` seconds; while it is empty, up to ``timeout``.
    """
    from nodl.live.graph_events import follower

    graph = follower(node)
    graph.settle(quiet, time.monotonic() + timeout, on=['nodes'], ready=lambda: bool(graph.counts),
                 watched=settle)
    return list_nodes(node)


def describe_all(directory: str, *, timeout: float = 5.0, parameters: bool = True,
                 format: str = 'yaml', settle: float = DISCOVERY_WINDOW,
                 client_library: str | None = None, force: bool = False
                 ) -> list[tuple[str, str, list[str]]]:
    """Describe every node in the graph into ``directory``; returns (node, file, notes) per node.

    Discovery is given up to ``timeout`` seconds (see :func:`_discover`); every
    node is then observed in the same session.  A node that vanishes while it
    is described is reported in its notes and skipped.  ``client_library``: see
    :func:`~nodl.live.describe.describe_observed` (by default deduced per node).
    Each file is written as :func:`~nodl.writing.write_marked` writes it: a file
    there that nodl did not write, or that was edited, stops the run with a
    :class:`~nodl.writing.WriteError` unless ``force``; so does a file that would
    land outside ``directory`` (NODL708).
    """
    with ros_session() as node:
        names = _discover(node, timeout, settle)
        os.makedirs(directory, exist_ok=True)
        written = []
        for fqn in names:
            if is_hidden_node(fqn):
                # as `ros2 node list` does without --all: a tool's or daemon's node
                written.append((fqn, '(skipped)', ['a hidden node (its name starts with _), '
                                                   'left out']))
                continue
            try:
                description = describe_node(fqn, timeout=timeout, parameters=parameters,
                                            session=node, client_library=client_library,
                                            watch=settle)
            except LiveError as exc:
                written.append((fqn, '(skipped)', [str(exc)]))
                continue
            path = os.path.join(directory, file_name_for(fqn, format))
            write_marked(path, render_description(description, format), force=force,
                         within=directory)
            written.append((fqn, path, description.warnings + description.notes
                            + [f'version skew: {w} [NODL423]' for w in description.skew_warnings]
                            + description.skew_notes))
    return written
