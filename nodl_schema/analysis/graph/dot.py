"""The graph as Graphviz DOT (every name and message escaped)."""

from __future__ import annotations

from nodl_schema.analysis.graph.model import Edge, Graph, Vertex
from nodl_schema.text_safety import visible

__all__ = ['format_dot', 'dot_string', 'SHAPES', 'COLOURS']

#: Vertex kind -> Graphviz attributes (rqt_graph's shapes for nodes and topics).
SHAPES = {
    'node': 'shape=ellipse, style=filled, fillcolor="#e8f0fe"',
    'topic': 'shape=box, style=filled, fillcolor="#f1f3f4"',
    'service': 'shape=hexagon, style=filled, fillcolor="#e6f4ea"',
    'action': 'shape=doubleoctagon, style=filled, fillcolor="#fef7e0"',
}
#: Severity -> the colour of what a finding concerns.
COLOURS = {'error': '#d93025', 'warning': '#e37400', 'info': '#5f6368'}
_EDGE_STYLES = {'publisher': '', 'subscription': '', 'service_server': 'style=dashed',
                'service_client': 'style=dashed', 'action_server': 'style=bold',
                'action_client': 'style=bold'}


def dot_string(text: str) -> str:
    """``text`` as a quoted DOT string (backslashes, quotes and line breaks escaped)."""
    # control and bidi characters shown as escapes, never rendered (nodl_schema.text_safety)
    escaped = visible(text).replace('\\', '\\\\').replace('"', '\\"')
    return '"' + escaped.replace('\n', '\\n') + '"'


def _tooltip(vertex_or_edge: Vertex | Edge, fallback: str) -> str:
    messages = [f"{f['severity']}: {f['message']}" for f in vertex_or_edge.findings]
    return '\n'.join(messages[:5] + (['...'] if len(messages) > 5 else [])) or fallback


def _vertex(v: Vertex) -> str:
    attrs = [SHAPES[v.kind], f'label={dot_string(v.name)}', f'id={dot_string(v.id)}',
             f'tooltip={dot_string(_tooltip(v, v.name))}']
    if not v.defined:
        attrs.append('style="filled,dashed", fillcolor="#ffffff"')
    worst = v.worst
    if worst in ('error', 'warning'):
        attrs.append(f'color="{COLOURS[worst]}", penwidth=2.5')
    return f'  {v.id} [{", ".join(attrs)}];'


def _edge(e: Edge) -> str:
    attrs = [a for a in (_EDGE_STYLES.get(e.role, ''),) if a]
    attrs.append(f'id={dot_string(e.source + "-" + e.target)}')
    severities = {f['severity'] for f in e.findings}
    worst = next((s for s in ('error', 'warning') if s in severities), None)
    if worst is not None:
        attrs.append(f'color="{COLOURS[worst]}", penwidth=2')
        attrs.append(f'tooltip={dot_string(_tooltip(e, ""))}')
    return f'  {e.source} -> {e.target} [{", ".join(attrs)}];'


def format_dot(graph: Graph) -> str:
    """The DOT text."""
    lines = ['digraph system {',
             f'  label={dot_string(graph.title)}; labelloc=t; rankdir=LR;',
             '  graph [fontname="Helvetica", fontsize=12, nodesep=0.3, ranksep=0.9];',
             '  node [fontname="Helvetica", fontsize=11];',
             '  edge [color="#5f6368", arrowsize=0.7];']
    lines += [_vertex(v) for v in graph.vertices.values()]
    lines += [_edge(e) for e in graph.edges]
    lines.append('}')
    return '\n'.join(lines) + '\n'
