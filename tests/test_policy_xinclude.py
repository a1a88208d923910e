"""XInclude in hand-written policies, expanded as SROS 2 expands it before it reads a policy."""

import json
import shutil
from pathlib import Path

import pytest

from nodl_schema.policy.check import check_policy_file, granted_names
from nodl_schema.policy.generate import policy_for_instances
from nodl_schema.policy.names import dds_topics
from nodl_schema.policy.schema_check import check_policy_structure, read_policy
from nodl_schema.policy.targets import Definition, instances_from_definitions

POLICY = Path(__file__).parent / 'fixtures' / 'policy'
INCLUDING = POLICY / 'xinclude' / 'talker_listener.policy.xml'


@pytest.fixture
def expected():
    instances, _ = instances_from_definitions(
        [Definition(file=str(POLICY / 'talker.nodl.yaml')), Definition(file=str(POLICY / 'listener.nodl.yaml'))])
    return policy_for_instances(instances).policy


def test_same_dds_topics_as_sros2_after_its_xinclude():
    """Includes nest (a profile including files that include files), under two XInclude
    namespaces and any prefix, at profile and enclave level; the DDS topics equal those
    sros2 0.13.0 makes of the file (lxml xinclude, policy.xsd, dds/permissions.xsl)."""
    parsed = read_policy(INCLUDING)
    assert check_policy_structure(parsed) == []
    names, _ = granted_names(parsed)
    got: dict = {}
    for g in names:
        sides = got.setdefault(g.enclave, {'publish': set(), 'subscribe': set()})
        for side, topic in dds_topics(g.communication, g.access, g.name):
            sides[side].add(topic)
    oracle = json.loads((POLICY / 'xinclude' / 'talker_listener.dds.json').read_text())
    assert {e: {k: sorted(v) for k, v in s.items()} for e, s in got.items()} == oracle


def test_an_including_policy_is_checked_and_findings_name_the_included_file(expected, tmp_path):
    assert check_policy_file(INCLUDING, expected) == []
    copy = tmp_path / 'xinclude'
    shutil.copytree(INCLUDING.parent, copy)
    logging = copy / 'common' / 'base' / 'logging.xml'
    logging.write_text(logging.read_text().replace('<topic>rosout</topic>',
                                                   '<topic>rosout</topic>\n    <topic>/cmd_vel</topic>'))
    found = check_policy_file(copy / INCLUDING.name, expected)
    # included by both profiles: an extra grant for each node, at its place in logging.xml
    assert [(d.code, d.file, d.line) for d in found] == [('NODL605', str(logging), 5)] * 2
    assert {d.message.split(' is granted')[0] for d in found} == {'extra: /talker', 'extra: /listener'}


@pytest.mark.parametrize('include, message', [
    ('<xi:include href="none.xml"/>', 'cannot read none.xml'),
    ('<xi:include href="https://example.com/base.xml"/>', 'a local file'),
    ('<xi:include href="base.xml" xpointer="element(/1/2)"/>', 'is not supported'),
    ('<xi:include href="base.xml" parse="text"/>', "parse='text'"),
    ('<xi:include href="base.xml"><xi:fallback/></xi:include>', '<fallback>'),
    ('<xi:include href="p.xml" xpointer="xpointer(/policy/enclaves/*)"/>', 'include cycle'),
])
def test_unsupported_or_broken_includes_are_reported_at_the_include(tmp_path, include, message):
    (tmp_path / 'base.xml').write_text('<profile><topics publish="ALLOW"><topic>a</topic></topics></profile>')
    policy = tmp_path / 'p.xml'
    policy.write_text('<policy version="0.2.0" xmlns:xi="http://www.w3.org/2001/XInclude"><enclaves>\n'
                      f'  {include}\n'
                      '  <enclave path="/a"><profiles><profile ns="/" node="a"/></profiles></enclave>\n'
                      '</enclaves></policy>\n')
    problems = check_policy_structure(read_policy(policy))
    assert [(d.code, d.file, d.line, d.column) for d in problems] == [('NODL606', str(policy), 2, 3)]
    assert message in problems[0].message


def test_an_include_element_outside_the_xinclude_namespace_is_an_unknown_element(tmp_path):
    policy = tmp_path / 'p.xml'
    policy.write_text('<policy version="0.2.0" xmlns:xi="http://example.com/not-xinclude"><enclaves>'
                      '<xi:include href="p.xml"/></enclaves></policy>')
    problems = check_policy_structure(read_policy(policy))
    assert any('<xi:include> is not allowed in <enclaves>' in d.message for d in problems)
