"""Former path of :mod:`nodl.graph` (the pictures of a system, shared by every consumer)."""

from __future__ import annotations

from nodl.graph import FORMATS, GraphError, render_graph

__all__ = ['FORMATS', 'GraphError', 'render_graph']
