"""The graph as Graphviz DOT (every name and message escaped)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from nodl.graph.model import Edge, Graph, Vertex, isolated_vertices
from nodl.text_safety import visible

__all__ = ['COLOURS', 'GRID_ASPECT', 'SHAPES', 'dot_string', 'format_dot', 'grid_edges']

#: The width/height a grid of unconnected nodes aims at (a 1280x800 window's).
GRID_ASPECT = 1.6
#: At most this many lines of a node's interface in its tooltip.
TOOLTIP_ENTITIES = 12

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
    # control and bidi characters shown as escapes, never rendered (nodl.text_safety)
    escaped = visible(text).replace('\\', '\\\\').replace('"', '\\"')
    return '"' + escaped.replace('\n', '\\n') + '"'


def _tooltip(vertex_or_edge: Vertex | Edge, fallback: str) -> str:
    messages = [f"{f['severity']}: {f['message']}" for f in vertex_or_edge.findings]
    return '\n'.join(messages[:5] + (['...'] if len(messages) > 5 else [])) or fallback


def _node_tooltip(v: Vertex) -> str:
    """A node's name, its findings, then its own interface before what its client library
    gives it (counted, not listed: every node has the same)."""
    lines = [v.name]
    findings = _tooltip(v, '')
    if findings:
        lines.append(findings)
    interface = v.details.get('interface', [])
    own = [e for e in interface if e['provider'] != 'client_library']
    for entity in own[:TOOLTIP_ENTITIES]:
        word = entity['section'].replace('_', ' ').rstrip('s')
        lines.append(f"{word} {entity['name']} ({entity['type']})")
    if len(own) > TOOLTIP_ENTITIES:
        lines.append(f'... and {len(own) - TOOLTIP_ENTITIES} more')
    base = len(interface) - len(own)
    if base:
        lines.append(f"+ {base} from {v.details.get('client_library', 'the client library')} "
                     '(parameter services, /parameter_events, /rosout, ...)')
    return '\n'.join(lines)


def _vertex(v: Vertex) -> str:
    tooltip = _node_tooltip(v) if v.kind == 'node' else _tooltip(v, v.name)
    attrs = [SHAPES[v.kind], f'label={dot_string(v.name)}', f'id={dot_string(v.id)}',
             f'tooltip={dot_string(tooltip)}']
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


@dataclass
class _Item:
    """Something placed in a grid: a vertex, or a namespace box holding a grid of its own."""

    head: str   # the vertex the chain enters it by (its first rank)
    tail: str   # the vertex the chain leaves it by (its last rank)
    along: float   # its extent along the ranks (points, estimated)
    across: float   # its extent across them


def _size(v: Vertex, rankdir: str) -> tuple[float, float]:
    """A vertex's estimated extent along and across the ranks, spacing included, in points
    (11 pt Helvetica: about 6.2 pt a character; ranksep 65, nodesep 22)."""
    width, height = len(v.name) * 6.2 + 30, 36.0
    return (width + 65, height + 22) if rankdir == 'LR' else (height + 65, width + 22)


def grid_edges(graph: Graph, rankdir: str = 'LR') -> list[tuple[str, str, bool]]:
    """The invisible edges that lay out what has no edge as a grid instead of one long column.

    ``dot`` puts every vertex without an edge in the first rank: one column (a row, top to
    bottom) as long as there are such vertices.  In each namespace (and at the top), the
    vertices without an edge and the namespaces none of whose vertices has one are chained
    along the ranks (``(a, b, False)``: b one rank after a), the chains' first items tied
    across them (``(a, b, True)``: b next to a, in the same rank), as many to a chain as
    makes the grid about :data:`GRID_ASPECT` wide for its height.
    """
    ratio = GRID_ASPECT if rankdir == 'LR' else 1 / GRID_ASPECT
    lonely = isolated_vertices(graph)
    out: list[tuple[str, str, bool]] = []

    def level(vertices: list[str], children: list[str]) -> tuple[_Item | None, bool]:
        """The level's grid as an item, and whether nothing in it has an edge."""
        items: list[_Item] = []
        all_lonely = True
        for child in children:
            item, child_lonely = level(graph.clusters[child].vertices,
                                       graph.clusters[child].children)
            all_lonely &= child_lonely
            if child_lonely and item is not None:   # the box's margins and label
                items.append(_Item(item.head, item.tail, item.along + 24, item.across + 24))
        for vid in vertices:
            if vid in lonely:
                items.append(_Item(vid, vid, *_size(graph.vertices[vid], rankdir)))
            else:
                all_lonely = False
        if not items:
            return None, all_lonely
        along = sum(i.along for i in items) / len(items)
        across = sum(i.across for i in items) / len(items)
        # k to a chain, n/k chains: k*along / ((n/k)*across) = ratio (LR: width/height)
        per_chain = max(1, min(len(items), round(math.sqrt(ratio * len(items)
                                                           * across / along))))
        chains = [items[i:i + per_chain] for i in range(0, len(items), per_chain)]
        for chain in chains:
            out.extend((a.tail, b.head, False) for a, b in zip(chain, chain[1:], strict=False))
        out.extend((a[0].head, b[0].head, True) for a, b in zip(chains, chains[1:], strict=False))
        return _Item(chains[0][0].head, chains[0][-1].tail,
                     max(sum(i.along for i in chain) for chain in chains),
                     sum(max(i.across for i in chain) for chain in chains)), all_lonely

    level(graph.top_vertices(), graph.top_clusters())
    return out


def _cluster_lines(graph: Graph, cid: str, depth: int) -> list[str]:
    cluster = graph.clusters[cid]
    pad = '  ' * (depth + 1)
    fill = ('#f8f9fa', '#f1f3f4')[depth % 2]
    lines = [f'{pad}subgraph cluster_{cid} {{',
             f'{pad}  id={dot_string(cid)}; label={dot_string(cluster.name)}; labeljust=l;',
             f'{pad}  style="rounded,filled"; color="#9aa0a6"; fillcolor="{fill}"; '
             'fontcolor="#3c4043";']
    lines += [pad + _vertex(graph.vertices[vid]).lstrip() for vid in cluster.vertices]
    for child in cluster.children:
        lines += _cluster_lines(graph, child, depth + 1)
    lines.append(f'{pad}}}')
    return lines


def format_dot(graph: Graph, rankdir: str = 'LR') -> str:
    """The DOT text: namespaces as clusters (``cluster_k<N>``, id ``k<N>``), what has no edge
    as a grid (:func:`grid_edges`); ``rankdir`` ``LR`` (rqt_graph's, the default) or ``TB``."""
    if rankdir not in ('LR', 'TB'):
        raise ValueError(f"rankdir must be 'LR' or 'TB', not {rankdir!r}")
    lines = ['digraph system {',
             f'  label={dot_string(graph.title)}; labelloc=t; rankdir={rankdir};',
             '  graph [fontname="Helvetica", fontsize=12, nodesep=0.3, ranksep=0.9];',
             '  node [fontname="Helvetica", fontsize=11];',
             '  edge [color="#5f6368", arrowsize=0.7];']
    lines += [_vertex(graph.vertices[vid]) for vid in graph.top_vertices()]
    for cid in graph.top_clusters():
        lines += _cluster_lines(graph, cid, 0)
    lines += [_edge(e) for e in graph.edges]
    lines += [f'  {a} -> {b} [style=invis{", minlen=0" if below else ""}];'
              for a, b, below in grid_edges(graph, rankdir)]
    lines.append('}')
    return '\n'.join(lines) + '\n'
