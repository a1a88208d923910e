"""Pictures of an analysed system: Graphviz DOT, SVG and a self-contained HTML page.

The shapes are those of rqt_graph: nodes are ellipses, topics boxes; services
and actions get their own shapes (a hexagon, a double octagon), so the three
are told apart.  What the client library gives every node (``/rosout``,
``/parameter_events``, the parameter services) is left out, as rqt_graph hides
it.  Findings are marked on the nodes and on the topics, services and actions
they concern (red: error, orange: warning), with their messages as tooltips;
nodes without a definition are dashed.  Namespaces are clusters (foldable in the
HTML page); what has no edge is laid out as a grid.

SVG and HTML are laid out by ``graphviz-pure`` (the ``graph`` extra:
``pip install 'nodl-toolkit[graph]'``); without it they fail with a
:class:`GraphError` that says so.  DOT needs nothing.
"""

from __future__ import annotations

from nodl.graph.dot import format_dot
from nodl.graph.html import format_html
from nodl.graph.layout import layout_graph
from nodl.graph.model import GraphError, build_graph
from nodl.system.run import Analysis

__all__ = ['FORMATS', 'GraphError', 'render_graph']

#: The formats, by file extension.
FORMATS = ('dot', 'svg', 'html')


def render_graph(analysis: Analysis, format: str) -> str:
    """The picture of ``analysis`` as ``dot``, ``svg`` or ``html`` text."""
    if format not in FORMATS:
        raise GraphError(f"unknown graph format '{format}'; expected one of {', '.join(FORMATS)}")
    graph = build_graph(analysis)
    if format == 'dot':
        return format_dot(graph)
    svg = layout_graph(graph)
    if format == 'svg':
        return svg
    return format_html(graph, svg, analysis)
