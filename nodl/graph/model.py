"""The graph of a system: vertices (nodes, topics, services, actions) and edges, with
the findings that concern each."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from nodl.composition.entities import Provider
from nodl.system.run import Analysis

__all__ = [
    'Cluster',
    'Edge',
    'Graph',
    'GraphError',
    'Vertex',
    'build_graph',
    'isolated_vertices',
    'namespace_of',
]

#: Who provides an entity, in the order a node's interface is listed: the node's own code,
#: then other code it uses (a mixin), then what the client library gives every node.
PROVIDER_ORDER = (Provider.IMPLEMENTATION, Provider.OTHER_CODE, Provider.CLIENT_LIBRARY)


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
    #: The namespace the vertex is drawn in (rqt_graph's grouping): a node's namespace, a
    #: topic's, service's or action's name without its last token.
    namespace: str = '/'

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
class Cluster:
    """A namespace drawn as a box around its vertices (and the namespaces below it)."""

    id: str
    #: The namespace (``/rover/sensors``).
    name: str
    #: The enclosing cluster's id, or None at the top.
    parent: str | None = None
    #: The vertices directly in it (not in a cluster below it).
    vertices: list[str] = field(default_factory=list)
    #: The clusters directly below it.
    children: list[str] = field(default_factory=list)


@dataclass
class Graph:
    """The picture's content."""

    title: str
    vertices: dict[str, Vertex]
    edges: list[Edge]
    #: The namespaces drawn as boxes, by id (outer ones before the ones they hold).
    clusters: dict[str, Cluster] = field(default_factory=dict)

    def top_vertices(self) -> list[str]:
        """The vertices in no cluster."""
        inside = {v for c in self.clusters.values() for v in c.vertices}
        return [v for v in self.vertices if v not in inside]

    def top_clusters(self) -> list[str]:
        """The outermost clusters."""
        return [c.id for c in self.clusters.values() if c.parent is None]


def namespace_of(name: str) -> str:
    """The namespace of a fully qualified name: ``/a/b/c`` -> ``/a/b``, ``/c`` -> ``/``."""
    head = name.rstrip('/').rsplit('/', 1)[0]
    return head or '/'


def isolated_vertices(graph: Graph) -> set[str]:
    """The vertices no edge touches."""
    touched = {e.source for e in graph.edges} | {e.target for e in graph.edges}
    return set(graph.vertices) - touched


def _clusters(vertices: dict[str, Vertex]) -> dict[str, Cluster]:
    """The namespace boxes, as rqt_graph groups by namespace: a box for every namespace that
    holds two vertices or more (directly or below it); a namespace that would hold nothing
    but one box is not drawn (the box below it goes up a level)."""
    count: dict[str, int] = {}
    for vertex in vertices.values():
        namespace = vertex.namespace
        while namespace != '/':
            count[namespace] = count.get(namespace, 0) + 1
            namespace = namespace_of(namespace)
    boxed = {ns for ns, n in count.items() if n >= 2}

    def nearest(namespace: str) -> str | None:
        while namespace != '/':
            if namespace in boxed:
                return namespace
            namespace = namespace_of(namespace)
        return None

    direct: dict[str, list[str]] = {ns: [] for ns in boxed}
    for vid, vertex in vertices.items():
        home = nearest(vertex.namespace)
        if home is not None:
            direct[home].append(vid)
    below: dict[str, list[str]] = {ns: [] for ns in boxed}
    parent_of = {ns: nearest(namespace_of(ns)) for ns in boxed}
    for ns in sorted(boxed):
        above = parent_of[ns]
        if above is not None:
            below[above].append(ns)
    # a box holding only one box and no vertex adds nothing: its child takes its place
    for ns in sorted(boxed, key=lambda n: -n.count('/')):
        if not direct[ns] and len(below[ns]) == 1:
            child = below[ns][0]
            up = parent_of[ns]
            parent_of[child] = up
            if up is not None:
                below[up] = [child if c == ns else c for c in below[up]]
            boxed.discard(ns)
    ids = {ns: f'k{i}' for i, ns in enumerate(sorted(boxed))}
    clusters = {}
    for ns in sorted(boxed):
        above = parent_of[ns]
        clusters[ids[ns]] = Cluster(ids[ns], ns, ids[above] if above is not None else None,
                                    direct[ns], [ids[c] for c in below[ns]])
    return clusters


def build_graph(analysis: Analysis) -> Graph:
    """The graph of an analysis (one pass over nodes and findings)."""
    vertices: dict[str, Vertex] = {}
    node_ids: dict[str, str] = {}
    for node in analysis.nodes:
        if node.fqn in node_ids:
            continue  # a duplicate name: one vertex, the finding says there are two
        vid = f'n{len(node_ids)}'
        node_ids[node.fqn] = vid
        vertices[vid] = Vertex(vid, 'node', node.fqn, _node_details(node, node.to_dict()),
                               defined=node.instance is not None,
                               namespace=namespace_of(node.fqn))
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
                vertices[cid] = Vertex(cid, communication, bound.name, {'types': []},
                                       namespace=namespace_of(bound.name))
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
    return Graph(title, vertices, list(edges.values()), _clusters(vertices))


def _node_details(node: Any, report: dict[str, Any]) -> dict[str, Any]:
    """A node's details for the page: its JSON report entry, with its endpoints as one list
    (``interface``), the node's own first, then what other code (a mixin) brings, then what
    its client library gives every node (parameter services, ``/parameter_events``,
    ``/rosout``, ...), each ``{section, declared, name, type, provider}``."""
    details = {k: v for k, v in report.items() if k != 'endpoints'}
    interface: list[dict[str, str]] = []
    if node.instance is not None:
        details['client_library'] = node.instance.resolved.client_library
        rank = {provider: i for i, provider in enumerate(PROVIDER_ORDER)}
        # stable: within a provider, the definition's order (sections as written)
        for bound in sorted(node.instance.endpoints,
                            key=lambda b: rank.get(b.entity.provider, 0)):
            entity = bound.entity
            interface.append({'section': entity.section, 'declared': entity.name,
                              'name': bound.name, 'type': entity.type_name,
                              'provider': entity.provider.value})
    details['interface'] = interface
    return details
