"""Whole policies for small systems: golden files, the round trip of final names, gaps."""

from pathlib import Path

import pytest

from nodl.composition.entities import Location
from nodl.policy.check import granted_names
from nodl.policy.enclaves import load_enclave_mapping
from nodl.policy.generate import MissingNode, policy_for_instances
from nodl.policy.model import ACCESS_OF_KIND
from nodl.policy.schema_check import read_policy
from nodl.policy.targets import Definition, instances_from_definitions
from nodl.policy.writer import write_policy

REPO = Path(__file__).parent.parent
POLICY = Path('tests/fixtures/policy')
EXPECTED = REPO / POLICY / 'expected'

#: name -> (definition files, --name values, remaps, enclaves)
SYSTEMS = {
    'talker_listener': (['talker', 'listener'], [], [], 'node'),
    'service': (['add_server', 'add_client'], [], [], 'node'),
    'action': (['fibonacci_server', 'fibonacci_client'], [], [], 'node'),
    'lifecycle': (['camera'], ['/robot/camera'], [], 'node'),
    'namespaces_remaps': (['relay', 'talker', 'listener'], ['/robot/relay', '/robot/talker', '/ui/listener'],
                          ['talker:chatter:=relay/input', 'relay:input:=~/input',
                           'listener:chatter:=/robot/output'], 'node'),
    'one_enclave': (['talker', 'listener', 'camera'], ['/robot/talker', '/robot/listener', '/robot/camera'],
                    [], 'enclaves.yaml'),
}


def _system(name):
    files, names, remaps, enclaves = SYSTEMS[name]
    instances, problems = instances_from_definitions(
        [Definition(file=str(POLICY / f'{f}.nodl.yaml')) for f in files], names, remaps=remaps)
    assert problems == []
    if enclaves.endswith('.yaml'):
        enclaves, _ = load_enclave_mapping(str(POLICY / enclaves))
    result = policy_for_instances(instances, enclaves=enclaves, notes=[f'test system {name}'])
    # enclaves.yaml also lists /robot/lidar, which these systems do not have (NODL613, a warning)
    assert [d for d in result.diagnostics if d.code != 'NODL613'] == []
    return instances, result.policy


@pytest.fixture(autouse=True)
def _in_repo(monkeypatch):
    monkeypatch.chdir(REPO)  # comments hold paths relative to the current directory


@pytest.mark.parametrize('name', sorted(SYSTEMS))
def test_golden_policies(name, golden):
    _, policy = _system(name)
    text = write_policy(policy)
    golden.check(text, EXPECTED / f'{name}.policy.xml')
    assert write_policy(_system(name)[1]) == text  # deterministic


def round_trip(instances, text):
    """Per node: final names granted (as SROS 2 resolves them) == declared final names + base."""
    names, _ = granted_names(read_policy(text))
    for instance in instances:
        granted = {(g.communication, g.access, g.name) for g in names if g.node == instance.fqn}
        declared = {ACCESS_OF_KIND[e.entity.kind.value] + (e.name,) for e in instance.endpoints}
        assert granted == declared, instance.fqn


@pytest.mark.parametrize('name', sorted(SYSTEMS))
def test_round_trip_of_final_names(name):
    instances, policy = _system(name)
    round_trip(instances, write_policy(policy))


@pytest.mark.parametrize('name', ['namespaces_remaps', 'one_enclave'])
def test_the_order_of_the_nodes_does_not_matter(name):
    instances, policy = _system(name)
    enclaves = SYSTEMS[name][3]
    if enclaves.endswith('.yaml'):
        enclaves, _ = load_enclave_mapping(str(POLICY / enclaves))
    reordered = policy_for_instances(reversed(instances), enclaves=enclaves, notes=[f'test system {name}'])
    assert write_policy(reordered.policy) == write_policy(policy)


def test_two_nodes_in_one_enclave_keep_their_profiles():
    _, policy = _system('one_enclave')
    assert [(e.path, p.fqn) for e, p in policy.profiles()] == [
        ('/robot/sensing', '/robot/camera'), ('/robot/talking', '/robot/listener'),
        ('/robot/talking', '/robot/talker')]


def test_missing_definitions_are_errors_or_marked_gaps():
    instances, _ = _system('talker_listener')
    gap = MissingNode('/robot/mystery', 'nothing registered for pkg exe', Location('x.launch.xml', 4, 3))
    result = policy_for_instances(instances, missing=[gap])
    assert [(d.code, d.severity.value, d.line) for d in result.diagnostics] == [('NODL601', 'error', 4)]
    assert not result.ok
    result = policy_for_instances(instances, missing=[gap], allow_missing=True)
    assert [(d.code, d.severity.value) for d in result.diagnostics] == [('NODL601', 'warning')]
    text = write_policy(result.policy)
    assert '<!-- GAP: no node definition (nothing registered for pkg exe); nothing is granted -->' in text
    assert '<profile ns="/robot" node="mystery">\n        </profile>' in text


def test_duplicate_names_and_empty_systems():
    instances, _ = _system('talker_listener')
    result = policy_for_instances(instances + instances[:1])
    assert [d.code for d in result.diagnostics] == ['NODL611']
    assert [d.code for d in policy_for_instances([]).diagnostics] == ['NODL612']
