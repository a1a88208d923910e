"""Observing a running node: its endpoints (with QoS), actions and parameters.

Everything comes from the real ROS graph through rclpy.  Action servers and
clients are folded from their hidden ``<action>/_action/*`` topics and
services, which are then not listed as plain topics or services.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from nodl.live.graph_events import ANSWERS, follower, spin_once
from nodl.live.qos import qos_from_rclpy
from nodl.live.session import (
    LiveError,
    NodeNotFound,
    count_node_names,
    ros_session,
    split_node_name,
    without_toolkit_nodes,
)
from nodl.naming import join_name
from nodl.vocabulary import PARAMETER_TYPE_BY_NUMBER, SERVICE_SECTIONS, TOPIC_SECTIONS
from nodl.wording import did_you_mean

__all__ = ['ObservedEndpoint', 'ObservedParameter', 'ObservedNode', 'observe_node',
           'wait_for_node', 'list_nodes', 'count_nodes', 'ACTION_INFIX', 'DISCOVERY_WINDOW',
           'settle_nodes', 'observe_settled', 'read_parameters', 'read_lifecycle_states',
           'NAMESAKE_WATCH', 'namesake_warning', 'watched_line', 'recount', 'ParameterRead']

ACTION_INFIX = '/_action/'
#: How long a session must have been discovering before the graph is taken as complete.
#: Remote participants are discovered one by one: one that misses our first announcements
#: is seen only at its own next periodic announcement (Fast DDS: every 3 s), so a second
#: node of the same name can show up seconds after the first.  The library's observations
#: watch for namesakes that long by default (the work overlapping the watch).
DISCOVERY_WINDOW = 3.5
#: How long ``nodl describe`` watches for namesakes by default: as long as its work takes,
#: and at least until the answers to the session's first announcements are in
#: (:data:`~nodl.live.graph_events.ANSWERS`); what it watched is said in its output.
NAMESAKE_WATCH = ANSWERS
_PARAMETER_TYPES = PARAMETER_TYPE_BY_NUMBER


@dataclass
class ObservedEndpoint:
    """A topic, service or action endpoint as the graph reports it."""

    name: str
    type: str
    #: NoDL QoS fields the middleware reported (topics only).
    qos: dict[str, Any] | None = None
    #: QoS fields the middleware could not report.
    unobserved: list[str] = field(default_factory=list)


@dataclass
class ObservedParameter:
    """A parameter as the node's parameter services report it."""

    name: str
    type: str
    value: Any
    description: str = ''
    read_only: bool = False
    #: ``(from, to)`` of an integer or floating point range, else None.
    range: tuple[float, float] | None = None


@dataclass
class ObservedNode:
    """Everything observed about one node."""

    name: str
    namespace: str
    publishers: list[ObservedEndpoint] = field(default_factory=list)
    subscriptions: list[ObservedEndpoint] = field(default_factory=list)
    service_servers: list[ObservedEndpoint] = field(default_factory=list)
    service_clients: list[ObservedEndpoint] = field(default_factory=list)
    action_servers: list[ObservedEndpoint] = field(default_factory=list)
    action_clients: list[ObservedEndpoint] = field(default_factory=list)
    #: None when parameters were not asked for (or the node serves none).
    parameters: dict[str, ObservedParameter] | None = None
    #: Things that could not be observed, in words.
    notes: list[str] = field(default_factory=list)
    #: What makes the observation itself doubtful, in words (several nodes share the name).
    warnings: list[str] = field(default_factory=list)
    #: How many nodes in the graph have this name (more than one: what is observed is all of them).
    instances: int = 1
    #: The lifecycle state it was observed in (``unconfigured``, ``inactive``...), for a
    #: lifecycle node whose state was asked (:func:`read_lifecycle_states`); else None.
    lifecycle_state: str | None = None
    #: Seconds of discovery (from the session's start) after which :attr:`instances` was
    #: counted: a namesake discovered later is not counted.  None when not counted.
    watched: float | None = None

    @property
    def fully_qualified_name(self) -> str:
        """``/namespace/name``."""
        return join_name(self.namespace, self.name)


def list_nodes(node: Any) -> list[str]:
    """Fully qualified names of the nodes in the graph, less the toolkit's own observers.

    Hidden nodes (``_name``) other than the toolkit's are listed: each verb says
    what it does with them.
    """
    return sorted(count_nodes(node))


def count_nodes(node: Any) -> dict[str, int]:
    """How many nodes in the graph have each fully qualified name (less the toolkit's own).

    A name held more than once is a name several nodes share (usually in
    several processes): the graph cannot tell their endpoints apart.
    """
    return count_node_names(node.get_node_names_and_namespaces())


def wait_for_node(node: Any, fqn: str, timeout: float) -> None:
    """Wait until ``fqn`` is in the graph, or raise NodeNotFound (naming the closest nodes seen)."""
    graph = follower(node)
    if graph.wait(lambda: fqn in graph.counts, time.monotonic() + timeout):
        return
    hint = did_you_mean(fqn, list_nodes(node), most=3, aside=True)
    raise NodeNotFound(f"node '{fqn}' was not found within {timeout:g} s{hint} (is it "
                       'running, in the same ROS_DOMAIN_ID, with discovery reaching it?)')


def _endpoints(node: Any, name: str, namespace: str) -> dict[str, list[tuple[str, list[str]]]]:
    return {
        'publishers': node.get_publisher_names_and_types_by_node(name, namespace),
        'subscriptions': node.get_subscriber_names_and_types_by_node(name, namespace),
        'service_servers': node.get_service_names_and_types_by_node(name, namespace),
        'service_clients': node.get_client_names_and_types_by_node(name, namespace),
    }


#: How long the endpoints must stay unchanged when only writers or only readers are seen.
LOPSIDED_QUIET = 1.5


def _lopsided(raw: dict[str, list[tuple[str, list[str]]]]) -> bool:
    """Writers (publishers) but no readers (subscriptions, services), or the reverse.

    DDS discovers a participant's writers and readers through two separate
    streams, and one can arrive well after the other (seen on Fast DDS under
    load: every subscription and service missing for longer than ``quiet``).
    A default node has both (/rosout, the parameter services), so a lopsided
    view is given more time to fill in.
    """
    readers = raw['subscriptions'] or raw['service_servers'] or raw['service_clients']
    return bool(raw['publishers']) != bool(readers)


def _settle(node: Any, name: str, namespace: str, fqn: str, timeout: float,
            quiet: float, meanwhile: Callable[[], Any] | None = None
            ) -> dict[str, list[tuple[str, list[str]]]]:
    """Follow the graph until the node's endpoints (and the rest of the graph) have not
    changed for ``quiet`` seconds (``LOPSIDED_QUIET`` seconds if only writers or only
    readers are seen), or ``timeout`` seconds pass; then read them.  ``meanwhile`` is
    called after every poll (other work going on while the endpoints settle)."""
    graph = follower(node)
    graph.follow([fqn])

    def needed() -> float:
        if meanwhile is not None:
            meanwhile()
        raw = _followed(graph, fqn)
        return max(quiet, LOPSIDED_QUIET) if raw is not None and _lopsided(raw) else quiet

    # at the deadline, a node whose endpoints keep changing is taken as it is then
    graph.settle(needed, time.monotonic() + timeout, on=[fqn])
    try:
        return _endpoints(node, name, namespace)
    except Exception as exc:  # the node vanished between two calls
        if fqn not in list_nodes(node):
            raise LiveError(f"node '{fqn}' disappeared while it was being observed") from None
        raise LiveError(f"cannot read the endpoints of '{fqn}': {exc}") from None


def _followed(graph: Any, fqn: str) -> RawEndpoints | None:
    """The endpoints of a followed node as the follower's last poll read them."""
    sections = graph.part(fqn)
    if sections is None:
        return None
    return {section: [(n, list(t)) for n, t in entries] for section, entries in sections}


def _topic_qos(node: Any, topic: str, name: str, namespace: str, publishers: bool) -> Any:
    infos = (node.get_publishers_info_by_topic(topic) if publishers
             else node.get_subscriptions_info_by_topic(topic))
    for info in without_toolkit_nodes(infos):
        if info.node_name == name and info.node_namespace == namespace:
            return info.qos_profile
    return None


def _fold_actions(observed: ObservedNode, node: Any, name: str, namespace: str) -> None:
    from rclpy.action import graph

    servers = graph.get_action_server_names_and_types_by_node(node, name, namespace)
    clients = graph.get_action_client_names_and_types_by_node(node, name, namespace)
    observed.action_servers = [ObservedEndpoint(n, t[0]) for n, t in sorted(servers)]
    observed.action_clients = [ObservedEndpoint(n, t[0]) for n, t in sorted(clients)]
    action_names = {e.name for e in observed.action_servers + observed.action_clients}

    def hidden(endpoint: ObservedEndpoint) -> bool:
        prefix, infix, _ = endpoint.name.partition(ACTION_INFIX)
        return bool(infix) and prefix in action_names

    for section in TOPIC_SECTIONS + SERVICE_SECTIONS:
        setattr(observed, section, [e for e in getattr(observed, section) if not hidden(e)])


def _value(value: Any) -> Any:
    kind = value.type
    if kind == 1:
        return bool(value.bool_value)
    if kind == 2:
        return int(value.integer_value)
    if kind == 3:
        return float(value.double_value)
    if kind == 4:
        return str(value.string_value)
    if kind == 5:
        return [b[0] if isinstance(b, (bytes, bytearray)) else int(b) for b in value.byte_array_value]
    if kind == 6:
        return [bool(v) for v in value.bool_array_value]
    if kind == 7:
        return [int(v) for v in value.integer_array_value]
    if kind == 8:
        return [float(v) for v in value.double_array_value]
    if kind == 9:
        return [str(v) for v in value.string_array_value]
    return None


def _parameter_table(names: list[str], values: Any, descriptors: Any
                     ) -> dict[str, ObservedParameter]:
    """The parameters of one node from its get_parameters and describe_parameters answers."""
    found: dict[str, ObservedParameter] = {}
    for name, value, descriptor in zip(names, values.values, descriptors.descriptors, strict=False):
        rng: tuple[float, float] | None = None
        if descriptor.integer_range:
            r = descriptor.integer_range[0]
            rng = (int(r.from_value), int(r.to_value))
        elif descriptor.floating_point_range:
            r = descriptor.floating_point_range[0]
            rng = (float(r.from_value), float(r.to_value))
        found[name] = ObservedParameter(
            name, _PARAMETER_TYPES.get(value.type, 'none'), _value(value),
            descriptor.description, bool(descriptor.read_only), rng)
    return found


class ParameterRead:
    """One node's parameters read step by step while something else is waited for:
    ``list_parameters``, then ``get_parameters`` and ``describe_parameters`` together, each
    sent as soon as its server is discovered; :meth:`step` after each spin (of the executor
    that spins ``node``), :meth:`result` once it is done, :meth:`close` always.  Used by
    :func:`observe_node` and by ``nodl monitor`` (its initial reads)."""

    def __init__(self, node: Any, fqn: str, deadline: float) -> None:
        from rcl_interfaces.srv import DescribeParameters, GetParameters, ListParameters

        self.node = node
        self.deadline = deadline
        self.kinds = (ListParameters, GetParameters, DescribeParameters)
        self.clients = [node.create_client(kind, f'{fqn}/{service}') for kind, service in
                        zip(self.kinds, ('list_parameters', 'get_parameters',
                                         'describe_parameters'), strict=True)]
        self.futures: list[Any] = [None, None, None]
        self.names: list[str] | None = None

    def step(self) -> bool:
        """Send what can be sent; True once every answer is in, or past the deadline."""
        futures, clients = self.futures, self.clients
        if futures[0] is None and clients[0].service_is_ready():
            futures[0] = clients[0].call_async(self.kinds[0].Request())
        if self.names is None and futures[0] is not None and futures[0].done():
            listed = futures[0].result()
            self.names = sorted(listed.result.names) if listed is not None else []
        if self.names is not None:
            for i in (1, 2):
                if futures[i] is None and clients[i].service_is_ready():
                    futures[i] = clients[i].call_async(self.kinds[i].Request(names=self.names))
        done = all(f is not None and f.done() for f in futures)
        return done or time.monotonic() >= self.deadline

    def result(self) -> dict[str, ObservedParameter] | None:
        """The parameters read, or None if some answer is missing."""
        if self.names is None or not all(f is not None and f.done() for f in self.futures):
            return None
        values, descriptors = self.futures[1].result(), self.futures[2].result()
        if values is None or descriptors is None:
            return None
        return _parameter_table(self.names, values, descriptors)

    def close(self) -> None:
        """Destroy the clients."""
        for client in self.clients:
            self.node.destroy_client(client)


def observe_node(fqn: str, *, timeout: float = 5.0, parameters: bool = True,
                 quiet: float = 0.15, session: Any = None,
                 watch: float = DISCOVERY_WINDOW) -> ObservedNode:
    """Observe the running node ``fqn`` (``/namespace/name``).

    Waits up to ``timeout`` seconds for the node to appear and its endpoints
    to settle (no change for ``quiet`` seconds), following the graph's changes
    (:mod:`~nodl.live.graph_events`).  The nodes that share its name
    (:attr:`ObservedNode.instances`, a warning) are watched for while the
    endpoints settle and the parameters are read, and at least until the session
    has been discovering for ``watch`` seconds (or ``timeout`` seconds have
    passed): a namesake is often discovered seconds after the first node of that
    name.  :attr:`ObservedNode.watched` says how long that was.  Raises
    :class:`LiveError` (:class:`NodeNotFound` if it never appears) with a message
    for the user.  ``session`` is an observer node from :func:`ros_session` to
    reuse (its discovery is then already under way, and counts from its start);
    by default a session of its own.
    """
    if session is None:
        with ros_session() as node:
            return _observe(node, fqn, timeout, parameters, quiet, watch)
    return _observe(session, fqn, timeout, parameters, quiet, watch)


def _observe(node: Any, fqn: str, timeout: float, parameters: bool, quiet: float,
             watch: float = DISCOVERY_WINDOW) -> ObservedNode:
    namespace, name = split_node_name(fqn)
    fqn = join_name(namespace, name)
    start = time.monotonic()
    wait_for_node(node, fqn, timeout)
    remaining = max(0.5, timeout - (time.monotonic() - start))
    # the parameters are read while the endpoints settle (each call sent once its server
    # is discovered)
    reading = ParameterRead(node, fqn, start + max(1.0, timeout)) if parameters else None
    try:
        raw = _settle(node, name, namespace, fqn, remaining, quiet,
                      reading.step if reading is not None else None)
        observed = observe_settled(node, fqn, raw)
        if reading is not None:
            follower(node).wait(reading.step, reading.deadline)
            observed.parameters = reading.result()
            if observed.parameters is None:
                observed.notes.append(_NO_PARAMETERS)
    finally:
        if reading is not None:
            reading.close()
    # Namesakes were watched for while the work above went on; at least ``watch`` seconds of
    # discovery (the first node of a name seen says nothing about a second one whose
    # participant is not discovered yet).
    return recount(node, observed, watch, start + timeout)


def recount(node: Any, observed: ObservedNode, watch: float, deadline: float) -> ObservedNode:
    """Count the nodes named as ``observed`` once the session ``node`` has discovered for
    ``watch`` seconds (not past ``deadline``), following the graph until then: its
    :attr:`~ObservedNode.instances`, :attr:`~ObservedNode.watched` and namesake warning
    are set again.  For work done after :func:`observe_node` (``watch=0``) that namesakes
    should be watched during.  Raises :class:`LiveError` if the node is gone."""
    fqn = observed.fully_qualified_name
    graph = follower(node)
    graph.watch_until(watch, deadline)
    counts = graph.counts
    if fqn not in counts:
        raise LiveError(f"node '{fqn}' disappeared while it was being observed")
    old = namesake_warning(fqn, observed.instances)
    observed.warnings = [w for w in observed.warnings if w != old]
    observed.instances = counts[fqn]
    observed.watched = graph.watched
    warning = namesake_warning(fqn, observed.instances)
    if warning:
        observed.warnings.append(warning)
    return observed


def namesake_warning(fqn: str, instances: int) -> str | None:
    """The warning for a name ``instances`` nodes share (None for one node)."""
    if instances < 2:
        return None
    return (f'{instances} nodes in the graph are named {fqn}: what was observed is all of them '
            'together (give each node a unique name)')


def watched_line(watched: float | None, watch: float | None = None) -> str:
    """One line saying how long namesakes were watched for (``watched``: seconds of
    discovery) and what a longer watch would add."""
    if watched is None:
        return 'namesakes: not counted'
    text = f'namesakes watched for {watched:.1f} s of discovery'
    if watched < DISCOVERY_WINDOW:
        text += (' (a node of the same name whose participant is discovered later is not '
                 f'counted: --watch {DISCOVERY_WINDOW:g} waits for the 3 s periodic announcements)')
    return text


_NO_PARAMETERS = ('parameters could not be read (the node serves no parameter services, or they '
                  'did not answer in time)')

#: The raw endpoints of one node, by section (what the graph calls return).
RawEndpoints = dict[str, list[tuple[str, list[str]]]]


def settle_nodes(node: Any, expected: dict[str, int], timeout: float, quiet: float = 0.15
                 ) -> tuple[dict[str, RawEndpoints], dict[str, int]]:
    """Wait for several nodes at once: until each fully qualified name of ``expected`` is in
    the graph (at least as many times as given) and the endpoints of all of them have not
    changed for ``quiet`` seconds (``LOPSIDED_QUIET`` while one shows only writers or only
    readers), or until ``timeout`` seconds have passed.

    Returns the endpoints of every expected node seen (by name; one that never appeared
    has none) and how many nodes of each name the graph held at the end (the toolkit's
    own left out).  Waiting for them together costs one ``quiet`` period, not one each.
    """
    graph = follower(node)
    graph.follow(expected)

    def seen() -> dict[str, RawEndpoints]:
        raw = {}
        for fqn in expected:
            found = _followed(graph, fqn)
            if found is not None and graph.counts.get(fqn, 0) >= 1:
                raw[fqn] = found
        return raw

    def complete() -> bool:
        return all(graph.counts.get(fqn, 0) >= n for fqn, n in expected.items()) and all(
            any(r.values()) for r in seen().values())

    def needed() -> float:
        return max(quiet, LOPSIDED_QUIET) if any(_lopsided(r) for r in seen().values()) else quiet

    graph.settle(needed, time.monotonic() + timeout, on=['nodes', *expected], ready=complete)
    return seen(), dict(graph.counts)


def observe_settled(node: Any, fqn: str, raw: RawEndpoints) -> ObservedNode:
    """The :class:`ObservedNode` of ``fqn`` from endpoints already settled (``raw``, from
    :func:`settle_nodes`): each topic endpoint's QoS read, actions folded; no parameters."""
    namespace, name = split_node_name(fqn)
    observed = ObservedNode(name, namespace)
    for section, entries in raw.items():
        topic = section in TOPIC_SECTIONS
        endpoints = []
        for topic_name, types in sorted(entries):
            endpoint = ObservedEndpoint(topic_name, types[0] if types else '')
            if topic:
                profile = _topic_qos(node, topic_name, name, namespace, section == 'publishers')
                if profile is not None:
                    endpoint.qos, endpoint.unobserved = qos_from_rclpy(profile)
                else:
                    endpoint.unobserved = ['qos']
            endpoints.append(endpoint)
        setattr(observed, section, endpoints)
    _fold_actions(observed, node, name, namespace)
    return observed


def _call_many(node: Any, calls: list[tuple[Any, str, Any]], deadline: float) -> list[Any]:
    """Call several services at once (``(type, service name, request)`` each): every
    request is sent as soon as its server is discovered, and all are awaited together
    until ``deadline``.  The responses in order; None for a call without an answer."""
    clients = [node.create_client(kind, service) for kind, service, _ in calls]
    futures: list[Any] = [None] * len(calls)
    try:
        while time.monotonic() < deadline:
            for i, client in enumerate(clients):
                if futures[i] is None and client.service_is_ready():
                    futures[i] = client.call_async(calls[i][2])
            if all(f is not None and f.done() for f in futures):
                break
            spin_once(node, 0.01)  # the graph followed meanwhile (namesakes)
        return [f.result() if f is not None and f.done() else None for f in futures]
    finally:
        for client in clients:
            node.destroy_client(client)


def read_parameters(node: Any, fqns: list[str], timeout: float
                    ) -> dict[str, dict[str, ObservedParameter] | None]:
    """The parameters of several nodes, read at once (names, values and descriptors, as
    :func:`observe_node` reads one node's); None for a node that serves no parameter
    services or did not answer within ``timeout`` seconds."""
    from rcl_interfaces.srv import DescribeParameters, GetParameters, ListParameters

    deadline = time.monotonic() + timeout
    listed = _call_many(node, [(ListParameters, f'{fqn}/list_parameters', ListParameters.Request())
                               for fqn in fqns], deadline)
    names = {fqn: sorted(r.result.names) for fqn, r in zip(fqns, listed, strict=True) if r is not None}
    asked = [fqn for fqn in fqns if fqn in names]
    calls: list[tuple[Any, str, Any]] = []
    for fqn in asked:
        calls.append((GetParameters, f'{fqn}/get_parameters', GetParameters.Request(names=names[fqn])))
        calls.append((DescribeParameters, f'{fqn}/describe_parameters',
                      DescribeParameters.Request(names=names[fqn])))
    answers = _call_many(node, calls, max(deadline, time.monotonic() + 1.0)) if calls else []
    out: dict[str, dict[str, ObservedParameter] | None] = {fqn: None for fqn in fqns}
    for i, fqn in enumerate(asked):
        values, descriptors = answers[2 * i], answers[2 * i + 1]
        if values is not None and descriptors is not None:
            out[fqn] = _parameter_table(names[fqn], values, descriptors)
    return out


def read_lifecycle_states(node: Any, fqns: list[str], timeout: float) -> dict[str, str | None]:
    """The lifecycle state (``unconfigured``, ``inactive``, ``active``, ``finalized``) each
    lifecycle node of ``fqns`` reports through its ``~/get_state`` service, read at once;
    None for one that did not answer within ``timeout`` seconds."""
    from lifecycle_msgs.srv import GetState  # type: ignore[import-untyped]

    answers = _call_many(node, [(GetState, f'{fqn}/get_state', GetState.Request()) for fqn in fqns],
                         time.monotonic() + timeout)
    return {fqn: (str(a.current_state.label) or None) if a is not None else None
            for fqn, a in zip(fqns, answers, strict=True)}

