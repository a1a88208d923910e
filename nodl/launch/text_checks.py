"""Control characters and Trojan Source bidi controls in what a launch file gives a node.

A launch file (XML, YAML or Python) and the parameter files it gives carry text into
the ROS graph: node names and namespaces, remapping rules, parameter names and
values.  rcl carries a parameter value as it is: ``ros2 param get`` prints it to a
terminal, a node logs it, a tool writes it into a report.  So the same characters
that are errors in a definition (:mod:`nodl.validation.characters`) are
errors here, with their own codes:

* NODL221: a C0 or C1 control character (or DEL); tab and newline are ordinary text;
* NODL222: a bidirectional control of the Trojan Source set (U+202A-202E,
  U+2066-2069); LRM and RLM (U+200E, U+200F) stay allowed for right-to-left text.

A node whose name or namespace holds one is left out (as an invalid name is); a
remapping rule holding one is left out (rcl would refuse it) and said once where it
is written; a parameter name or value holding one is reported and kept (the node
would get it).  Each finding is placed at the character where the launch file writes
it (the raw character, an XML character reference, a YAML or Python escape), else at
the attribute, entry or call that gives the value (a value made by substitutions).
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.launch.errors import LaunchProblem
from nodl.launch.model import LaunchedNode, SourceLocation
from nodl.text_safety import UNSAFE, first_unsafe, line_column, offset_of, visible

if TYPE_CHECKING:
    from typing import Any

    from nodl.launch.context import LaunchContext

__all__ = ['CONTROL_CHARACTER', 'BIDI_CONTROL', 'unsafe_diagnostic', 'refuse_unsafe',
           'check_node_text', 'place_character']

#: The code of a control character in a launch file's names or values.
CONTROL_CHARACTER = 'NODL221'
#: The code of a Trojan Source bidi control in a launch file's names or values.
BIDI_CONTROL = 'NODL222'

# One escape or character reference of XML, YAML or Python, or any other character.
_TOKEN = re.compile(r'&#[xX][0-9a-fA-F]{1,8};|&#[0-9]{1,9};|\\x[0-9a-fA-F]{2}|\\u[0-9a-fA-F]{4}'
                    r'|\\U[0-9a-fA-F]{8}|\\N\{[^}\n]{1,80}\}|\\[0-7]{1,3}|\\.', re.DOTALL)
_SIMPLE = {'a': '\a', 'b': '\b', 'v': '\v', 'f': '\f', 'r': '\r', 'e': '\x1b', 'N': '\x85'}
_ATTRIBUTE = re.compile(r'[\w:.-]+\s*=\s*(["\'])')
_TEXTS: dict[str, str | None] = {}


def _decoded(token: str) -> str:
    """The character an escape or reference of :data:`_TOKEN` stands for ('' if none)."""
    try:
        if token.startswith('&#'):
            number = token[3:-1] if token[2] in 'xX' else token[2:-1]
            return chr(int(number, 16 if token[2] in 'xX' else 10))
        letter = token[1]
        if letter in 'xuU':
            return chr(int(token[2:], 16))
        if letter == 'N' and token[2:3] == '{':
            import unicodedata

            return unicodedata.lookup(token[3:-1])
        if letter.isdigit():
            return chr(int(token[1:], 8))
        return _SIMPLE.get(letter, '')
    except (ValueError, KeyError, OverflowError):
        return ''


def _file_text(path: str) -> str | None:
    """The text of a launch file, read once (only when a finding is placed: rare)."""
    if path not in _TEXTS:
        from nodl.frontends.source import decode, read_limited

        try:
            text, _ = decode(read_limited(path), path)
        except (OSError, ValueError):
            text = None
        if len(_TEXTS) > 64:
            _TEXTS.clear()
        _TEXTS[path] = text
    return _TEXTS[path]


def _span_end(text: str, start: int) -> int:
    """Where what is written at ``start`` ends: an XML start tag at its ``>``, an XML
    attribute at its closing quote, anything else (a YAML entity, a Python argument) with its
    line and the lines indented deeper below it."""
    if text.startswith('<', start):
        quote = ''
        for index in range(start, min(len(text), start + 1_000_000)):
            char = text[index]
            if quote:
                quote = '' if char == quote else quote
            elif char in '"\'':
                quote = char
            elif char == '>':
                return index + 1
        return len(text)
    attribute = _ATTRIBUTE.match(text, start)
    if attribute is not None:
        end = text.find(attribute.group(1), attribute.end())
        return len(text) if end < 0 else end
    line_start = text.rfind('\n', 0, start) + 1
    prefix = text[line_start:start]
    indent = len(prefix) - len(prefix.lstrip(' \t'))  # (a YAML item's keys: deeper than its '-')
    end = text.find('\n', start)
    while end >= 0:
        following = text.find('\n', end + 1)
        line = text[end + 1:following if following >= 0 else len(text)]
        if line.strip() and len(line) - len(line.lstrip(' \t')) <= indent:
            return end
        end = following
    return len(text)


def place_character(at: SourceLocation, char: str) -> SourceLocation:
    """Where, in what is written at ``at``, the launch file writes ``char``: the character
    itself or an escape or reference that makes it; ``at`` if it is not there (a value made by
    substitutions, a Python expression)."""
    if not at.line:
        return at
    text = _file_text(at.file)
    if text is None:
        return at
    column = at.column or 1
    if at.file.endswith('.py'):  # Python's columns count UTF-8 bytes
        line_start = offset_of(text, at.line, 1)
        if line_start >= 0:
            line_end = text.find('\n', line_start)
            line = text[line_start:line_end if line_end >= 0 else len(text)]
            column = len(line.encode('utf-8')[:column - 1].decode('utf-8', 'ignore')) + 1
    start = offset_of(text, at.line, column)
    if not 0 <= start < len(text):
        return at
    end = _span_end(text, start)
    for match in _TOKEN.finditer(text, start, end) if '\\' in text[start:end] or '&#' in text[start:end] else ():
        if match.start() > 0 and text.find(char, start, match.start()) >= 0:
            break  # the raw character comes first
        if _decoded(match.group(0)) == char:
            return SourceLocation(at.file, *line_column(text, match.start()))
    found = text.find(char, start, end)
    if found >= 0:
        return SourceLocation(at.file, *line_column(text, found))
    return at


def unsafe_diagnostic(value: str, what: str, at: SourceLocation,
                      severity: Severity = Severity.ERROR) -> Diagnostic | None:
    """The finding for ``value`` (``what`` says what it is: "node name 'x'") written at
    ``at`` when it holds an unsafe character (placed at that character), else None."""
    index = first_unsafe(value)
    if index < 0:
        return None
    from nodl.validation.characters import unsafe_problem

    found = unsafe_problem(value, what)
    assert found is not None
    bidi, message = found
    where = place_character(at, value[index])
    return Diagnostic(severity, message, (), where.file, where.line, where.column,
                      code=BIDI_CONTROL if bidi else CONTROL_CHARACTER)


def refuse_unsafe(value: str | None, what: str, at: Any) -> None:
    """Raise the :class:`LaunchProblem` for ``value`` if it holds an unsafe character (a name
    that leaves its node out).  ``at``: where it is written, or a function that says it (called
    only then)."""
    if value is None or UNSAFE.search(value) is None:
        return
    place = at() if callable(at) else at
    found = unsafe_diagnostic(value, f'{what} {_shown(value)}', place)
    assert found is not None
    raise LaunchProblem(found.code or CONTROL_CHARACTER, found.message, found.file, found.line,
                        found.column)


def _shown(value: str) -> str:
    return f"'{visible(value, one_line=True)}'"


def _unsafe_in(value: Any) -> str | None:
    """The first string of a parameter value (a string, or a list holding strings) that holds
    an unsafe character."""
    if isinstance(value, str):
        return value if UNSAFE.search(value) is not None else None
    if isinstance(value, (list, tuple)):
        for item in value:
            if isinstance(item, str) and UNSAFE.search(item) is not None:
                return item
    return None


def check_node_text(context: LaunchContext, record: LaunchedNode) -> None:
    """Report the remapping rules, parameter names and parameter values of ``record`` that
    hold an unsafe character (each said once at its place); the rules are left out."""
    from nodl.launch.model import remap_source

    kept = []
    for rule in record.remaps:
        bad = next((part for part in rule if UNSAFE.search(part) is not None), None)
        if bad is None:
            kept.append(rule)
            continue
        where = remap_source(rule, record.source)
        found = unsafe_diagnostic(bad, f'the remapping rule {_shown(f"{rule[0]}:={rule[1]}")}', where)
        assert found is not None
        context.report(found.replace(message=found.message + '; the rule is left out (rcl would '
                                     'refuse it)'))
    if len(kept) != len(record.remaps):
        record.remaps = kept
    for source in record.parameters:
        if source.kind != 'values':
            continue  # a parameter file: read and checked where files are (params.py)
        for name, value in source.values.items():
            where = source.places.get(name) or source.source
            if UNSAFE.search(name) is not None:
                found = unsafe_diagnostic(name, f'the parameter name {_shown(name)}', where)
                assert found is not None
                context.report(found)
            bad = _unsafe_in(value)
            if bad is not None:
                found = unsafe_diagnostic(bad, f'the value of parameter {_shown(name)} '
                                          f'({_shown(bad)})', where)
                assert found is not None
                context.report(found.replace(message=found.message + '; rcl would pass it to the '
                                             'node as it is'))
