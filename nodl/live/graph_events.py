"""Following the local graph cache: the one primitive every live wait is made of.

rclpy exposes no graph guard condition, so the graph is followed by reading the local
graph cache (what the session's participant has discovered; reading it sends nothing)
between short spins of the session's executor, every :data:`POLL_PERIOD` seconds: a
change is seen within that period plus one spin (under 100 ms).  Every wait has a
deadline.

A session (:func:`~nodl.live.session.ros_session`, or ``nodl monitor``'s node, see
:func:`~nodl.live.session.open_session`) carries one :class:`GraphFollower`; every wait of
the live layer spins through it (:func:`spin_once`), so what it knows of the graph (how
many nodes hold each name) stays current while parameters and lifecycle states are read.
Namesakes are therefore watched for as long as the work lasts, and
:attr:`GraphFollower.watched` says how long that was.

A long-running loop that must not wake up at every poll (an executor rebuilds its wait set
of every entity at every wake-up: ``nodl monitor``'s steady-state budget) has the follower
poll in a thread of its own instead (:meth:`GraphFollower.watch`), told of each poll, and
takes the changes it found (:meth:`GraphFollower.take_changes`).  Such a follower may read
the topic names only every few polls, and the service names not at all
(``topics_every``, ``services``): with 50 nodes, 300 service names are three quarters of a
poll's cost.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from nodl.naming import join_name

__all__ = ['POLL_PERIOD', 'ANSWERS', 'GraphFollower', 'follower', 'graph_signature', 'spin_once']

#: Seconds between two reads of the local graph cache while waiting.
POLL_PERIOD = 0.05
#: Seconds after a session starts by which the participants that answer its first
#: announcements are usually discovered (measured on one machine with Fast DDS: within
#: 0.03-0.3 s).  One that misses them is discovered only at its own next periodic
#: announcement (Fast DDS: every 3 s), which is what a longer watch waits for.
ANSWERS = 0.3


def _node_names(node: Any) -> list[tuple[str, str]]:
    return sorted(node.get_node_names_and_namespaces())


def graph_signature(node: Any, nodes: Iterable[str] = (), *, topics: bool = True,
                    services: bool = True) -> tuple[Any, ...]:
    """A value that changes when the local graph cache does: node names (each as often as
    the graph holds it), topic and service names and types (None for those not read:
    ``topics``, ``services``), and the endpoints of each of ``nodes`` (fully qualified
    names) that is present."""
    from nodl.live.session import split_node_name

    names = _node_names(node)
    wanted = set(nodes)
    present = {join_name(ns, n) for n, ns in names} if wanted else set()
    endpoints: list[tuple[str, Any]] = []
    for fqn in sorted(wanted & present):
        namespace, name = split_node_name(fqn)
        try:
            endpoints.append((fqn, tuple(
                (section, tuple((n, tuple(t)) for n, t in sorted(read(name, namespace))))
                for section, read in (
                    ('publishers', node.get_publisher_names_and_types_by_node),
                    ('subscriptions', node.get_subscriber_names_and_types_by_node),
                    ('service_servers', node.get_service_names_and_types_by_node),
                    ('service_clients', node.get_client_names_and_types_by_node)))))
        except Exception:  # noqa: BLE001 - it vanished between two calls: the next poll sees it
            endpoints.append((fqn, None))
    # the names and types as rclpy lists them (compared, never changed: not copied)
    return (tuple(names),
            node.get_topic_names_and_types() if topics else None,
            node.get_service_names_and_types() if services else None,
            tuple(endpoints))


class GraphFollower:
    """The graph as one session's observer ``node`` follows it.

    :meth:`poll` reads the local graph cache (at most every ``period`` seconds) and notes
    when it last changed; :meth:`spin_once` spins the session's executor briefly, then
    polls; :meth:`changes` and :meth:`settle` wait on those changes until a deadline.
    ``started`` is when the session's discovery started (its participant's creation).
    ``topics_every``: the topic names are read every that many polls (the first poll
    included); ``services``: whether the service names are read (without, a service
    added to a node is seen only through the node's followed endpoints).  :meth:`watch`
    polls in a thread of its own instead of between spins.
    """

    def __init__(self, node: Any, *, started: float | None = None,
                 period: float = POLL_PERIOD, topics_every: int = 1,
                 services: bool = True) -> None:
        self.node = node
        self.period = period
        self.topics_every = max(1, topics_every)
        self.services = services
        self._started = time.monotonic() if started is None else started
        self._polls = 0
        # a watching thread and the session's own thread may both poll
        self._lock = threading.RLock()
        self._halt = threading.Event()
        self._watcher: threading.Thread | None = None
        #: When polls found a change, oldest first, until taken (:meth:`take_changes`).
        self._change_times: deque[float] = deque(maxlen=1024)
        #: The nodes whose endpoints are part of the signature (see :meth:`follow`).
        self.followed: set[str] = set()
        self.signature: Any = None
        #: When the signature last changed, and when it was last read.
        self.changed_at = self.started
        self.polled_at = float('-inf')
        #: When each part last changed: ``nodes`` (the node names), ``topics``, ``services``
        #: and each followed node's endpoints (by its fully qualified name).
        self.part_changed_at: dict[str, float] = {}
        self._parts: dict[str, Any] = {}
        #: How many nodes of each fully qualified name the graph held at the last poll
        #: (the toolkit's own observers left out).
        self.counts: dict[str, int] = {}
        #: How many polls found a change (a test's and a curious user's figure).
        self.changes_seen = 0

    @property
    def started(self) -> float:
        """When discovery started (``time.monotonic()``): the session's ``nodl_started``
        when it has one (see :func:`~nodl.live.session.ros_session`)."""
        return float(getattr(self.node, 'nodl_started', self._started))

    # -- reading ---------------------------------------------------------------------------

    def follow(self, fqns: Iterable[str]) -> None:
        """Make the endpoints of ``fqns`` part of what a change is."""
        new = set(fqns) - self.followed
        if new:
            self.followed |= new
            self.poll(force=True)

    def poll(self, *, force: bool = False) -> bool:
        """Read the local graph cache unless it was read less than ``period`` seconds ago
        (``force``: read it anyway); True if it changed since the last read."""
        with self._lock:
            now = time.monotonic()
            if not force and now - self.polled_at < self.period:
                return False
            return self._poll()

    def _poll(self) -> bool:
        from nodl.live.session import count_node_names

        topics = self._polls % self.topics_every == 0
        self._polls += 1
        signature = graph_signature(self.node, self.followed, topics=topics,
                                    services=self.services)
        self.polled_at = time.monotonic()
        if not topics and self.signature is not None:  # not read this time: as they were
            signature = (signature[0], self.signature[1], *signature[2:])
        if signature == self.signature and self.followed.issubset(self._parts):
            return False  # nothing changed: no part either
        if signature[0] != self._parts.get('nodes'):
            self.counts = count_node_names(signature[0])
        parts = {'nodes': signature[0], 'topics': signature[1], 'services': signature[2],
                 **dict(signature[3])}
        for key in self.followed:
            parts.setdefault(key, None)  # followed, not in the graph
        for key, value in parts.items():
            if key not in self._parts or self._parts[key] != value:
                # a part seen empty from the first poll on has been quiet since the start
                self.part_changed_at[key] = (self.polled_at if value or key in self._parts
                                             else self.started)
        self._parts = parts
        if signature == self.signature:
            return False
        first = self.signature is None
        self.signature = signature
        if not first or signature[0]:
            self.changed_at = self.polled_at
            self.changes_seen += 1
            self._change_times.append(self.polled_at)
        return True

    def take_changes(self) -> list[float]:
        """When polls found the graph changed since the last call (``time.monotonic()``,
        oldest first): for a loop that follows the graph through :meth:`watch`."""
        taken = []
        while self._change_times:
            taken.append(self._change_times.popleft())
        return taken

    def part(self, key: str) -> Any:
        """One part of the last poll's signature (see :attr:`part_changed_at`): the node
        names, or a followed node's endpoints as ``((section, ((name, types)...))...)``
        (None while it is not in the graph)."""
        return self._parts.get(key)

    def quiet_on(self, keys: Iterable[str] | None = None) -> float:
        """Seconds since any of the parts ``keys`` (by default, anything) last changed."""
        if self.signature is None:
            return 0.0
        if keys is None:
            return self.polled_at - self.changed_at
        times = [self.part_changed_at.get(k, self.polled_at) for k in keys]
        return self.polled_at - max(times, default=self.started)

    @property
    def quiet(self) -> float:
        """Seconds since the graph last changed (as of the last poll)."""
        return self.polled_at - self.changed_at if self.signature is not None else 0.0

    @property
    def watched(self) -> float:
        """Seconds of discovery the last poll covers (from the session's start)."""
        return max(0.0, self.polled_at - self.started)

    # -- a thread of its own ----------------------------------------------------------------

    def watch(self, on_poll: Callable[[bool], None]) -> None:
        """Poll every ``period`` seconds in a thread of its own, calling ``on_poll(changed)``
        (in that thread) after each poll, until :meth:`unwatch`: for a loop that sleeps in
        its executor until something happens (``on_poll`` triggers a guard condition of it
        when the graph changed) and takes the changes (:meth:`take_changes`).  The thread
        ends by itself if reading the graph fails (the context shutting down)."""
        if self._watcher is not None:
            raise RuntimeError('the graph is already watched')
        self._halt.clear()
        self._watcher = threading.Thread(target=self._watch, args=(on_poll,),
                                         name='nodl-graph-follower', daemon=True)
        self._watcher.start()

    def _watch(self, on_poll: Callable[[bool], None]) -> None:
        while True:
            try:
                changed = self.poll(force=True)
            except Exception:  # noqa: BLE001 - the context is shutting down: stop polling
                return
            on_poll(changed)
            if self._halt.wait(self.period):
                return

    def unwatch(self) -> None:
        """Stop the thread of :meth:`watch` (waits for it, up to a poll's time and a second)."""
        watcher, self._watcher = self._watcher, None
        if watcher is not None:
            self._halt.set()
            watcher.join(timeout=2 * self.period + 1.0)

    # -- waiting ---------------------------------------------------------------------------

    def spin_once(self, timeout: float) -> None:
        """Spin the session's executor for up to ``timeout`` seconds (one callback, or
        none), then poll the graph if its period has passed."""
        remaining = self.polled_at + self.period - time.monotonic()
        self.node.nodl_executor.spin_once(
            timeout_sec=max(0.0, min(timeout, remaining if remaining > 0 else self.period)))
        self.poll()

    def changes(self, deadline: float) -> Iterator[float]:
        """Yield ``time.monotonic()`` now (the graph as it is), then each time the graph
        changes, until ``deadline``.  The caller may stop at any point."""
        self.poll(force=True)
        yield time.monotonic()
        seen = self.changes_seen
        while time.monotonic() < deadline:
            self.spin_once(deadline - time.monotonic())
            if self.changes_seen != seen:
                seen = self.changes_seen
                yield time.monotonic()

    def wait(self, until: Callable[[], bool], deadline: float) -> bool:
        """Spin until ``until()`` (asked after each poll) is true or ``deadline`` passes;
        whether it came true."""
        self.poll(force=True)
        while True:
            if until():
                return True
            now = time.monotonic()
            if now >= deadline:
                return False
            self.spin_once(deadline - now)

    def settle(self, quiet: float | Callable[[], float], deadline: float, *,
               on: Iterable[str] | None = None, ready: Callable[[], bool] = lambda: True,
               watched: float = 0.0) -> bool:
        """Spin until what is waited for (the parts ``on``, see :attr:`part_changed_at`;
        by default the whole graph) has not changed for ``quiet`` seconds (a number, or
        a function asked after each poll), ``ready()`` holds and discovery has run for
        ``watched`` seconds, or until ``deadline``.  True if settled, False at the
        deadline (the graph is then taken as it is)."""
        keys = None if on is None else list(on)

        def settled() -> bool:
            needed = quiet() if callable(quiet) else quiet
            return self.quiet_on(keys) >= needed and self.watched >= watched and ready()

        return self.wait(settled, deadline)

    def watch_until(self, watched: float, deadline: float) -> None:
        """Keep following the graph until discovery has run ``watched`` seconds (not past
        ``deadline``): namesakes found late are counted."""
        self.wait(lambda: self.watched >= watched, min(deadline, self.started + watched))
        self.poll(force=True)


def follower(node: Any) -> GraphFollower:
    """The :class:`GraphFollower` of a session's observer ``node`` (made on first use)."""
    existing = getattr(node, 'nodl_graph', None)
    if isinstance(existing, GraphFollower):
        return existing
    made = GraphFollower(node)
    node.nodl_graph = made
    return made


def spin_once(node: Any, timeout: float) -> None:
    """Spin a session for up to ``timeout`` seconds, following its graph (see
    :meth:`GraphFollower.spin_once`)."""
    follower(node).spin_once(timeout)
