"""The monitor's rclpy node and its event loop.

The node (``_nodl_monitor``: hidden, and left out by the other live verbs) publishes
``diagnostic_msgs/DiagnosticArray`` on ``/diagnostics`` every ``1/publish_rate`` seconds,
and at once when a status changes level (or gains or loses a finding).  It subscribes to
``/parameter_events`` (every change checked as it arrives) and, best effort, to every
topic whose definition declares a deadline (its rate measured).  It follows the graph
through the live layer's :class:`~nodl.live.graph_events.GraphFollower`, as every live
verb does, scans it (:mod:`nodl.monitor.graph`) when it changed, and calls each node's
``~/get_parameters`` service
every ``liveness_period`` seconds (one node of a process in turn, all of them once one is
silent): a node that stops answering for ``liveness_timeout`` seconds is ERROR long
before its participant lease ends.  The rate subscriptions and liveness clients belong to
a second hidden node that nothing waits on (taken from at each tick); the follower polls
the graph in a thread of its own and wakes the loop only on a change.  Bad input is kept
up with or said in ``nodl: system``: a parameter event storm is coalesced (NODL441),
events lost are said and the parameters read again (NODL442), a graph that does not
settle is said (NODL443), scans spaced out for the budget are said (NODL439).

Its parameters: ``publish_rate`` (Hz, 1.0), ``grace_period`` (s, 5.0: how long an
expected node may take to appear), ``rate_window`` (s, 2.0) and ``rate_tolerance`` (0.2:
a rate below ``(1 - tolerance) / deadline`` is WARN), ``liveness_period`` (s, 1.0),
``liveness_timeout`` (s, 2.0), ``scan_period`` (s, 3.0: the full scan when nothing
changed), ``restart_window`` (s, 30.0: how long two nodes of one name are "restarting",
the old one's lease, before they are namesakes) and ``scan_budget`` (0.1: the share of
one core graph scans may take; beyond it scans are spaced out and the system status says
it is shedding).
"""

from __future__ import annotations

import fnmatch
import time
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from nodl.live.graph_events import GraphFollower
from nodl.live.observe import ObservedNode, ObservedParameter, ParameterRead
from nodl.live.session import MONITOR_NODE_NAME, LiveError, close_session, is_hidden_node, open_session, require_rclpy
from nodl.monitor.checks import (
    StatusFinding,
    connection_findings,
    endpoint_findings,
    parameter_event_findings,
    rate_finding,
)
from nodl.monitor.expected import DeadlineTopic, ExpectedNode, ExpectedSystem
from nodl.monitor.graph import GraphView, Snapshot, discovered, observed_node
from nodl.monitor.status import SYSTEM, Status, status_name, to_message
from nodl.vocabulary import PARAMETER_TYPE_BY_NUMBER

__all__ = ['MonitorSettings', 'Monitor', 'DEFAULT_IGNORED', 'POLL_PERIOD']

#: Nodes never reported as unexpected (besides hidden ones): launch_ros's own node and
#: tf2's transform listener nodes.
DEFAULT_IGNORED = ('launch_ros_*', 'transform_listener_impl_*')
#: How often the graph follower polls (10 Hz, in its thread): node names each time, topic
#: names every TOPIC_POLLS-th time, service names only with ``--once`` (see run).
POLL_PERIOD = 0.1
TOPIC_POLLS = 3
#: ``--once`` watches at least this long: a participant that missed the middleware's first
#: announcements is discovered at its next periodic one (every 3 s with Fast DDS).
ONCE_MIN_WATCH = 3.2
#: The scan period at most with ``--once`` (its report waits for a scan to confirm the
#: graph settled).
ONCE_SCAN_PERIOD = 0.5
#: How often timers (grace, liveness, rates) are evaluated (a scan and a parameter event
#: refresh the statuses at once).
TICK = 0.5
#: Seconds a parameter read (list, get, describe) may take before it is asked again.
READ_TIMEOUT = 5.0
#: The largest history a rate subscription keeps between two drains.
_MAX_RATE_DEPTH = 10000
#: A node's status is refreshed for its parameter events at most this often: the first
#: event after a quiet spell is checked and published at once, a storm's are coalesced.
EVENT_GAP = 0.02
#: Parameter events a second from one node beyond which they are a storm (NODL441).
STORM_RATE = 50
#: Seconds a storm is still reported after its last second above STORM_RATE.
STORM_HOLD = 2.0
#: The graph does not settle (NODL443) when it changed at least CHURN_CHANGES times in the
#: last CHURN_WINDOW seconds.
CHURN_WINDOW = 10.0
CHURN_CHANGES = 10


@dataclass
class MonitorSettings:
    """The monitor's parameters (see the module docstring)."""

    publish_rate: float = 1.0
    grace_period: float = 5.0
    rate_window: float = 2.0
    rate_tolerance: float = 0.2
    liveness_period: float = 1.0
    liveness_timeout: float = 2.0
    scan_period: float = 3.0
    restart_window: float = 30.0
    scan_budget: float = 0.1
    #: Node name patterns (fnmatch, on the fully qualified name or the base name) never
    #: reported as unexpected, besides :data:`DEFAULT_IGNORED` and hidden nodes.
    ignore: list[str] = field(default_factory=list)

    def problems(self) -> list[str]:
        """What is wrong with the values (each must be positive; the tolerance below 1)."""
        out = [f'{name} must be greater than 0 (got {getattr(self, name)!r})'
               for name in ('publish_rate', 'grace_period', 'rate_window', 'liveness_period',
                            'liveness_timeout', 'scan_period', 'restart_window', 'scan_budget')
               if not getattr(self, name) > 0]
        if not 0 <= self.rate_tolerance < 1:
            out.append(f'rate_tolerance must be at least 0 and below 1 (got {self.rate_tolerance!r})')
        return out


_NUMERIC = ('publish_rate', 'grace_period', 'rate_window', 'rate_tolerance', 'liveness_period',
            'liveness_timeout', 'scan_period', 'restart_window', 'scan_budget')


@dataclass
class _NodeState:
    """What the monitor knows of one expected node."""

    expected: ExpectedNode
    count: int = 0
    seen_at: float | None = None
    ever_seen: bool = False
    gone_at: float | None = None
    second_at: float | None = None
    namesake_at_start: bool = False
    restarts: int = 0
    observed: ObservedNode | None = None
    parameters: dict[str, ObservedParameter] | None = None
    params_state: str = 'unread'  # unread, reading, read, none
    params_buffer: list[tuple[str, str, Any, bool]] = field(default_factory=list)
    event_findings: dict[str, list[StatusFinding]] = field(default_factory=dict)
    endpoint_findings: list[StatusFinding] = field(default_factory=list)
    #: The parameter read under way (its clients on the monitor's node), None when none.
    reading: ParameterRead | None = None
    #: The liveness client (``~/get_parameters``, on the probe node: polled, not waited on).
    liveness: Any = None
    #: The sequence number of the liveness request awaiting its answer.
    ping: int | None = None
    ping_sent: float = 0.0
    not_answering_since: float | None = None
    last_answer: float | None = None
    #: When its parameter events arrived in the last second (storm detection).
    event_times: deque[float] = field(default_factory=deque)
    #: The most events it sent in one second during the current storm, and when the storm
    #: was last above STORM_RATE.
    storm_peak: int = 0
    storm_at: float | None = None
    #: Parameter events of it that never reached the monitor (sequence gaps).
    events_lost: int = 0
    lost_at: float | None = None
    #: When scans found its endpoints changed (the last CHURN_WINDOW seconds).
    churn: deque[float] = field(default_factory=deque)
    #: Its DDS participant (the GUID prefix its endpoints' GIDs share), None if unknown.
    participant: str | None = None
    #: The endpoint findings' inputs when last computed (the raw endpoints, the parameters'
    #: version): they are computed again only when these change.
    compared: Any = None
    params_version: int = 0


class Monitor:
    """Monitors a running system against ``expected`` (see the module docstring).

    ``ros_args``: the monitor node's ``--ros-args`` (remaps, parameters, log level);
    ``on_change(status, wall_time)``: called for every change of a status's level (and
    its first level).  :meth:`start`, then :meth:`run` until ``stop()`` is true or, with
    ``once``, until every expected node was seen and read.  Raises
    :class:`~nodl.live.session.LiveError` when ROS cannot be started.
    """

    def __init__(self, expected: ExpectedSystem, settings: MonitorSettings | None = None, *,
                 ros_args: Sequence[str] = (),
                 on_change: Callable[[Status, float], None] | None = None) -> None:
        self.expected = expected
        self.settings = settings or MonitorSettings()
        self.ros_args = list(ros_args)
        self.on_change = on_change
        self.states = {fqn: _NodeState(node) for fqn, node in expected.nodes.items()}
        self.node: Any = None
        self.executor: Any = None
        #: The session's graph follower (polling in its thread while :meth:`run` runs).
        self.graph: GraphFollower | None = None
        self.view: GraphView | None = None
        self.snapshot: Snapshot | None = None
        self.connections: dict[str, list[StatusFinding]] = {}
        self.arrivals: dict[str, deque[float]] = {}
        self.subscribed_at: dict[str, float] = {}
        self.started = 0.0
        self.statuses: dict[str, Status] = {}
        self._published: dict[str, tuple[Any, ...]] = {}
        self._levels: dict[str, int] = {}
        self._once = False
        #: When polls found the graph changed (the last CHURN_WINDOW seconds).
        self._changes: deque[float] = deque()
        self._next_scan = 0.0
        self._min_scan_gap = 0.0
        #: When the next periodic publication is due.
        self._next_publish = 0.0
        #: Wall seconds the last scan and the refresh after it took.
        self._scan_took = 0.0
        self._scan_wanted = False
        self._stable_since = 0.0
        self._shedding: list[str] = []
        self._events = 0
        #: Nodes whose status awaits a coalesced refresh for their parameter events.
        self._pending_events: set[str] = set()
        self._event_refreshed: dict[str, float] = {}
        #: The last sequence number of each /parameter_events publisher (by GID).
        self._event_sequences: dict[bytes, int] = {}
        self._unverifiable_rates: list[StatusFinding] = []
        self._rate_subscriptions: list[tuple[Any, deque[float]]] = []
        self.publisher: Any = None
        #: A second node, never waited on: the rate subscriptions and liveness clients,
        #: drained and polled at each tick (an executor rebuilds its wait set of every
        #: entity at every wake-up: with them there, 50 nodes cost a core's tenth).
        self.probe: Any = None

    # -- life cycle ------------------------------------------------------------------------

    def start(self) -> None:
        """Start rclpy (a private context), the node, its publisher and subscriptions."""
        rclpy = require_rclpy()
        try:
            from diagnostic_msgs.msg import DiagnosticArray  # type: ignore[import-untyped]
            from rcl_interfaces.msg import ParameterEvent
        except ImportError as exc:
            raise LiveError(f'nodl monitor needs diagnostic_msgs ({exc}); install it '
                            '(pip install ros-diagnostic-msgs, or from your ROS distribution)'
                            ) from None
        from rclpy.qos import QoSProfile, qos_profile_parameter_events

        # one live session, as every live verb's (its executor, its graph follower)
        self.node = open_session(MONITOR_NODE_NAME, ['nodl_monitor', '--ros-args', *self.ros_args],
                                 parameter_services=True)
        self.executor = self.node.nodl_executor
        self.graph = GraphFollower(self.node, period=POLL_PERIOD, topics_every=TOPIC_POLLS,
                                   services=False)
        self.node.nodl_graph = self.graph
        self._declare_parameters()
        self.probe = rclpy.create_node(MONITOR_NODE_NAME + '_probe', context=self.node.context,
                                       start_parameter_services=False, enable_rosout=False)
        self.view = GraphView(self.node)
        self.publisher = self.node.create_publisher(DiagnosticArray, '/diagnostics',
                                                    QoSProfile(depth=10))
        self.node.create_subscription(ParameterEvent, '/parameter_events', self._on_parameter_event,
                                      qos_profile_parameter_events)
        self.started = time.monotonic()
        self._subscribe_rates()

    def close(self) -> None:
        """Destroy the nodes and shut the session down (safe to call twice)."""
        if self.probe is not None:
            self.probe.destroy_node()
            self.probe = None
        if self.node is not None:
            node, self.node = self.node, None
            close_session(node)

    def _declare_parameters(self) -> None:
        from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult

        node = self.node
        for name in _NUMERIC:
            node.declare_parameter(name, float(getattr(self.settings, name)),
                                   ParameterDescriptor(description=f'nodl monitor: {name}'))
        values = {name: node.get_parameter(name).value for name in _NUMERIC}
        candidate = MonitorSettings(**{k: float(v) for k, v in values.items()},
                                    ignore=list(self.settings.ignore))
        problems = candidate.problems()
        if problems:
            raise LiveError('invalid monitor parameter: ' + '; '.join(problems))
        self.settings = candidate

        def on_set(parameters: list[Any]) -> Any:
            changed = {p.name: p.value for p in parameters if p.name in _NUMERIC}
            try:
                trial = MonitorSettings(**{**{k: getattr(self.settings, k) for k in _NUMERIC},
                                           **{k: float(v) for k, v in changed.items()}},
                                        ignore=list(self.settings.ignore))
            except (TypeError, ValueError) as exc:
                return SetParametersResult(successful=False, reason=str(exc))
            problems = trial.problems()
            if problems:
                return SetParametersResult(successful=False, reason='; '.join(problems))
            self.settings = trial
            return SetParametersResult(successful=True)

        node.add_on_set_parameters_callback(on_set)

    def _subscribe_rates(self) -> None:
        import importlib

        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

        topics: dict[str, DeadlineTopic] = {}
        for state in self.states.values():
            for deadline in state.expected.deadlines:
                topics.setdefault(deadline.topic, deadline)
        for topic, deadline in sorted(topics.items()):
            package, _, name = deadline.type.partition('/msg/')
            try:
                kind = getattr(importlib.import_module(f'{package}.msg'), name)
            except (ImportError, AttributeError, ValueError):
                self._unverifiable_rates.append(StatusFinding(
                    'NODL408', 'info', f'rate {topic}', f"the rate of '{topic}' cannot be "
                    f'measured: its type {deadline.type} is not installed', deadline.location))
                continue
            arrivals: deque[float] = deque(maxlen=100000)
            self.arrivals[topic] = arrivals
            self.subscribed_at[topic] = time.monotonic()
            # drained every TICK: room for four times the declared rate between two drains
            depth = min(_MAX_RATE_DEPTH, max(16, int(4 * TICK * deadline.expected_rate) + 1))
            qos = QoSProfile(depth=depth, reliability=ReliabilityPolicy.BEST_EFFORT,
                             durability=DurabilityPolicy.VOLATILE)
            subscription = self.probe.create_subscription(kind, topic, lambda _m: None, qos,
                                                          raw=True)
            self._rate_subscriptions.append((subscription, arrivals))

    def _drain_rates(self) -> None:
        """Take every message the rate subscriptions hold, recording when each arrived."""
        for subscription, arrivals in self._rate_subscriptions:
            offset = time.monotonic() - time.time()
            with subscription.handle:
                while True:
                    taken = subscription.handle.take_message(subscription.msg_type, True)
                    if taken is None:
                        break
                    received = taken[1].get('received_timestamp') if len(taken) > 1 else None
                    arrivals.append(received / 1e9 + offset if received else time.monotonic())

    # -- the loop --------------------------------------------------------------------------

    def run(self, stop: Callable[[], bool], *, once: bool = False, wait: float = 10.0) -> list[Status]:
        """Run until ``stop()`` is true (checked at least every 0.1 s) or, with ``once``,
        until every expected node was seen and read (or ``wait`` seconds passed).  Returns
        the last statuses (published before returning)."""
        assert self.node is not None and self.graph is not None
        deadline = time.monotonic() + wait if once else float('inf')
        self._once = once
        next_tick = self._next_publish = time.monotonic()
        # --once's report waits for the graph to settle, and costs no steady state: it
        # follows topic and service names at every poll
        self.graph.topics_every = 1 if once else TOPIC_POLLS
        self.graph.services = once
        # the follower polls in its thread and wakes the executor only when the graph
        # changed (or ``stop()`` became true): every wake-up of an executor rebuilds its
        # wait set
        wake = self.node.create_guard_condition(lambda: None)

        def on_poll(changed: bool) -> None:
            if changed or stop():
                wake.trigger()

        self.graph.watch(on_poll)
        try:
            while not stop():
                now = time.monotonic()
                if now >= deadline:
                    break
                self.executor.spin_once(timeout_sec=max(0.0, min(
                    next_tick, self._next_publish, deadline, self._next_flush(),
                    self._scan_at(now, self._next_publish)) - now))
                self._step_reads()
                now = time.monotonic()
                self._flush_events(now)
                self._publish_due()  # before a scan that could make it late
                self._follow(now, self._next_publish)
                if now >= next_tick:
                    next_tick = now + TICK
                    self._tick(now)
                    self._refresh(now)
                    if once and self._complete(now):
                        break
                self._publish_due()
        finally:
            self.graph.unwatch()
            self.node.destroy_guard_condition(wake)
        now = time.monotonic()
        self._refresh(now, publish_changes=False)
        self._publish(now)
        return self.ordered_statuses()

    def ordered_statuses(self) -> list[Status]:
        """The statuses: the system's first, then the nodes' by name."""
        return [self.statuses[k] for k in sorted(self.statuses, key=lambda n: (n != SYSTEM, n))]

    def _scan_due(self) -> float:
        """When the next scan may run: at once for a first one, as soon as the budget
        allows for a change, else every ``scan_period``."""
        if self.snapshot is None:
            return 0.0
        if self._scan_wanted:
            return self._next_scan
        period = self.settings.scan_period
        if self._once:
            period = min(period, ONCE_SCAN_PERIOD)  # a report waits for a confirming scan
        return max(self._next_scan, self.snapshot.time + period)

    def _scan_at(self, now: float, publish_at: float) -> float:
        """When to scan: :meth:`_scan_due`, or just after the publication due at
        ``publish_at`` when the scan and the refresh after it (as long as the last, in
        processor or in wall time: a loaded machine's scan takes longer than its processor
        time) would not end before it."""
        due = self._scan_due()
        period = 1.0 / max(self.settings.publish_rate, 1e-3)
        if self.snapshot is None:
            return due
        length = max(self.snapshot.cost, self._scan_took)
        if length < period and max(due, now) + length >= publish_at:
            return max(due, publish_at)  # (a scan longer than the period cannot wait)
        return due

    def _follow(self, now: float, publish_at: float = float('inf')) -> None:
        """Take the graph changes the follower found; scan when one is wanted and due, and
        would end before the next periodic publication (``publish_at``) is due (else just
        after it: a scan of thousands of endpoints takes a while)."""
        assert self.graph is not None
        changed = False
        for when in self.graph.take_changes():
            self._changes.append(when)
            self._stable_since = max(self._stable_since, when)
            changed = True
        if changed:
            self._scan_wanted = True
        if now >= self._scan_at(now, publish_at):
            began = time.monotonic()
            self._scan(now)
            self._refresh(now)  # a change is published within a poll, not a tick
            self._scan_took = time.monotonic() - began
        elif self._scan_wanted and self._min_scan_gap > 1.0:
            self._shed(f'graph scans spaced out to every {self._min_scan_gap:.1f} s to stay within the CPU '
                       'budget')

    def _shed(self, why: str) -> None:
        if why not in self._shedding:
            self._shedding = [w for w in self._shedding if w.split()[0] != why.split()[0]] + [why]

    def _scan(self, now: float) -> None:
        assert self.view is not None and self.graph is not None
        previous = self.snapshot
        # --once reads every node's endpoints: its report waits for their discovery; the
        # nodes present are those of the follower's last poll (what woke this scan)
        snapshot = self.view.scan(self.graph.counts, [fqn for fqn, s in self.states.items()
                                                      if s.expected.resolved is not None],
                                  everyone=self._once, meanwhile=self._publish_due)
        self.snapshot = snapshot
        self._scan_wanted = False
        self._min_scan_gap = snapshot.cost / self.settings.scan_budget
        self._next_scan = now + self._min_scan_gap
        if self._min_scan_gap <= 1.0:
            self._shedding = [w for w in self._shedding if not w.startswith('graph')]
        for fqn, state in self.states.items():
            self._update_presence(state, snapshot.counts.get(fqn, 0), now)
            raw = snapshot.endpoints.get(fqn)
            if raw is None:
                continue
            prefixes = {e.gid[:24] for e in snapshot.of_node(fqn) if len(e.gid) == 32}
            state.participant = prefixes.pop() if len(prefixes) == 1 else None
            old = previous.endpoints.get(fqn) if previous else None
            if old != raw or state.observed is None:
                self._stable_since = now
                if old is not None:
                    state.churn.append(now)
                state.observed = observed_node(fqn, snapshot)
            elif previous is None or previous.of_node(fqn) != snapshot.of_node(fqn):
                # an endpoint recreated (another GID): compared again if its QoS changed
                observed = observed_node(fqn, snapshot)
                if observed is not None and _qos_of(state.observed) != _qos_of(observed):
                    state.observed = observed
        self.connections = connection_findings(snapshot.topics)
        if previous is None or previous.topics != snapshot.topics:
            # an endpoint's QoS arrives with DDS discovery, after its node's announcement:
            # --once waits for the topic infos to settle too
            self._stable_since = now

    def _update_presence(self, state: _NodeState, count: int, now: float) -> None:
        before = state.count
        state.count = count
        if count and not before:
            if not state.ever_seen and count > 1:
                state.namesake_at_start = True
            state.ever_seen = True
            state.seen_at = now
            state.gone_at = None
            self._new_instance(state)
        elif before and not count:
            state.gone_at = now
            state.second_at = None
            state.observed = None
            self._drop_clients(state)
        if count > 1 and before == 1:
            state.second_at = now
            state.restarts += 1
        if count == 1 and before > 1:
            state.second_at = None
            state.namesake_at_start = False
            self._new_instance(state)

    def _new_instance(self, state: _NodeState) -> None:
        """A (new) process holds the name: read its parameters again."""
        self._stop_reading(state)
        state.parameters = None
        state.params_state = 'unread'
        state.event_findings.clear()
        state.not_answering_since = None

    def _drop_clients(self, state: _NodeState) -> None:
        self._stop_reading(state)
        if state.liveness is not None:
            self.probe.destroy_client(state.liveness)
            state.liveness = None
        state.ping = None
        state.last_answer = None
        state.params_state = 'unread'
        state.parameters = None

    # -- parameters and liveness -----------------------------------------------------------

    def _serves_parameters(self, state: _NodeState) -> bool:
        observed = state.observed
        fqn = state.expected.fqn
        return observed is not None and any(e.name == f'{fqn}/get_parameters'
                                            for e in observed.service_servers)

    def _stop_reading(self, state: _NodeState) -> None:
        """Destroy the parameter read's clients (the executor waits on each of them)."""
        if state.reading is not None:
            state.reading.close()
            state.reading = None

    def _tick(self, now: float) -> None:
        due = self._liveness_due(now)
        for state in self.states.values():
            if state.storm_at is not None and now - state.storm_at > STORM_HOLD:
                state.storm_at, state.storm_peak = None, 0
            if state.lost_at is not None and state.params_state == 'read' \
                    and now - state.lost_at > STORM_HOLD:
                state.lost_at = None
            if not state.count or state.expected.resolved is None:
                continue
            if state.observed is None:
                continue
            if not self._serves_parameters(state):
                if state.params_state == 'unread':
                    state.params_state = 'none'
                continue
            if state.params_state == 'none':
                state.params_state = 'unread'
            if state.params_state == 'unread':
                self._read_parameters(state, now)
            self._liveness(state, now, state.expected.fqn in due)

    def _liveness_due(self, now: float) -> set[str]:
        """The nodes to call this period.  The nodes of one process share its DDS
        participant (their endpoints' GIDs share one GUID prefix), and a process killed
        takes them all: each period one of them is called, in turn (a component container
        of 20 nodes costs one call a period, not 20), and all of them as soon as one has
        stopped answering.  A node whose participant is not known is called every period."""
        groups: dict[str, list[str]] = {}
        due: set[str] = set()
        for fqn, state in self.states.items():
            if not state.count or state.expected.resolved is None or state.observed is None \
                    or not self._serves_parameters(state):
                continue  # not called (see _tick): never a process's turn
            if state.participant is None:
                due.add(fqn)
            else:
                groups.setdefault(state.participant, []).append(fqn)
        turn = int(now / self.settings.liveness_period)
        for members in groups.values():
            if len(members) == 1 or any(self.states[f].not_answering_since is not None
                                        for f in members):
                due.update(members)
            else:
                due.add(sorted(members)[turn % len(members)])
        return due

    def _liveness(self, state: _NodeState, now: float, due: bool = True) -> None:
        """Poll the node's answer to the last ``~/get_parameters`` call; call again (when
        ``due``) every ``liveness_period`` seconds.  The client is on the probe node: nothing
        waits on it."""
        from rcl_interfaces.srv import GetParameters

        if state.liveness is None:
            state.liveness = self.probe.create_client(GetParameters,
                                                      f'{state.expected.fqn}/get_parameters')
        client = state.liveness
        with client.handle:
            while state.ping is not None:
                header, _response = client.handle.take_response(GetParameters.Response)
                if header is None:
                    break
                if header.request_id.sequence_number == state.ping:
                    state.ping = None
                    state.last_answer = now
                    state.not_answering_since = None
            if state.ping is not None and now - state.ping_sent > self.settings.liveness_timeout:
                # a first call can be lost while the service's reply path is still being
                # discovered: until it first answered, a node has the grace period
                first = state.last_answer is None and \
                    now - (state.seen_at or now) < self.settings.grace_period
                if state.not_answering_since is None and not first:
                    state.not_answering_since = state.ping_sent
                state.ping = None
            period = self.settings.liveness_period
            if due and state.ping is None and now - state.ping_sent >= period \
                    and (state.last_answer is not None or client.service_is_ready()):
                state.ping = client.handle.send_request(GetParameters.Request(names=[]))
                state.ping_sent = now

    def _read_parameters(self, state: _NodeState, now: float) -> None:
        """Start reading the node's parameters, as every live verb reads them
        (:class:`~nodl.live.observe.ParameterRead`: each call sent once its server is
        discovered); :meth:`_step_reads` follows it after each wake-up.  Without every
        answer within READ_TIMEOUT seconds, it is asked again at the next tick."""
        self._stop_reading(state)
        state.reading = ParameterRead(self.node, state.expected.fqn, now + READ_TIMEOUT)
        state.params_state = 'reading'
        state.reading.step()

    def _step_reads(self) -> None:
        """Send what the parameter reads under way can send; take those done (their events
        buffered meanwhile applied after), and refresh the statuses at once."""
        done = False
        for state in self.states.values():
            reading = state.reading
            if reading is None or not reading.step():
                continue
            parameters = reading.result()
            self._stop_reading(state)
            if parameters is None:
                state.params_state = 'unread'  # no answer in time: asked again
                continue
            state.parameters = parameters
            state.params_state = 'read'
            for name, type_name, value, changed in state.params_buffer:
                self._apply_parameter(state, name, type_name, value, changed)
            state.params_buffer.clear()
            done = True
        if done:
            self._refresh(time.monotonic())

    def _on_parameter_event(self, event: Any, info: Any) -> None:
        """Check one parameter event as it arrives (the callback takes the message info:
        a gap in a publisher's sequence numbers is events lost)."""
        from nodl.live.observe import _value

        state = self.states.get(event.node)
        if state is None:
            return
        self._events += 1
        now = time.monotonic()
        self._count_event(state, info, now)
        touched = False
        for items, changed in ((event.new_parameters, False), (event.changed_parameters, True)):
            for parameter in items:
                type_name = PARAMETER_TYPE_BY_NUMBER.get(parameter.value.type, 'none')
                value = _value(parameter.value)
                if state.params_state != 'read':
                    state.params_buffer.append((parameter.name, type_name, value, changed))
                self._apply_parameter(state, parameter.name, type_name, value, changed)
                touched = True
        for parameter in event.deleted_parameters:
            if state.parameters is not None:
                state.parameters.pop(parameter.name, None)
                state.params_version += 1
                touched = True
        if touched:
            self._pending_events.add(event.node)
            self._flush_events(now)

    def _count_event(self, state: _NodeState, info: Any, now: float) -> None:
        """Storm detection (events in the last second) and lost events (sequence gaps:
        the node's parameters are read again)."""
        times = state.event_times
        times.append(now)
        while times and times[0] < now - 1.0:
            times.popleft()
        if len(times) > STORM_RATE:
            first = state.storm_at is None
            state.storm_peak = max(state.storm_peak, len(times))
            state.storm_at = now
            if first:
                self._refresh(now)  # NODL441 published at once
        gid = (info or {}).get('publisher_gid') or {}
        sequence = (info or {}).get('publication_sequence_number')
        if not isinstance(gid, dict) or not isinstance(sequence, int) or sequence <= 0:
            return
        key = bytes(gid.get('data') or b'')
        last = self._event_sequences.get(key)
        self._event_sequences[key] = sequence
        if last is not None and sequence > last + 1:
            state.events_lost += sequence - last - 1
            state.lost_at = now
            if state.params_state == 'read':
                state.params_state = 'unread'  # read again: the values lost are not known

    def _flush_events(self, now: float) -> None:
        """Refresh (and publish, if changed) the statuses of the nodes whose parameter
        events arrived, each at most every EVENT_GAP seconds."""
        for fqn in sorted(self._pending_events):
            if now - self._event_refreshed.get(fqn, -1.0) >= EVENT_GAP:
                self._pending_events.discard(fqn)
                self._event_refreshed[fqn] = now
                self._refresh(now, only=fqn)

    def _next_flush(self) -> float:
        """When the next coalesced refresh is due (infinity when none is pending)."""
        return min((self._event_refreshed.get(f, 0.0) + EVENT_GAP for f in self._pending_events),
                   default=float('inf'))

    def _apply_parameter(self, state: _NodeState, name: str, type_name: str, value: Any,
                         changed: bool) -> None:
        findings = parameter_event_findings(state.expected, name, type_name, value, changed)
        if findings:
            state.event_findings[name] = findings
        state.params_version += 1
        if state.parameters is None:
            return
        old = state.parameters.get(name)
        if old is None:
            state.parameters[name] = ObservedParameter(name, type_name, value)
        else:
            old.type, old.value = type_name, value

    # -- statuses ----------------------------------------------------------------------------

    def _node_status(self, state: _NodeState, now: float) -> Status:
        from nodl.live.conformance import compare

        expected = state.expected
        status = Status(status_name(expected.fqn), expected.hardware_id,
                        location=expected.location)
        if expected.definition_file:
            status.facts.append(('definition', expected.definition_file))
        else:
            status.findings.append(StatusFinding('NODL433', 'info', 'definition',
                                                 f'{expected.no_definition}', expected.location))
        settings = self.settings
        if not state.count:
            if state.ever_seen:
                status.findings.append(StatusFinding(
                    'NODL430', 'error', 'node', f'{expected.fqn} is not running: gone from the '
                    f'graph {now - (state.gone_at or now):.1f} s ago', expected.location))
                status.facts.append(('state', 'gone'))
            elif now - self.started >= settings.grace_period:
                status.findings.append(StatusFinding(
                    'NODL430', 'error', 'node', f'{expected.fqn} is not running: not seen within '
                    f'the grace period of {settings.grace_period:g} s', expected.location))
                status.facts.append(('state', 'missing'))
            else:
                status.ok_message = 'waiting for it to appear (grace period)'
                status.facts.append(('state', 'waiting'))
            return status
        status.facts.append(('state', 'running'))
        status.facts.append(('instances', str(state.count)))
        if state.restarts:
            status.facts.append(('restarts', str(state.restarts)))
        if state.count > 1:
            since = state.second_at if state.second_at is not None else self.started
            if state.namesake_at_start or now - since >= settings.restart_window:
                status.findings.append(StatusFinding(
                    'NODL550', 'error', 'node', f'duplicate-node: {state.count} nodes in the graph '
                    f'are named {expected.fqn} (namesakes): their endpoints cannot be told apart; '
                    'give each a unique name', expected.location))
            else:
                status.findings.append(StatusFinding(
                    'NODL432', 'warning', 'node', f'{expected.fqn} is restarting: a new node of '
                    f'this name appeared {now - since:.1f} s ago while the old one is still in the '
                    f'graph (until its participant lease ends; namesakes after '
                    f'{settings.restart_window:g} s)', expected.location))
        if state.not_answering_since is not None:
            status.findings.append(StatusFinding(
                'NODL434', 'error', 'node', f'{expected.fqn} stopped answering its parameter '
                f'services {now - state.not_answering_since:.1f} s ago (killed or hung?)',
                expected.location))
        if expected.resolved is not None and state.observed is not None and state.count == 1:
            key = (id(state.observed), state.params_state, state.params_version)
            if key != state.compared:
                observed = state.observed
                # read, or being read again (events were lost): the values known so far
                known = state.params_state == 'read' or (state.params_state == 'reading'
                                                         and state.parameters is not None)
                observed.parameters = state.parameters if known else None
                differences = compare(expected.resolved, observed, expected.names)
                if not known:
                    differences = [d for d in differences if d.section != 'parameters']
                state.endpoint_findings = endpoint_findings(differences)
                state.compared = key
            status.findings.extend(state.endpoint_findings)
        for findings in state.event_findings.values():
            status.findings.extend(findings)
        status.findings.extend(self.connections.get(expected.fqn, []))
        for finding in self._unverifiable_rates:
            if any(finding.subject == f'rate {d.topic}' for d in expected.deadlines):
                status.findings.append(finding)
        for deadline in expected.deadlines:
            arrivals = self.arrivals.get(deadline.topic)
            if arrivals is None:
                continue
            window = settings.rate_window
            since = max(self.subscribed_at[deadline.topic], state.seen_at or now)
            if now - since < window:
                continue
            while arrivals and arrivals[0] < now - window:
                arrivals.popleft()
            count = len(arrivals)
            status.facts.append((f'rate {deadline.topic}', f'{count / window:.3g} Hz '
                                 f'(deadline {deadline.deadline_ns / 1e6:g} ms: '
                                 f'{deadline.expected_rate:g} Hz)'))
            slow = rate_finding(deadline, count, window, settings.rate_tolerance)
            if slow is not None:
                status.findings.append(slow)
        status.ok_message = 'running as defined' if expected.resolved is not None else 'running'
        return status

    def _system_status(self, now: float) -> Status:
        status = Status(SYSTEM, 'nodl', ok_message=f'{len(self.states)} expected nodes')
        counts = self.snapshot.counts if self.snapshot is not None else {}
        patterns = list(DEFAULT_IGNORED) + list(self.settings.ignore)
        unexpected = []
        for fqn, count in sorted(counts.items()):
            if fqn in self.states or is_hidden_node(fqn):
                continue
            base = fqn.rpartition('/')[2]
            if any(fnmatch.fnmatchcase(fqn, p) or fnmatch.fnmatchcase(base, p) for p in patterns):
                continue
            unexpected.append(fqn)
            status.findings.append(StatusFinding('NODL431', 'warning', f'node {fqn}',
                                                 f'{fqn} is running but the expected system does not '
                                                 'have it'))
            if count > 1:
                status.findings.append(StatusFinding(
                    'NODL550', 'error', f'node {fqn}', f'duplicate-node: {count} nodes in the '
                    f'graph are named {fqn} (namesakes)'))
        for diagnostic in self.expected.diagnostics:
            if diagnostic.code == 'NODL440':
                status.findings.append(StatusFinding('NODL440', 'warning', f'entry {diagnostic.line}',
                                                     diagnostic.message,
                                                     _location(diagnostic)))
        for why in self._shedding:
            status.findings.append(StatusFinding('NODL439', 'warning', 'shedding ' + why.split()[0],
                                                 f'shedding: {why}'))
        churn = self._churn(now)
        if churn is not None:
            status.findings.append(churn)
        lost = 0
        for fqn, state in sorted(self.states.items()):
            lost += state.events_lost
            if state.storm_at is not None:
                status.findings.append(StatusFinding(
                    'NODL441', 'warning', f'parameter events {fqn}',
                    f'shedding: a parameter event storm from {fqn} (up to {state.storm_peak} '
                    f'events a second): every event is checked, its status refreshed and '
                    f'published at most every {EVENT_GAP * 1000:g} ms'))
            if state.lost_at is not None:
                status.findings.append(StatusFinding(
                    'NODL442', 'warning', f'parameter events lost {fqn}',
                    f'{state.events_lost} parameter events of {fqn} never reached the monitor '
                    f'(it fell behind, or the network dropped them): its parameters are read '
                    f'again'))
        presence = [s.expected.fqn for s in self.states.values() if s.expected.resolved is None]
        if presence:
            status.facts.append(('presence only', ', '.join(presence)))
        status.facts.append(('expected', str(len(self.states))))
        status.facts.append(('running', str(sum(1 for s in self.states.values() if s.count))))
        status.facts.append(('unexpected', str(len(unexpected))))
        status.facts.append(('parameter events', str(self._events)))
        if lost:
            status.facts.append(('parameter events lost', str(lost)))
        return status

    def _churn(self, now: float) -> StatusFinding | None:
        """NODL443 when the graph changed CHURN_CHANGES times in CHURN_WINDOW seconds,
        naming the expected nodes whose endpoints kept changing."""
        for times in [self._changes] + [s.churn for s in self.states.values()]:
            while times and times[0] < now - CHURN_WINDOW:
                times.popleft()
        if len(self._changes) < CHURN_CHANGES:
            return None
        busy = sorted(((len(s.churn), fqn) for fqn, s in self.states.items() if s.churn),
                      key=lambda item: (-item[0], item[1]))
        named = ', '.join(f'{fqn} ({n} times)' for n, fqn in busy[:5])
        more = f' and {len(busy) - 5} more' if len(busy) > 5 else ''
        where = f'; endpoints keep changing on {named}{more}' if busy else ''
        return StatusFinding('NODL443', 'warning', 'graph',
                             f'the graph does not settle: it changed {len(self._changes)} times in the '
                             f'last {CHURN_WINDOW:g} s (nodes, topics or endpoints keep coming and '
                             f'going){where}; endpoint findings follow the last scan')

    def _refresh(self, now: float, *, only: str | None = None, publish_changes: bool = True) -> None:
        """Recompute the statuses (one node's with ``only``); publish at once if one changed."""
        if self.node is None:
            return
        self._drain_rates()  # the rates counted up to now
        if only is not None:
            state = self.states[only]
            fresh = {status_name(only): self._node_status(state, now)}
        else:
            fresh = {status_name(fqn): self._node_status(s, now) for fqn, s in self.states.items()}
            fresh[SYSTEM] = self._system_status(now)
        self.statuses.update(fresh)
        changed = [s for name, s in fresh.items() if self._published.get(name) != s.signature()]
        if not changed:
            return
        for status in changed:
            if self._levels.get(status.name) != status.level and self.on_change is not None:
                self.on_change(status, time.time())
            self._levels[status.name] = status.level
        if publish_changes:
            self._publish(now)

    def _publish_due(self) -> None:
        """The periodic publication, if it is due (also between the chunks of a long
        scan: a scan of thousands of endpoints on a loaded machine takes longer than
        the publish period)."""
        now = time.monotonic()
        if now >= self._next_publish:
            self._publish(now)
            self._next_publish = now + 1.0 / max(self.settings.publish_rate, 1e-3)

    def _publish(self, now: float) -> None:
        from diagnostic_msgs.msg import DiagnosticArray

        if self.node is None or not self.statuses:
            return
        message = DiagnosticArray()
        message.header.stamp = self.node.get_clock().now().to_msg()
        statuses = self.ordered_statuses()
        message.status = [to_message(s) for s in statuses]
        self.publisher.publish(message)
        self._published = {s.name: s.signature() for s in statuses}

    def _complete(self, now: float) -> bool:
        """``--once``: every expected node seen, scanned, its parameters read, and its
        deadline topics measured over a whole window; the graph unchanged for 0.3 s, as a
        scan at least 0.3 s after the last change confirms (QoS arrive with DDS discovery,
        after the nodes' announcements)."""
        if self.snapshot is None or self.snapshot.time - self._stable_since < 0.3 \
                or not discovered(self.snapshot) or now - self.started < ONCE_MIN_WATCH:
            return False
        for state in self.states.values():
            if not state.count:
                return False
            if state.expected.resolved is None:
                continue
            if state.observed is None or state.params_state in ('unread', 'reading'):
                return False
            for deadline in state.expected.deadlines:
                if deadline.topic in self.arrivals and now - max(
                        self.subscribed_at[deadline.topic], state.seen_at or now) < \
                        self.settings.rate_window:
                    return False
        return True


def _qos_of(observed: ObservedNode) -> list[Any]:
    return [(e.name, e.qos, e.unobserved) for e in observed.publishers + observed.subscriptions]


def _location(diagnostic: Any) -> Any:
    from nodl.composition.entities import Location

    return Location(diagnostic.file, diagnostic.line, diagnostic.column)
