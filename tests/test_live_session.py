"""The toolkit's own observer nodes never appear as the user's nodes.

Each live session creates a real rclpy node to observe the graph. It is named as ROS
hides a node (a leading underscore), uniquely per process and session, and every live
feature leaves it out: node listings, namesake counting, and per-topic endpoint lists
(its ``/parameter_events`` publisher, its ``~/get_type_description`` service).
These run real sessions in this process and real nodes in other processes.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

from conftest import NodeProcess
from nodl.live.observe import count_nodes, list_nodes
from nodl.live.session import OBSERVER_PREFIX, is_hidden_node, is_toolkit_node, ros_session, without_toolkit_nodes


def raw_names(session) -> set[str]:
    return {(ns.rstrip('/') + '/' + n) for n, ns in session.get_node_names_and_namespaces()}


def wait_until(session, predicate, timeout: float = 15.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        session.nodl_executor.spin_once(timeout_sec=0.05)
    return False


def test_names_are_hidden_and_unique() -> None:
    assert is_hidden_node('/ns/_daemon') and not is_hidden_node('/_ns/daemon')
    assert is_toolkit_node(f'/{OBSERVER_PREFIX}12_1') and not is_toolkit_node('/_daemon')
    with ros_session() as first, ros_session() as second:
        names = {first.get_fully_qualified_name(), second.get_fully_qualified_name()}
        assert len(names) == 2
        for name in names:
            assert name.startswith(f'/{OBSERVER_PREFIX}{os.getpid()}_')
            assert is_hidden_node(name) and is_toolkit_node(name)


def test_another_session_is_neither_listed_nor_a_namesake() -> None:
    with ros_session() as first, ros_session() as second:
        other = second.get_fully_qualified_name()
        # the graph does hold the other observer: the filter below is what leaves it out
        assert wait_until(first, lambda: other in raw_names(first)), 'discovery failed'
        assert other not in list_nodes(first)
        assert first.get_fully_qualified_name() not in list_nodes(first)
        assert other not in count_nodes(first)
        # its /parameter_events publisher is in the topic's endpoints, and is filtered out
        assert wait_until(first, lambda: any(
            i.node_name == other.lstrip('/')
            for i in first.get_publishers_info_by_topic('/parameter_events')))
        kept = without_toolkit_nodes(first.get_publishers_info_by_topic('/parameter_events'))
        assert not [i for i in kept if i.node_name.startswith(OBSERVER_PREFIX)]


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl', *args], capture_output=True,
                          text=True, timeout=60)


def test_describe_all_leaves_hidden_nodes_out_and_says_so(tmp_path: Path) -> None:
    hidden = NodeProcess('plain_node.py', '_helper', '/sess_hidden')
    shown = NodeProcess('plain_node.py', 'talker', '/sess_hidden')
    try:
        # another toolkit session is running at the same time (as a second nodl would be)
        with ros_session():
            result = nodl('describe', '--all', '-o', str(tmp_path / 'out'), '--timeout', '10')
    finally:
        hidden.stop()
        shown.stop()
    assert result.returncode == 0, result.stderr
    lines = dict(line.split(' -> ', 1) for line in result.stdout.splitlines())
    assert lines['/sess_hidden/_helper'] == '(skipped)'
    assert '  note: a hidden node (its name starts with _), left out' in result.stderr
    assert lines['/sess_hidden/talker'].endswith('sess_hidden.talker.nodl.yaml')
    assert not [n for n in lines if OBSERVER_PREFIX in n]
    assert not [p for p in (tmp_path / 'out').iterdir() if 'observer' in p.name]


def test_policy_live_lists_no_observer(tmp_path: Path) -> None:
    shown = NodeProcess('plain_node.py', 'listener', '/sess_policy')
    try:
        with ros_session():
            result = nodl('policy', '--live', '--timeout', '10')
    finally:
        shown.stop()
    assert result.returncode == 0, result.stderr
    assert '/sess_policy/listener' in result.stdout
    # neither this test's session nor the verb's own is in the policy or its notes
    assert OBSERVER_PREFIX not in result.stdout + result.stderr
    assert 'nodl_observer' not in result.stdout + result.stderr
