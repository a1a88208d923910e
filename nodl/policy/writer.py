"""Writing a policy document: deterministic, canonically ordered, with comments that trace.

Enclaves are ordered by path, profiles by namespace and node, permission
lists as SROS 2 orders them (actions, services, topics; offering access
first), names alphabetically; one permission list per access, so that a
changed grant is a one-line diff.  Each name carries a comment saying what
declares it (definition file and line, layer, launch entry).

:func:`write_policy` refuses to return a document SROS 2 would reject.  The
structure of ``policy.xsd`` (:mod:`nodl.policy.schema_check`) is
checked while the document is written: the elements, attributes and
permission lists come from the model's one table, so what can go wrong is
an element left empty (no enclave, an enclave without profiles: NODL606)
and text XML cannot hold (a character XML 1.0 forbids: NODL012, a lone
surrogate: NODL002), found by one scan of the finished text; every name is
checked to resolve, as SROS 2 resolves it, to the final name it grants.
Comments are for people: a control or bidi character in them (a file name,
a note) is written as a visible escape (``\\x1b``, ``\\u202e``).  A name (an
enclave path, a profile's ``ns`` or ``node``, a granted name) is what SROS 2
grants: one holding a control character (C1, DEL, CR) or a Trojan Source bidi
control is refused, as text XML cannot hold is (NODL223, NODL224 at it): the
document never carries one raw.
Reading the document back (:func:`~nodl.policy.schema_check.check_policy_text`)
finds nothing more; the tests hold the two to agreeing.
"""

from __future__ import annotations

import re

from nodl.diagnostics import Diagnostic, Severity
from nodl.policy.model import POLICY_VERSION, Policy, Profile, permission_list
from nodl.policy.names import resolve_policy_name, written_name, written_name_error
from nodl.system.gc_tuning import batch_collection
from nodl.text_safety import (
    UNSAFE,
    describe_character,
    is_bidi_control,
    one_line,
    visible,
)

__all__ = ['write_policy', 'PolicyNotWritable', 'xml_text', 'xml_attribute', 'xml_comment']


#: A character XML 1.0 does not allow in a document (its ``Char`` production), lone surrogates
#: included.
_NOT_XML = re.compile('[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]')


class PolicyNotWritable(ValueError):
    """The policy would be rejected by SROS 2; ``diagnostics`` say why (a bug or a bad model)."""

    def __init__(self, diagnostics: list[Diagnostic]) -> None:
        self.diagnostics = diagnostics
        super().__init__('; '.join(d.message for d in diagnostics))


def xml_text(text: str) -> str:
    """``text`` escaped for element content."""
    return text.replace('&', '&amp;').replace('<', '&lt;').replace('>', '&gt;')


def xml_attribute(text: str) -> str:
    """``text`` escaped for a double-quoted attribute value."""
    return xml_text(text).replace('"', '&quot;').replace('\n', '&#10;').replace('\t', '&#9;')


def xml_comment(text: str) -> str:
    """``<!-- text -->`` with what a comment cannot hold (``--``, a final ``-``, line breaks) defused,
    control and bidi characters written as visible escapes."""
    text = one_line(text)
    while '--' in text:
        text = text.replace('--', '- -')
    if text.endswith('-'):
        text += ' '
    return f'<!-- {text} -->'


def _profile_lines(profile: Profile, problems: list[Diagnostic]) -> list[str]:
    out = []
    head = [profile.fqn]
    if profile.definition:
        head.append(f'definition {profile.definition}')
    if profile.base:
        head.append(f'base entities as {profile.base} creates them')
    if profile.launch:
        head.append(f'launched at {profile.launch}')
    out.append('        ' + xml_comment(head[0] + (': ' + '; '.join(head[1:]) if head[1:] else '')))
    for note in profile.notes:
        out.append('        ' + xml_comment(note))
    out.append(f'        <profile ns="{xml_attribute(profile.namespace)}" '
               f'node="{xml_attribute(profile.node)}">')
    current: tuple[str, str] | None = None
    kind = None
    for grant in profile.sorted_grants():
        if (grant.communication, grant.access) != current:
            if kind is not None:
                out.append(f'          </{kind.element}>')
            current = (grant.communication, grant.access)
            kind = permission_list(grant.communication)
            out.append(f'          <{kind.element} {grant.access}="ALLOW">')
        assert kind is not None
        name = written_name(grant.name, profile.namespace, profile.node)
        problem = written_name_error(grant.name)
        if problem is None and resolve_policy_name(name, profile.namespace, profile.node) != grant.name:
            problem = f'{name!r} would resolve to another name'
        if problem is not None:
            problems.append(Diagnostic(Severity.ERROR, f'{profile.fqn}: {grant.communication} '
                                       f'{grant.name!r} cannot be written: {problem}', code='NODL602'))
            continue
        comment = '; '.join(str(s) for s in grant.sources)
        line = f'            <{kind.item}>{xml_text(name)}</{kind.item}>'
        out.append(line + (' ' + xml_comment(comment) if comment else ''))
    if kind is not None:
        out.append(f'          </{kind.element}>')
    out.append('        </profile>')
    return out


def write_policy(policy: Policy) -> str:
    """The policy document as text (UTF-8 XML); :class:`PolicyNotWritable` if SROS 2 would reject it."""
    with batch_collection():  # the lines live until the end
        return _write_policy(policy)


_GENERATED = '<generated policy>'


def _structure_error(message: str, line: int, column: int) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, (), _GENERATED, line, column, code='NODL606')


def _write_policy(policy: Policy) -> str:
    problems: list[Diagnostic] = []
    lines = ['<?xml version="1.0" encoding="UTF-8"?>']
    for note in policy.notes:
        lines.append(xml_comment(note))
    lines.append(f'<policy version="{POLICY_VERSION}">')
    lines.append('  <enclaves>')
    enclaves = policy.sorted_enclaves()
    if not enclaves:
        problems.append(_structure_error('<enclaves> needs at least one <enclave>', len(lines), 3))
    for enclave in enclaves:
        lines.append(f'    <enclave path="{xml_attribute(enclave.path)}">')
        lines.append('      <profiles>')
        profiles = enclave.sorted_profiles()
        if not profiles:
            problems.append(_structure_error('<profiles> needs at least one <profile>', len(lines), 7))
        for profile in profiles:
            lines.extend(_profile_lines(profile, problems))
        lines.append('      </profiles>')
        lines.append('    </enclave>')
    lines.append('  </enclaves>')
    lines.append('</policy>')
    text = '\n'.join(lines) + '\n'
    if not problems:
        problems = _text_problems(text)
    if problems:
        raise PolicyNotWritable(problems)
    return text


def _text_problems(text: str) -> list[Diagnostic]:
    """The first character of ``text`` that XML 1.0 does not allow, as a diagnostic (one scan);
    else the first control or bidi character (only names can hold one: comments escape them)."""
    found = _NOT_XML.search(text)
    if found is None:
        return _unsafe_name(text)
    at = found.start()
    line = text.count('\n', 0, at) + 1
    column = at - (text.rfind('\n', 0, at) + 1) + 1
    char = ord(text[at])
    if 0xD800 <= char <= 0xDFFF:
        return [Diagnostic(Severity.ERROR, f'the document would contain a lone surrogate '
                           f'(U+{char:04X}), which is not valid Unicode text', (), _GENERATED, line,
                           column, code='NODL002')]
    return [Diagnostic(Severity.ERROR, f'malformed XML: the document would contain the character '
                       f'U+{char:04X}, which XML does not allow', (), _GENERATED, line, column,
                       code='NODL012')]


def _unsafe_name(text: str) -> list[Diagnostic]:
    """The first control character (NODL223) or Trojan Source bidi control (NODL224) of the
    written ``text``, as an error at it: SROS 2 would grant the name as it is, and a reviewer
    would not see it (or see it reordered)."""
    found = UNSAFE.search(text)
    if found is None:
        return []
    at = found.start()
    line = text.count('\n', 0, at) + 1
    start = text.rfind('\n', 0, at) + 1
    end = text.find('\n', at)
    char = text[at]
    shown = visible(text[start:end if end >= 0 else len(text)].strip(), one_line=True)
    if is_bidi_control(char):
        what = ('a bidirectional control (Trojan Source: the policy would read differently from '
                'what it grants)')
        code = 'NODL224'
    else:
        what, code = 'a control character', 'NODL223'
    return [Diagnostic(Severity.ERROR, f'a name in the policy holds {describe_character(char)}, '
                       f'{what} ({shown}); no policy is written: fix the name where it comes from '
                       '(the launch file, the node)', (), _GENERATED, line, at - start + 1, code=code)]
