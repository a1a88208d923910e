"""Writing a policy: never a document SROS 2 would reject; everything from definitions escaped."""

import pytest

from nodl_schema.policy.model import Policy, Profile, Source
from nodl_schema.policy.schema_check import check_policy_text
from nodl_schema.policy.writer import PolicyNotWritable, write_policy, xml_comment


def _policy(*grants, namespace='/robot', node='driver'):
    policy = Policy(notes=['a note'])
    profile = Profile(namespace, node)
    for communication, access, name in grants:
        profile.grant(communication, access, name, Source('declared', 'f.nodl.yaml:3:5'))
    policy.enclave(f'{namespace.rstrip("/")}/{node}').profiles.append(profile)
    return policy


def test_a_valid_policy_is_written_and_checks_clean():
    text = write_policy(_policy(('topic', 'publish', '/robot/scan'), ('action', 'call', '/nav/go')))
    assert check_policy_text(text) == []
    assert '<topic>scan</topic>' in text and '<action>/nav/go</action>' in text


@pytest.mark.parametrize('name, why', [
    ('/robot/sc an', 'must not contain characters'),    # malformed: rmw would reject it
    ('/robot/scan*', 'pattern'),                         # DDS would read it as a pattern
    ('/robot/[ab]', 'pattern'),
    ('robot/scan', 'absolute'),                          # not a final name
    ('/robot/scan/', 'must not end'),
])
def test_a_name_sros2_would_misread_is_never_written(name, why):
    with pytest.raises(PolicyNotWritable) as raised:
        write_policy(_policy(('topic', 'publish', '/robot/ok'), ('topic', 'subscribe', name)))
    assert [d.code for d in raised.value.diagnostics] == ['NODL602']
    assert why in str(raised.value)


def test_an_unknown_permission_kind_cannot_even_be_granted():
    with pytest.raises(ValueError, match='unknown permission kind'):
        _policy(('parameter', 'publish', '/robot/x'))
    with pytest.raises(ValueError, match="unknown services permission 'publish'"):
        _policy(('service', 'publish', '/robot/x'))


def test_an_empty_policy_is_not_written():
    """policy.xsd needs at least one enclave."""
    with pytest.raises(PolicyNotWritable) as raised:
        write_policy(Policy())
    assert {d.code for d in raised.value.diagnostics} == {'NODL606'}


def test_text_from_definitions_is_escaped():
    policy = _policy(('topic', 'publish', '/robot/scan'))
    profile = policy.enclaves[0].profiles[0]
    profile.definition = 'dir--x/<a & "b">-'
    profile.notes.append('ends with a dash -')
    profile.grants[('topic', 'publish', '/robot/scan')].sources.append(
        Source("publisher 'scan' -->", 'we--ird&<x>.nodl.yaml:1:2'))
    text = write_policy(policy)
    assert check_policy_text(text) == []   # still well-formed: comments cannot be closed early
    comments = [line.split('<!--', 1)[1] for line in text.splitlines() if '<!--' in line]
    assert all(c.count('--') == 0 or c.rstrip().endswith('-->') and c[:-4].count('--') == 0
               for c in comments)
    assert xml_comment('a -- b -') == '<!-- a - - b -  -->'
