"""The structure SROS 2's policy.xsd requires, checked in Python."""

import pytest

from nodl.policy.schema_check import check_policy_text

GOOD = '''<?xml version="1.0" encoding="UTF-8"?>
<policy version="0.2.0" xmlns:xi="http://www.w3.org/2001/XInclude">
  <enclaves>
    <enclave path="/a">
      <profiles type="x">
        <profile ns="/" node="a">
          <topics publish="ALLOW" subscribe="DENY"><topic>chatter</topic></topics>
          <services reply="ALLOW"><service>~/s</service></services>
          <actions call="ALLOW"><action>/fib</action></actions>
          <topics subscribe="ALLOW"><topic>/x</topic></topics>
        </profile>
        <metadata><anything at="all"/></metadata>
      </profiles>
    </enclave>
  </enclaves>
</policy>
'''


def test_a_valid_policy_passes():
    assert check_policy_text(GOOD) == []


@pytest.mark.parametrize('old, new, expected', [
    ('version="0.2.0"', 'version="0.1.0"', "policy version '0.1.0' is not supported"),
    ('<topics publish="ALLOW" subscribe="DENY"><topic>chatter</topic></topics>',
     '<params publish="ALLOW"><topic>chatter</topic></params>', '<params> is not allowed in <profile>'),
    ('<topics subscribe="ALLOW">', '<topics subscribe="YES">', "subscribe='YES' is not a rule qualifier"),
    ('<services reply="ALLOW">', '<services publish="ALLOW">', "<services> has no attribute 'publish'"),
    ('<profile ns="/" node="a">', '<profile ns="/">', "<profile> needs the attribute 'node'"),
    ('<enclave path="/a">', '<enclave>', "<enclave> needs the attribute 'path'"),
    ('<actions call="ALLOW"><action>/fib</action></actions>', '<actions call="ALLOW"></actions>',
     '<actions> needs at least one <action>'),
    ('<metadata><anything at="all"/></metadata>', '<metadata/><profile ns="/" node="b"/>',
     '<profile> after <metadata>'),
    ('<topic>chatter</topic>', '<topic>chatter<b/></topic>', '<b> is not allowed in <topic>'),
    ('<policy version="0.2.0"', '<polcy version="0.2.0"', 'starts with <policy>'),
])
def test_each_violation_is_found_with_its_place(old, new, expected):
    text = GOOD.replace(old, new, 1)
    if old.startswith('<policy'):
        text = text.replace('</policy>', '</polcy>')
    found = check_policy_text(text, 'p.xml')
    assert any(expected in d.message for d in found), found
    assert all(d.code == 'NODL606' and d.file == 'p.xml' and d.line > 0 for d in found)


def test_empty_enclaves_and_doctype_are_rejected():
    found = check_policy_text('<policy version="0.2.0"><enclaves/></policy>')
    assert [d.message for d in found] == ['<enclaves> needs at least one <enclave>']
    bomb = '<?xml version="1.0"?><!DOCTYPE p [<!ENTITY a "aaaa">]><policy version="0.2.0"/>'
    assert [d.code for d in check_policy_text(bomb)] == ['NODL013']
