"""--check: an existing policy against the system; missing and extra grants, placed in the file."""

from pathlib import Path

import pytest

from nodl.policy.check import check_parsed_policy, check_policy_file
from nodl.policy.enclaves import EnclaveMapping
from nodl.policy.generate import policy_for_instances
from nodl.policy.schema_check import read_policy
from nodl.policy.targets import Definition, instances_from_definitions
from nodl.policy.writer import write_policy

POLICY = Path(__file__).parent / 'fixtures' / 'policy'


@pytest.fixture
def expected():
    instances, _ = instances_from_definitions(
        [Definition(file=str(POLICY / 'talker.nodl.yaml')), Definition(file=str(POLICY / 'listener.nodl.yaml'))])
    return policy_for_instances(instances).policy


def _check(text, expected):
    return check_parsed_policy(read_policy(text, 'p.xml'), expected)


def _line(text, needle):
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


def test_the_generated_policy_passes(expected):
    assert _check(write_policy(expected), expected) == []


def test_one_missing_and_one_extra_grant_are_exactly_reported(expected):
    text = write_policy(expected)
    text = text.replace('            <topic>chatter</topic> <!-- publisher',
                        '            <topic>chatting</topic> <!-- publisher')
    found = _check(text, expected)
    assert [(d.code, d.line) for d in found] == [
        ('NODL604', _line(text, '<profile ns="/" node="talker">')),
        ('NODL605', _line(text, '<topic>chatting</topic>'))]
    assert 'topic publish on /chatter' in found[0].message and '/chatting' in found[1].message


def test_names_compare_by_final_name_whatever_their_form(expected):
    text = write_policy(expected).replace('<topic>chatter</topic> <!-- publisher', '<topic>/chatter</topic> <!--')
    assert _check(text, expected) == []


def test_white_space_around_a_name_is_part_of_it_as_for_sros2(expected):
    """SROS 2's transform takes the element's text as it is: `<topic> chatter\n</topic>` grants
    'rt/ chatter\n' (checked with sros2's permissions.xsl), so the node would lack /chatter."""
    text = write_policy(expected).replace('<topic>chatter</topic> <!-- publisher',
                                          '<topic> chatter\n            </topic> <!-- publisher')
    found = _check(text, expected)
    assert [(d.code, d.line) for d in found] == [
        ('NODL604', _line(text, '<profile ns="/" node="talker">')), ('NODL605', _line(text, '> chatter'))]
    assert 'white space included' in found[1].message and '/chatter' in found[0].message


def test_wildcards_deny_and_profiles(expected):
    text = write_policy(expected)
    widened = text.replace('<topic>chatter</topic> <!-- publisher', '<topic>/chat*</topic> <!--')
    assert [(d.code, d.severity.value) for d in _check(widened, expected)] == [('NODL603', 'warning')]
    denied = text.replace('<topics subscribe="ALLOW">', '<topics subscribe="DENY">')
    assert [d.code for d in _check(denied, expected)] == ['NODL604']
    no_listener = text.replace('node="listener"', 'node="lister"')
    assert sorted(d.code for d in _check(no_listener, expected)) == ['NODL607', 'NODL608']


def test_a_profile_in_another_enclave_is_misplaced(expected):
    """Permissions belong to enclaves: the talker started with its own enclave would get none
    of the grants written for it under the listener's enclave (and the listener would)."""
    text = write_policy(expected)
    swapped = text.replace('<enclave path="/talker">', '<enclave path="/tmp">').replace(
        '<enclave path="/listener">', '<enclave path="/talker">').replace(
        '<enclave path="/tmp">', '<enclave path="/listener">')
    found = _check(swapped, expected)
    assert [(d.code, d.line) for d in found] == [
        ('NODL609', _line(swapped, '<profile ns="/" node="listener">')),
        ('NODL609', _line(swapped, '<profile ns="/" node="talker">'))]
    assert "the profile of /listener is in enclave '/talker'" in found[0].message
    # the same layout is right when the system is started that way
    instances, _ = instances_from_definitions(
        [Definition(file=str(POLICY / 'talker.nodl.yaml')), Definition(file=str(POLICY / 'listener.nodl.yaml'))])
    crossed = EnclaveMapping('m.yaml', [('/talker', ['/listener'], (1, 1)), ('/listener', ['/talker'], (2, 1))])
    assert _check(swapped, policy_for_instances(instances, enclaves=crossed).policy) == []


def test_structure_problems_come_alone(expected, tmp_path):
    bad = tmp_path / 'bad.xml'
    bad.write_text('<policy version="0.1"><enclaves/></policy>')
    assert {d.code for d in check_policy_file(bad, expected)} == {'NODL606'}
    with pytest.raises(OSError):
        check_policy_file(tmp_path / 'missing.xml', expected)
