"""Policy names: written so that SROS 2 resolves them to the final names (checked against
what SROS 2's own transform made of real generated policies, see fixtures/policy/sros2_oracle)."""

import json
from pathlib import Path

import pytest

from nodl.policy.check import granted_names
from nodl.policy.names import dds_topics, has_wildcard, resolve_policy_name, written_name, written_name_error
from nodl.policy.schema_check import read_policy

ORACLE = Path(__file__).parent / 'fixtures' / 'policy' / 'sros2_oracle'


@pytest.mark.parametrize('final, namespace, node, written', [
    ('/chatter', '/', 'talker', 'chatter'),
    ('/talker/status', '/', 'talker', '~/status'),
    ('/robot/relay/status', '/robot', 'relay', '~/status'),
    ('/robot/scan', '/robot', 'relay', 'scan'),
    ('/robot/relay', '/robot', 'relay', 'relay'),
    ('/other/scan', '/robot', 'relay', '/other/scan'),
    ('/robotics/scan', '/robot', 'relay', '/robotics/scan'),
    ('/robot/relay2/x', '/robot', 'relay', 'relay2/x'),
    ('/a/b/c', '/a', 'b', '~/c'),
])
def test_written_names_resolve_back(final, namespace, node, written):
    assert written_name(final, namespace, node) == written
    assert resolve_policy_name(written, namespace, node) == final


def test_tilde_is_node_then_rest_as_sros2_reads_it():
    # '~x' would be '/ns/nodex' for SROS 2 (not rcl's meaning): never written, but read as SROS 2 does
    assert resolve_policy_name('~x', '/ns', 'node') == '/ns/nodex'
    assert resolve_policy_name('~/x', '/ns/', 'node') == '/ns/node/x'


def test_wildcards_and_invalid_names_cannot_be_granted():
    assert has_wildcard('/scan*') and has_wildcard('/a?') and has_wildcard('/[ab]')
    assert written_name_error('/scan*') is not None
    assert written_name_error('/bad name') is not None
    assert written_name_error('/good/name') is None


def test_dds_topics_of_each_permission():
    assert dds_topics('topic', 'publish', '/chatter') == [('publish', 'rt/chatter')]
    assert dds_topics('service', 'request', '/add') == [('publish', 'rq/addRequest'),
                                                         ('subscribe', 'rr/addReply')]
    server = dds_topics('action', 'execute', '/fib')
    assert ('publish', 'rt/fib/_action/feedback') in server
    assert ('subscribe', 'rq/fib/_action/send_goalRequest') in server
    assert len(server) == 8


@pytest.mark.parametrize('name', ['relay', 'shared_enclave', 'placements'])
def test_same_dds_topics_as_sros2_transform(name):
    """Each enclave's DDS topics, computed by the toolkit from the policy, equal SROS 2's."""
    expected = json.loads((ORACLE / f'{name}.dds.json').read_text())
    parsed = read_policy(ORACLE / f'{name}.policy.xml')
    names, _ = granted_names(parsed)
    got: dict = {}
    for g in names:
        sides = got.setdefault(g.enclave, {'publish': set(), 'subscribe': set()})
        for side, topic in dds_topics(g.communication, g.access, g.name):
            sides[side].add(topic)
    assert {e: {k: sorted(v) for k, v in s.items()} for e, s in got.items()} == expected
