"""Writing a policy: never a document SROS 2 would reject; everything from definitions escaped."""

import pytest

from nodl.policy.model import Policy, Profile, Source
from nodl.policy.schema_check import check_policy_text
from nodl.policy.writer import PolicyNotWritable, write_policy, xml_comment
from nodl.text_safety import one_line


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


def _refusal(policy):
    with pytest.raises(PolicyNotWritable) as raised:
        write_policy(policy)
    return [(d.code, d.line, d.column) for d in raised.value.diagnostics]


def _one_node(namespace='/', node='n', path='/n', notes=(), what='declared'):
    policy = Policy(notes=list(notes))
    profile = Profile(namespace, node)
    profile.grant('topic', 'publish', '/x', Source(what, 'f.nodl.yaml:1:1'))
    policy.enclave(path).profiles.append(profile)
    return policy


# (no white space among them: a comment turns that into a space; a control character in a
# comment is written as a visible escape: test_comments_show_control_and_bidi_characters)
@pytest.mark.parametrize('bad, where', [
    *[(bad, where) for bad in ('\x01', '\x08', '\ufffe', '\ud800') for where in ('node', 'path')],
    *[(bad, where) for bad in ('\ufffe', '\ud800') for where in ('note', 'source')]])
def test_what_the_writer_refuses_is_what_reading_the_document_back_finds(bad, where):
    """Text is checked in one scan of the written document, not by reading it back: the finding
    (code, line, column) is the one reading the document back gives."""
    def policy(text):
        return _one_node(notes=[f'a {text} note'] if where == 'note' else [],
                         node=f'n{text}' if where == 'node' else 'n',
                         path=f'/p{text}' if where == 'path' else '/n',
                         what=f'declared {text}' if where == 'source' else 'declared')

    # (the writer's comments show a control character as an escape, a name holds it as it is)
    document = '\n'.join(line.replace('Q9Z', one_line(bad) if '<!--' in line else bad)
                          for line in write_policy(policy('Q9Z')).split('\n'))
    # (reading back also reports the elements a broken document leaves unfinished)
    expected = [(d.code, d.line, d.column) for d in check_policy_text(document)
                if d.code in ('NODL002', 'NODL012')]
    assert len(expected) == 1
    assert _refusal(policy(bad)) == expected


def test_empty_elements_are_refused_while_writing():
    empty_enclave = Policy()
    empty_enclave.enclave('/a')
    assert _refusal(empty_enclave) == [('NODL606', 5, 7)]
    assert _refusal(Policy()) == [('NODL606', 3, 3)]


def test_a_large_policy_is_written_and_reads_back_clean():
    policy = Policy()
    for i in range(300):
        profile = Profile(f'/g{i % 7}', f'n{i}')
        profile.grant('topic', 'publish', f'/g{i % 7}/out_{i}', Source('publisher', f'f{i}.nodl.yaml:3:5'))
        profile.grant('service', 'reply', f'/g{i % 7}/n{i}/get', Source('server'))
        policy.enclave(f'/g{i % 7}/n{i}' if i % 3 else '/shared').profiles.append(profile)
    text = write_policy(policy)
    assert check_policy_text(text) == []
    assert text.count('<profile ns=') == 300


@pytest.mark.parametrize('bad', ['\x01', '\x1b', '\x9b', '\u202e', '\u2066'])
def test_comments_show_control_and_bidi_characters(bad):
    """Text of a comment (a note, a launch file's name, a source) holding a control or bidi
    character is written as a visible escape: the policy is written, and carries none raw."""
    escape = f'\\x{ord(bad):02x}' if ord(bad) < 0x100 else f'\\u{ord(bad):04x}'
    policy = _one_node(notes=[f'a {bad} note'], what=f'declared in dir{bad}x')
    policy.enclaves[0].profiles[0].launch = f'launch{bad}.xml:1:2'
    text = write_policy(policy)
    assert bad not in text and text.count(escape) == 3
    assert check_policy_text(text) == []


@pytest.mark.parametrize('bad, code', [('\u202e', 'NODL224'), ('\u2069', 'NODL224'),
                                       ('\x85', 'NODL223'), ('\x9b', 'NODL223'), ('\x7f', 'NODL223')])
@pytest.mark.parametrize('where', ['node', 'namespace', 'path'])
def test_a_name_holding_a_control_or_bidi_character_is_refused(bad, code, where):
    """A profile's node or namespace, or an enclave path, holding a bidi control or a control
    character XML could carry (C1, DEL) is refused at the character: the written policy never
    holds one raw (a granted name is refused earlier, NODL602)."""
    policy = _one_node(namespace=f'/a{bad}' if where == 'namespace' else '/',
                       node=f'n{bad}' if where == 'node' else 'n',
                       path=f'/p{bad}' if where == 'path' else '/n')
    with pytest.raises(PolicyNotWritable) as raised:
        write_policy(policy)
    (found,) = raised.value.diagnostics
    assert found.code == code and found.line > 1 and found.column > 1
    assert bad not in found.message and 'no policy is written' in found.message
    clean = write_policy(_one_node(namespace='/a' if where == 'namespace' else '/'))
    assert found.line == [i for i, line in enumerate(clean.splitlines(), 1)
                          if (' ns="/a"' if where == 'namespace' else '<profile ' if where == 'node'
                              else '<enclave ') in line][0]
