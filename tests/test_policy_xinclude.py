"""XInclude in hand-written policies, expanded as SROS 2 expands it before it reads a policy."""

import json
import shutil
from pathlib import Path

import pytest

from nodl.policy.check import check_policy_file, granted_names
from nodl.policy.generate import policy_for_instances
from nodl.policy.names import dds_topics
from nodl.policy.schema_check import check_policy_structure, read_policy
from nodl.policy.targets import Definition, instances_from_definitions

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


# --- hostile policies: bounded in count, size and place -------------------------------

BOMB = POLICY.parent / 'policy' / 'xinclude_bomb' / 'bomb.policy.xml'


def _structure_in_bounded_child(path: Path) -> dict:
    from bounded_child import run_bounded

    return run_bounded(
        'from pathlib import Path\nfrom nodl.policy.schema_check import check_policy_structure, read_policy',
        f'''
        found = check_policy_structure(read_policy(Path({str(path)!r})))
        out = [[d.code, d.file, d.line, d.column, d.message] for d in found]
        ''', megabytes=1024)


def test_an_include_bomb_stops_at_1000_includes_with_one_located_error():
    """10 levels of files each including the next 10 times (10^10 leaves): one NODL614 at the
    1,001st include, in bounded time and memory (a child limited to 1 GiB)."""
    from nodl.policy.xinclude import MAX_INCLUDES

    got = _structure_in_bounded_child(BOMB)
    assert MAX_INCLUDES == 1000
    # depth first: 10 includes down to level 10, then 9 more there, ... the 1,001st is in level9.xml
    assert [d[:4] for d in got['out']] == [['NODL614', str(BOMB.parent / 'level9.xml'), 6, 3]], got
    assert 'more than 1,000 includes' in got['out'][0][4]
    assert got['seconds'] < 5.0 and got['peak_mb'] < 400, got


def test_exactly_1000_includes_are_expanded(tmp_path):
    (tmp_path / 'one.xml').write_text('<profile><topics publish="ALLOW"><topic>t</topic></topics></profile>')

    def policy(count: int) -> Path:
        path = tmp_path / f'p{count}.xml'
        path.write_text('<policy version="0.2.0" xmlns:xi="http://www.w3.org/2001/XInclude"><enclaves>'
                        '<enclave path="/a"><profiles><profile ns="/" node="a">\n'
                        + '<xi:include href="one.xml" xpointer="xpointer(/profile/*)"/>\n' * count
                        + '</profile></profiles></enclave></enclaves></policy>\n')
        return path

    parsed = read_policy(policy(1000))
    assert check_policy_structure(parsed) == []
    assert len(parsed.tree.root.children[0].children[0].children[0].children[0].children) == 1000
    problems = check_policy_structure(read_policy(policy(1001)))
    assert [(d.code, d.line) for d in problems] == [('NODL614', 1002)]


def test_included_text_is_bounded_to_10_mb_in_all(tmp_path, monkeypatch):
    """Each include counts its whole file, every time: past the total, one NODL615 at the
    include that passes it.  (Checked here with the limit lowered to 10,000 characters: 10 MB
    of policy XML takes seconds to read, as a 10 MB policy file itself does.)"""
    from nodl.policy import xinclude

    assert xinclude.MAX_INCLUDED_BYTES == 10 * 1024 * 1024
    monkeypatch.setattr(xinclude, 'MAX_INCLUDED_BYTES', 10_000)
    big = f'<profile><topics publish="ALLOW">{"<topic>t</topic>" * 59}</topics></profile>    '
    assert len(big) == 1000
    (tmp_path / 'big.xml').write_text(big)
    policy = tmp_path / 'p.xml'
    policy.write_text('<policy version="0.2.0" xmlns:xi="http://www.w3.org/2001/XInclude"><enclaves>\n'
                      + ''.join(f'<enclave path="/e{i}"><profiles><profile ns="/" node="n{i}">'
                                '<xi:include href="big.xml" xpointer="xpointer(/profile/*)"/>'
                                '</profile></profiles></enclave>\n' for i in range(12))
                      + '</enclaves></policy>\n')
    problems = check_policy_structure(read_policy(policy))
    # 10 includes make exactly 10,000 characters; the 11th (line 12) passes the limit
    assert [(d.code, d.file, d.line) for d in problems] == [('NODL615', str(policy), 12)]
    assert 'more than 10,000 characters' in problems[0].message


@pytest.mark.parametrize('href', ['../outside.xml', 'sub/../../outside.xml', '/etc/hostname', 'link.xml',
                                  'linked_folder/inner.xml'])
def test_an_href_outside_the_including_files_folder_is_refused(tmp_path, href):
    inside = tmp_path / 'policies'
    (inside / 'sub').mkdir(parents=True)
    outside_folder = tmp_path / 'elsewhere'
    outside_folder.mkdir()
    grant = '<profile><topics publish="ALLOW"><topic>secret</topic></topics></profile>'
    (tmp_path / 'outside.xml').write_text(grant)
    (outside_folder / 'inner.xml').write_text(grant)
    (inside / 'link.xml').symlink_to(tmp_path / 'outside.xml')
    (inside / 'linked_folder').symlink_to(outside_folder)
    policy = inside / 'p.xml'
    policy.write_text('<policy version="0.2.0" xmlns:xi="http://www.w3.org/2001/XInclude"><enclaves>'
                      '<enclave path="/a"><profiles><profile ns="/" node="a">\n'
                      f'  <xi:include href="{href}" xpointer="xpointer(/profile/*)"/>\n'
                      '</profile></profiles></enclave></enclaves></policy>\n')
    problems = check_policy_structure(read_policy(policy))
    assert [(d.code, d.file, d.line, d.column) for d in problems] == [('NODL616', str(policy), 2, 3)]
    assert 'outside the folder of the including file' in problems[0].message
    names, _ = granted_names(read_policy(policy))
    assert '/secret' not in {g.name for g in names}


def test_an_href_inside_the_folder_through_dot_dot_or_a_link_is_followed(tmp_path):
    (tmp_path / 'common' / 'deeper').mkdir(parents=True)
    (tmp_path / 'common' / 'deeper' / 'g.xml').write_text(
        '<profile><topics publish="ALLOW"><topic>t</topic></topics></profile>')
    (tmp_path / 'alias.xml').symlink_to(tmp_path / 'common' / 'deeper' / 'g.xml')
    policy = tmp_path / 'p.xml'
    policy.write_text('<policy version="0.2.0" xmlns:xi="http://www.w3.org/2001/XInclude"><enclaves>'
                      '<enclave path="/a"><profiles><profile ns="/" node="a">\n'
                      '  <xi:include href="common/../common/deeper/g.xml" xpointer="xpointer(/profile/*)"/>\n'
                      '  <xi:include href="alias.xml" xpointer="xpointer(/profile/*)"/>\n'
                      '</profile></profiles></enclave></enclaves></policy>\n')
    parsed = read_policy(policy)
    assert check_policy_structure(parsed) == []
    names, _ = granted_names(parsed)
    assert [g.name for g in names] == ['/t', '/t']


def test_a_nested_include_is_bounded_by_its_own_folder(tmp_path):
    """common/base.xml may include common/base/x.xml, not ../secret.xml (beside the policy)."""
    (tmp_path / 'common').mkdir()
    (tmp_path / 'secret.xml').write_text('<profile><topics publish="ALLOW"><topic>s</topic></topics></profile>')
    base = tmp_path / 'common' / 'base.xml'
    base.write_text('<profile xmlns:xi="http://www.w3.org/2001/XInclude">\n'
                    '  <xi:include href="../secret.xml" xpointer="xpointer(/profile/*)"/>\n</profile>\n')
    policy = tmp_path / 'p.xml'
    policy.write_text('<policy version="0.2.0" xmlns:xi="http://www.w3.org/2001/XInclude"><enclaves>'
                      '<enclave path="/a"><profiles><profile ns="/" node="a">\n'
                      '  <xi:include href="common/base.xml" xpointer="xpointer(/profile/*)"/>\n'
                      '</profile></profiles></enclave></enclaves></policy>\n')
    problems = check_policy_structure(read_policy(policy))
    assert [(d.code, d.file, d.line) for d in problems] == [('NODL616', str(base), 2)]
