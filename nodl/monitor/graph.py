"""The monitor's full scans of the live graph.

The graph is followed by the live layer's :class:`~nodl.live.graph_events.GraphFollower`
(node names at 10 Hz, topic names every third poll: what changes when nodes or topics
come or go), as every live verb follows it.  A :meth:`GraphView.scan` (the endpoints of
the nodes asked for, every topic's endpoint infos with QoS, type hash and GID) is taken
when the follower saw a change, and periodically, since an endpoint recreated with another
QoS leaves the names unchanged, and a service added to a running node changes no topic.
A scan converts only the endpoints it has not seen before (by GID and node name: an
endpoint's QoS and type never change).  Nothing here spins or polls.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from nodl.live.observe import ACTION_INFIX, ObservedEndpoint, ObservedNode
from nodl.live.qos import qos_from_rclpy
from nodl.live.session import is_toolkit_node, split_node_name
from nodl.naming import join_name

__all__ = ['LiveTopicEndpoint', 'Snapshot', 'GraphView', 'observed_node', 'discovered']

_SECTIONS = ('publishers', 'subscriptions', 'service_servers', 'service_clients')
#: How many topics a scan reads between two calls of its ``meanwhile``.
SCAN_CHUNK = 100


@dataclass(frozen=True)
class LiveTopicEndpoint:
    """One publisher or subscription of a topic, as the graph reports it."""

    topic: str
    #: The fully qualified name of its node.
    node: str
    #: ``publisher`` or ``subscription``.
    kind: str
    type: str
    #: The NoDL QoS fields the middleware reported, as ``(key, value)`` pairs.
    qos: tuple[tuple[str, Any], ...]
    #: QoS fields the middleware did not report.
    unobserved: tuple[str, ...]
    #: The type hash (``RIHS01_...``), '' when not reported.
    type_hash: str
    #: The endpoint's GID, as hex.
    gid: str

    @property
    def qos_dict(self) -> dict[str, Any]:
        """The reported QoS as a NoDL mapping."""
        return dict(self.qos)


@dataclass
class Snapshot:
    """One full scan of the graph."""

    #: When it was taken (``time.monotonic()``).
    time: float
    #: How many nodes of each fully qualified name the graph holds (the monitor's own and
    #: the toolkit's observers left out).
    counts: dict[str, int] = field(default_factory=dict)
    #: The raw endpoints of the nodes asked for (by name: ``(name, [types])`` per section).
    endpoints: dict[str, dict[str, list[tuple[str, list[str]]]]] = field(default_factory=dict)
    #: Every topic's publishers and subscriptions, by topic.
    topics: dict[str, list[LiveTopicEndpoint]] = field(default_factory=dict)
    #: Seconds the scan took.
    cost: float = 0.0
    _by_node: dict[str, tuple[LiveTopicEndpoint, ...]] | None = field(default=None, repr=False,
                                                                   compare=False)

    def of_node(self, fqn: str) -> tuple[LiveTopicEndpoint, ...]:
        """The topic endpoints of node ``fqn`` (indexed on first use)."""
        if self._by_node is None:
            index: dict[str, list[LiveTopicEndpoint]] = {}
            for infos in self.topics.values():
                for info in infos:
                    index.setdefault(info.node, []).append(info)
            self._by_node = {k: tuple(v) for k, v in index.items()}
        return self._by_node.get(fqn, ())

    def endpoint_count(self) -> int:
        """How many endpoints the scan read (topic endpoints and node endpoints)."""
        return (sum(len(v) for v in self.topics.values())
                + sum(len(e) for raw in self.endpoints.values() for e in raw.values()))


def _hash_text(value: Any) -> str:
    if value is None:
        return ''
    version = getattr(value, 'version', None)
    digest = getattr(value, 'value', None)
    if isinstance(digest, (bytes, bytearray)) and version:
        if not any(digest):
            return ''
        return f'RIHS{int(version):02d}_{bytes(digest).hex()}'
    text = str(value)
    return '' if not text or 'version=0' in text else text


class GraphView:
    """The graph as one rclpy ``node`` sees it, less the toolkit's own nodes (the monitor
    itself: see :func:`~nodl.live.session.is_toolkit_node`)."""

    def __init__(self, node: Any) -> None:
        self.node = node
        #: The endpoints converted by the last scan, by (topic, kind, GID, namespace, name).
        self._known: dict[tuple[str, str, bytes, str, str], LiveTopicEndpoint | None] = {}

    def scan(self, counts: Mapping[str, int], wanted: Iterable[str],
             everyone: bool = False, meanwhile: Callable[[], None] | None = None) -> Snapshot:
        """A full scan of the nodes ``counts`` holds (how many of each name: the graph
        follower's, :attr:`~nodl.live.graph_events.GraphFollower.counts`): the endpoints
        of the ``wanted`` nodes present (with ``everyone``: of every node present), every
        topic's endpoint infos.  ``meanwhile`` is called every :data:`SCAN_CHUNK` topics
        (what must not wait for a long scan: a periodic publication); the processor time
        it takes is not the scan's :attr:`~Snapshot.cost`."""
        start = time.monotonic()
        process = time.process_time()
        node = self.node
        snapshot = Snapshot(start, dict(counts))
        for fqn in sorted(snapshot.counts) if everyone else wanted:
            if snapshot.counts.get(fqn, 0) < 1:
                continue
            namespace, name = split_node_name(fqn)
            try:
                snapshot.endpoints[fqn] = {
                    'publishers': node.get_publisher_names_and_types_by_node(name, namespace),
                    'subscriptions': node.get_subscriber_names_and_types_by_node(name, namespace),
                    'service_servers': node.get_service_names_and_types_by_node(name, namespace),
                    'service_clients': node.get_client_names_and_types_by_node(name, namespace)}
            except Exception:  # noqa: BLE001 - it vanished between two calls: next scan
                continue
        known = self._known
        seen: dict[tuple[str, str, bytes, str, str], LiveTopicEndpoint | None] = {}
        publishers, subscriptions = self._info_functions()
        for index, (topic, _) in enumerate(node.get_topic_names_and_types()):
            if meanwhile is not None and index % SCAN_CHUNK == SCAN_CHUNK - 1:
                paused = time.process_time()
                meanwhile()
                process += time.process_time() - paused
            found: list[LiveTopicEndpoint] = []
            for kind, infos in (('publisher', publishers(topic)),
                                ('subscription', subscriptions(topic))):
                for info in infos:
                    # the node's name too: an endpoint discovered before its node's
                    # announcement is reported under an unknown node, then under its own
                    key = (topic, kind, bytes(info['endpoint_gid']), info['node_namespace'],
                           info['node_name'])
                    endpoint = known[key] if key in known else self._endpoint(topic, kind, info)
                    seen[key] = endpoint
                    if endpoint is not None:
                        found.append(endpoint)
            if found:
                snapshot.topics[topic] = found
        self._known = seen
        snapshot.cost = time.process_time() - process
        return snapshot

    def _info_functions(self) -> tuple[Callable[[str], list[dict[str, Any]]],
                                       Callable[[str], list[dict[str, Any]]]]:
        """The publishers' and subscriptions' infos of a topic (its full name, unmapped), as
        rcl reports them: a mapping per endpoint.  rclpy's own methods wrap each in a
        ``TopicEndpointInfo`` (with a ``QoSProfile``), which costs more than the call
        itself; a scan wraps only the endpoints it has not seen before.  Through rclpy's
        methods when its extension does not have the calls."""
        node = self.node
        try:
            from rclpy.impl.implementation_singleton import rclpy_implementation as impl

            raw_publishers = impl.rclpy_get_publishers_info_by_topic
            raw_subscriptions = impl.rclpy_get_subscriptions_info_by_topic
        except (ImportError, AttributeError):
            def wrapped(method: Callable[..., list[Any]]) -> Callable[[str], list[dict[str, Any]]]:
                return lambda topic: [_info_dict(i) for i in method(topic)]

            return (wrapped(node.get_publishers_info_by_topic),
                    wrapped(node.get_subscriptions_info_by_topic))

        def publishers(topic: str) -> list[dict[str, Any]]:
            with node.handle:
                return [dict(i) for i in raw_publishers(node.handle, topic, False)]

        def subscriptions(topic: str) -> list[dict[str, Any]]:
            with node.handle:
                return [dict(i) for i in raw_subscriptions(node.handle, topic, False)]

        return publishers, subscriptions

    def _endpoint(self, topic: str, kind: str, raw: dict[str, Any]) -> LiveTopicEndpoint | None:
        """One endpoint info as a :class:`LiveTopicEndpoint` (None for the toolkit's own)."""
        from rclpy.topic_endpoint_info import TopicEndpointInfo

        owner = join_name(raw['node_namespace'], raw['node_name'])
        if is_toolkit_node(owner):
            return None
        info = TopicEndpointInfo(**raw)
        qos, unobserved = qos_from_rclpy(info.qos_profile)
        return LiveTopicEndpoint(topic, owner, kind, info.topic_type, tuple(sorted(qos.items())),
                                 tuple(unobserved), _hash_text(getattr(info, 'topic_type_hash', None)),
                                 bytes(info.endpoint_gid).hex())


def discovered(snapshot: Snapshot) -> bool:
    """Whether every publisher and subscription the scanned nodes announce (their
    endpoint names, from the nodes' announcements) is also known with its QoS (the topic
    infos, from DDS discovery, which comes later)."""
    for fqn, raw in snapshot.endpoints.items():
        known = {(e.kind, e.topic) for e in snapshot.of_node(fqn)}
        for kind, section in (('publisher', 'publishers'), ('subscription', 'subscriptions')):
            if any((kind, name) not in known for name, _ in raw.get(section, [])):
                return False
    return True


def _info_dict(info: Any) -> dict[str, Any]:
    """A ``TopicEndpointInfo`` back as the mapping rcl gives (the fallback of
    :meth:`GraphView._info_functions`)."""
    return {'node_name': info.node_name, 'node_namespace': info.node_namespace,
            'topic_type': info.topic_type, 'topic_type_hash': info.topic_type_hash,
            'endpoint_type': info.endpoint_type, 'endpoint_gid': info.endpoint_gid,
            'qos_profile': info.qos_profile}


def observed_node(fqn: str, snapshot: Snapshot) -> ObservedNode | None:
    """What the snapshot says of node ``fqn`` as an :class:`~nodl.live.observe.ObservedNode`
    (topic QoS from the topic infos, actions folded from their hidden topics and services),
    or None if it was not scanned.  Parameters are not set."""
    raw = snapshot.endpoints.get(fqn)
    if raw is None:
        return None
    namespace, name = split_node_name(fqn)
    observed = ObservedNode(name, namespace)
    qos: dict[tuple[str, str], LiveTopicEndpoint] = {}
    for info in snapshot.of_node(fqn):
        qos.setdefault((info.kind, info.topic), info)
    for section in _SECTIONS:
        entries = []
        for entity_name, types in sorted(raw.get(section, [])):
            endpoint = ObservedEndpoint(entity_name, types[0] if types else '')
            if section in ('publishers', 'subscriptions'):
                found = qos.get((section[:-1], entity_name))
                if found is None:
                    endpoint.unobserved = ['qos']
                else:
                    endpoint.qos, endpoint.unobserved = found.qos_dict, list(found.unobserved)
            entries.append(endpoint)
        setattr(observed, section, entries)
    _fold_actions(observed)
    return observed


def _action_type(service_type: str, suffix: str) -> str:
    return service_type[:-len(suffix)] if service_type.endswith(suffix) else service_type


def _fold_actions(observed: ObservedNode) -> None:
    """Action servers (``<a>/_action/send_goal`` served) and clients (called), and their
    hidden topics and services left out of the plain sections."""
    servers = {e.name.partition(ACTION_INFIX)[0]: _action_type(e.type, '_SendGoal')
               for e in observed.service_servers if e.name.endswith(ACTION_INFIX + 'send_goal')}
    clients = {e.name.partition(ACTION_INFIX)[0]: _action_type(e.type, '_SendGoal')
               for e in observed.service_clients if e.name.endswith(ACTION_INFIX + 'send_goal')}
    observed.action_servers = [ObservedEndpoint(n, t) for n, t in sorted(servers.items())]
    observed.action_clients = [ObservedEndpoint(n, t) for n, t in sorted(clients.items())]
    actions = set(servers) | set(clients)
    for section in _SECTIONS:
        setattr(observed, section, [e for e in getattr(observed, section)
                                    if e.name.partition(ACTION_INFIX)[0] not in actions
                                    or ACTION_INFIX not in e.name])
