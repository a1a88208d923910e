"""The graph of a system: vertices (nodes, topics, services, actions) and edges, with
the findings that concern each."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from nodl_schema.analysis.system import Analysis
from nodl_schema.system.entities import Provider

__all__ = ['GraphError', 'Vertex', 'Edge', 'Graph', 'build_graph']


class GraphError(Exception):
    """A picture that cannot be made (the layout program is missing or fails)."""


@dataclass
class Vertex:
    """A node, topic, service or action of the picture."""

    id: str
    #: ``node``, ``topic``, ``service`` or ``action``.
    kind: str
    #: The final name.
    name: str
    #: Details for the page: what it runs, its interface, types.
    details: dict[str, Any] = field(default_factory=dict)
    #: The findings about it (their JSON form).
    findings: list[dict[str, Any]] = field(default_factory=list)
    #: False for a node without a definition.
    defined: bool = True

    @property
    def worst(self) -> str | None:
        """``error``, ``warning``, ``info`` or None."""
        order = ('error', 'warning', 'info')
        found = [f['severity'] for f in self.findings]
        return next((s for s in order if s in found), None)


@dataclass
class Edge:
    """From a vertex to another: publisher -> topic -> subscription, client -> service -> server."""

    source: str
    target: str
    #: ``publisher``, ``subscription``, ``service_server``, ...
    role: str
    findings: list[dict[str, Any]] = field(default_factory=list)


@dataclass
class Graph:
    """The picture's content."""

    title: str
    vertices: dict[str, Vertex]
    edges: list[Edge]


def build_graph(analysis: Analysis) -> Graph:
    """The graph of an analysis (one pass over nodes and findings)."""
    from nodl_schema.analysis.report import node_to_dict

    vertices: dict[str, Vertex] = {}
    node_ids: dict[str, str] = {}
    for node in analysis.nodes:
        if node.fqn in node_ids:
            continue  # a duplicate name: one vertex, the finding says there are two
        vid = f'n{len(node_ids)}'
        node_ids[node.fqn] = vid
        vertices[vid] = Vertex(vid, 'node', node.fqn, node_to_dict(node),
                               defined=node.instance is not None)
    channel_ids: dict[tuple[str, str], str] = {}
    edges: dict[tuple[str, str], Edge] = {}
    for node in analysis.nodes:
        if node.instance is None:
            continue
        nid = node_ids[node.fqn]
        for bound in node.instance.endpoints:
            entity = bound.entity
            if entity.provider is Provider.CLIENT_LIBRARY:
                continue
            communication = entity.kind.communication or 'topic'
            key = (communication, bound.name)
            cid = channel_ids.get(key)
            if cid is None:
                cid = f'c{len(channel_ids)}'
                channel_ids[key] = cid
                vertices[cid] = Vertex(cid, communication, bound.name, {'types': []})
            types = vertices[cid].details['types']
            if entity.type_name not in types:
                types.append(entity.type_name)
            offers = entity.kind.offers
            if communication == 'topic':
                source, target = (nid, cid) if offers else (cid, nid)
            else:  # client -> service -> server
                source, target = (cid, nid) if offers else (nid, cid)
            edges.setdefault((source, target), Edge(source, target, entity.kind.value))
    by_channel_name: dict[str, list[str]] = {}
    for (_, name), cid in channel_ids.items():
        by_channel_name.setdefault(name, []).append(cid)
    for finding in analysis.findings:
        data = finding.to_dict()
        involved = [node_ids[n] for n in finding.nodes if n in node_ids]
        channels = by_channel_name.get(finding.endpoint or '', [])
        for vid in involved + channels:
            vertices[vid].findings.append(data)
        for cid in channels:
            for nid in involved:
                for key in ((nid, cid), (cid, nid)):
                    if key in edges:
                        edges[key].findings.append(data)
    title = analysis.launch_file or 'system'
    return Graph(title, vertices, list(edges.values()))
