"""The live layer's graph follower against real node processes: it sees nodes come and go
within 100 ms of the local graph cache, settles on what is waited for (not the whole
graph), counts discovery from the session's start, and (``nodl monitor``'s way) follows
the graph in a thread of its own that tells of each change."""

from __future__ import annotations

import itertools
import threading
import time

from nodl.live.graph_events import POLL_PERIOD, GraphFollower, follower, graph_signature
from nodl.live.observe import list_nodes
from nodl.live.session import ros_session

_FLAPPING_NODE = '''
import sys

import rclpy
from std_msgs.msg import String

argv = sys.argv[1:]
rclpy.init()
node = rclpy.create_node(argv[argv.index('--name') + 1],
                         namespace=argv[argv.index('--namespace') + 1])
print('ready', flush=True)
i = 0
try:
    while rclpy.ok():
        publisher = node.create_publisher(String, f'flap_{i % 50}', 1)
        rclpy.spin_once(node, timeout_sec=0.02)
        node.destroy_publisher(publisher)
        i += 1
except KeyboardInterrupt:
    pass
'''


def test_changes_are_yielded_when_a_node_comes_and_goes(ros_node) -> None:
    with ros_session() as session:
        graph = follower(session)
        assert follower(session) is graph  # one per session
        node = ros_node('plain_node.py', 'comer', '/ge')
        deadline = time.monotonic() + 15
        for _ in graph.changes(deadline):
            if node.fqn in graph.counts:
                break
        assert graph.counts.get(node.fqn) == 1
        node.stop()
        for _ in graph.changes(time.monotonic() + 15):
            if node.fqn not in graph.counts:
                break
        assert node.fqn not in graph.counts
        assert time.monotonic() < deadline + 15


def test_a_change_in_the_local_graph_cache_is_seen_within_100_ms(ros_node) -> None:
    """The follower's view against the cache read directly after every spin: the follower
    never lags it by more than 100 ms."""
    node = ros_node('plain_node.py', 'quick', '/ge')
    with ros_session() as session:
        graph = follower(session)
        direct = followed = None
        deadline = time.monotonic() + 15
        while time.monotonic() < deadline and followed is None:
            graph.spin_once(0.005)
            now = time.monotonic()
            if direct is None and node.fqn in list_nodes(session):
                direct = now
            if node.fqn in graph.counts:
                followed = now
        assert direct is not None and followed is not None
        assert followed - direct <= 0.1
        assert graph.watched <= time.monotonic() - graph.started
        assert graph.signature == graph_signature(session, graph.followed) or graph.poll(force=True)


def test_settling_waits_for_what_is_waited_for_not_the_whole_graph(ros_node, tmp_path) -> None:
    script = tmp_path / 'flapping_node.py'
    script.write_text(_FLAPPING_NODE, encoding='utf-8')
    flapper = ros_node(str(script), 'flapper', '/ge')
    steady = ros_node('plain_node.py', 'steady', '/ge')
    with ros_session() as session:
        graph = follower(session)
        # both discovered (a participant that misses the session's first announcements is
        # discovered seconds later: until then the graph around the steady node is quiet)
        assert graph.wait(lambda: steady.fqn in graph.counts and flapper.fqn in graph.counts,
                          time.monotonic() + 15)
        graph.follow([steady.fqn])
        # the node's own endpoints settle although the graph keeps changing around it
        start = time.monotonic()
        assert graph.settle(0.3, start + 5, on=[steady.fqn])
        assert 0.3 <= time.monotonic() - start < 5
        assert graph.part(steady.fqn) is not None
        # the whole graph never does: taken as it is at the deadline
        start = time.monotonic()
        assert not graph.settle(0.5, start + 1.0)
        assert 1.0 <= time.monotonic() - start < 1.0 + 3 * POLL_PERIOD + 1


def test_discovery_is_watched_from_the_session_start_up_to_a_deadline() -> None:
    with ros_session() as session:
        graph = follower(session)
        graph.watch_until(0.8, time.monotonic() + 10)
        assert 0.8 <= graph.watched < 0.8 + 1
        session.nodl_started = time.monotonic()  # a session that has only just started ...
        start = time.monotonic()
        graph.watch_until(5.0, start + 0.3)  # ... stops watching at the deadline
        assert time.monotonic() - start < 1.5
        assert graph.watched < 1.5


def test_a_watching_thread_tells_of_each_change_within_100_ms(ros_node) -> None:
    """nodl monitor's follower: polled by a thread of its own (topic names every third poll,
    service names never), which tells of every poll; a node appearing is in its counts, and
    among the changes taken, within 100 ms of the local graph cache read directly."""
    with ros_session() as session:
        graph = GraphFollower(session, period=0.08, topics_every=3, services=False)
        session.nodl_graph = graph
        assert follower(session) is graph
        told: list[bool] = []
        woken = threading.Event()

        def on_poll(changed: bool) -> None:
            told.append(changed)
            if changed:
                woken.set()

        graph.watch(on_poll)
        try:
            end = time.monotonic() + 5
            while not told and time.monotonic() < end:  # the first poll
                time.sleep(0.01)
            assert told
            graph.take_changes()
            woken.clear()
            node = ros_node('plain_node.py', 'watched', '/ge')
            direct = followed = None
            deadline = time.monotonic() + 15
            while time.monotonic() < deadline and followed is None:
                now = time.monotonic()
                if direct is None and node.fqn in list_nodes(session):
                    direct = now
                if node.fqn in graph.counts:
                    followed = now
                time.sleep(0.002)
            assert direct is not None and followed is not None
            assert followed - direct <= 0.1
            changes = graph.take_changes()
            assert changes and all(a <= b for a, b in itertools.pairwise(changes))
            assert woken.is_set()
            assert graph.take_changes() == []
            assert graph.signature[2] is None  # no service names read
            polls = len(told)
            time.sleep(0.5)
            assert 4 <= len(told) - polls <= 8  # every 80 ms, told each time
            node.stop()
            assert graph.wait(lambda: node.fqn not in graph.counts, time.monotonic() + 15)
        finally:
            graph.unwatch()
        assert not any(t.name == 'nodl-graph-follower' for t in threading.enumerate())
        polls = len(told)
        time.sleep(0.2)
        assert len(told) == polls  # stopped
