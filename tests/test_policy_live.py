"""--live against real rclpy nodes: actions as <actions>, clients included, base entities granted."""

from __future__ import annotations

import subprocess
import sys

import pytest

from conftest import REPO, NodeProcess
from nodl.policy.live import live_policy
from nodl.policy.writer import write_policy


@pytest.fixture(scope='module')
def graph():
    started = []
    try:
        started.append(NodeProcess('full_node.py', 'full', '/live_p'))
        started.append(NodeProcess('action_nodes.py', 'fib', '/live_p'))
        started.append(NodeProcess('full_node.py', '_hidden', '/live_p'))  # a tool's node
        yield started
    finally:
        for node in started:
            node.stop()


def test_live_policy_of_real_nodes(graph):
    live = live_policy(timeout=15.0, settle=8.0)  # a loaded machine announces late
    assert {'/live_p/full', '/live_p/fib', '/live_p/fib_client'} <= set(live.nodes)
    policy = live.result.policy
    server = policy.profile('/live_p/fib')
    client = policy.profile('/live_p/fib_client')
    full = policy.profile('/live_p/full')
    assert server is not None and client is not None and full is not None
    assert ('action', 'execute', '/live_p/fib/fibonacci') in server.grants
    assert ('action', 'call', '/live_p/fib/fibonacci') in client.grants
    for profile in (server, client):  # no internal action topics or services
        assert not any('/_action/' in name for _, _, name in profile.grants)
    assert ('service', 'request', '/motor/enable') in full.grants  # clients included
    assert ('service', 'reply', '/live_p/full/reset') in full.grants
    assert ('topic', 'subscribe', '/emergency_stop') in full.grants
    assert ('service', 'reply', '/live_p/full/get_parameters') in full.grants  # base
    text = write_policy(policy)
    assert '<actions execute="ALLOW">\n            <action>~/fibonacci</action>' in text
    # what is not observed is listed, not silently dropped
    assert '/live_p/_hidden' not in live.nodes and policy.profile('/live_p/_hidden') is None
    assert '/live_p/_hidden: a hidden node, left out' in live.unobserved


def test_live_cli_writes_the_policy(graph, tmp_path):
    out = tmp_path / 'live.xml'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'policy', '--live', '--timeout', '15', '--settle', '8',
                             '-o', str(out)], cwd=REPO, text=True, capture_output=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert '<profile ns="/live_p" node="fib_client">' in out.read_text()
    assert 'nodl policy: not observed: /live_p/_hidden: a hidden node, left out' in result.stderr
