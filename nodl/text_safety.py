"""Characters that must not reach a reader as they are, and how each writer spells them.

Text from a definition, a launch file or a running node may hold characters
that change what a reader sees rather than show themselves:

* C0 and C1 control characters (and DEL): a terminal obeys ``ESC [`` sequences
  (move the cursor, recolour, clear the screen), NUL ends C strings, CR
  returns to the start of the line, NEL and form feed break lines;
* the bidirectional controls of the Trojan Source attacks (CVE-2021-42574):
  U+202A-202E (embeddings and overrides) and U+2066-2069 (isolates), which
  reorder the text around them so that code or a description reads
  differently from what it is.  LRM and RLM (U+200E, U+200F) stay allowed:
  right-to-left text needs them and they cannot reorder other text.

Tab and newline are ordinary text.  Validation rejects the rest in names and
descriptions (:mod:`nodl.validation.characters`); every writer still
spells them harmlessly, because text can bypass validation (``--ignore``, a
running node's descriptors, a launch file's values).  The per-format helpers
live here, in one place:

* :func:`visible` (terminal, logs, rendered reports, HTML, SVG, DOT): each
  such character becomes a visible escape (``\\x1b``, ``\\u202e``);
* :func:`xml_escape` (XML text and attributes): markup escaped, characters
  XML 1.0 forbids written as visible escapes, the other unsafe ones (and the
  line separators) as character references that keep the value;
* :func:`python_escapes` (inside Python string literals and docstrings):
  Python's own escapes, so the value is kept and the source shows them.
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ['UNSAFE', 'BIDI_CONTROLS', 'first_unsafe', 'is_bidi_control', 'describe_character',
           'escape_character', 'visible', 'xml_escape', 'python_escapes', 'line_column',
           'offset_of', 'locate_unsafe', 'json_escapes', 'dump_yaml', 'one_line',
           'xml_report_text', 'xml_report_attribute']

#: Bidirectional controls of the Trojan Source set (embeddings, overrides, isolates).
BIDI_CONTROLS = frozenset('\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069')
#: Every unsafe character: C0 controls but tab and newline, DEL, C1 controls, the bidi set.
UNSAFE = re.compile('[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]')
# Characters XML 1.0 does not allow at all, not even as a character reference.
_NOT_XML = frozenset(chr(c) for c in range(0x20)) - {'\t', '\n', '\r'}
_XML_MARKUP = {'&': '&amp;', '<': '&lt;', '>': '&gt;'}
_XML_QUOTES = {'"': '&quot;', "'": '&apos;'}
_C0_NAMES = ('NUL', 'SOH', 'STX', 'ETX', 'EOT', 'ENQ', 'ACK', 'BEL', 'BACKSPACE', 'TAB', 'LINE-FEED', 'VT',
             'FORM-FEED', 'CARRIAGE-RETURN', 'SO', 'SI', 'DLE', 'DC1', 'DC2', 'DC3', 'DC4', 'NAK', 'SYN',
             'ETB', 'CAN', 'EM', 'SUB', 'ESCAPE', 'FS', 'GS', 'RS', 'US')
# A YAML or JSON double-quoted escape: the escape letter -> the character it stands for, and the
# hexadecimal escapes with their number of digits.
_SIMPLE_ESCAPES = {'0': '\0', 'a': '\a', 'b': '\b', 't': '\t', '\t': '\t', 'n': '\n', 'v': '\v',
                   'f': '\f', 'r': '\r', 'e': '\x1b', ' ': ' ', '"': '"', '/': '/', '\\': '\\',
                   'N': '\x85', '_': '\xa0', 'L': '\u2028', 'P': '\u2029'}
_HEX_ESCAPES = {'x': 2, 'u': 4, 'U': 8}
_LINE_BREAKS = re.compile('\r\n|[\r\n\x85\u2028\u2029]')


def first_unsafe(text: str) -> int:
    """The index of the first unsafe character of ``text``, or -1 if there is none."""
    match = UNSAFE.search(text)
    return match.start() if match is not None else -1


def is_bidi_control(char: str) -> bool:
    """True if ``char`` is one of the Trojan Source bidirectional controls."""
    return char in BIDI_CONTROLS


def describe_character(char: str) -> str:
    """``char`` named for a message: ``U+202E RIGHT-TO-LEFT OVERRIDE``, ``U+001B ESCAPE``."""
    code = ord(char)
    if code < 0x20:
        name = _C0_NAMES[code]
    elif code == 0x7f:
        name = 'DELETE'
    elif 0x80 <= code <= 0x9f:
        name = 'NEXT-LINE' if code == 0x85 else 'C1 control'
    else:
        import unicodedata  # only for a message: not imported at start-up
        name = unicodedata.name(char, 'character')
    return f'U+{code:04X} {name}'


def escape_character(char: str) -> str:
    """The visible escape of one character: ``\\x1b``, ``\\u202e`` (Python's spelling)."""
    code = ord(char)
    if code <= 0xff:
        return f'\\x{code:02x}'
    return f'\\u{code:04x}' if code <= 0xffff else f'\\U{code:08x}'


# Each writer's spelling of the characters it must not leave raw, as str.translate tables (the
# character classes as regular expressions cost the command line's start-up their compilation).
#: The code points of :data:`UNSAFE`: C0 controls but tab and newline, DEL, C1 controls, the bidi set.
_UNSAFE_CODES = (*range(0x00, 0x09), *range(0x0b, 0x20), *range(0x7f, 0xa0), *range(0x202a, 0x202f),
                 *range(0x2066, 0x206a))
#: The line separators (and tab, newline, CR: all C0) a one-line rendering escapes as well.
_LINE_SEPARATORS = (0x09, 0x0a, 0x2028, 0x2029)
_VISIBLE_ESCAPES = {code: escape_character(chr(code)) for code in _UNSAFE_CODES}
_ONE_LINE_ESCAPES = {code: escape_character(chr(code)) for code in (*_UNSAFE_CODES, *_LINE_SEPARATORS)}
#: What XML keeps as character references: CR, DEL, C1 controls, the line separators, the bidi set.
_XML_REFERENCES = {code: f'&#x{code:X};' for code in (0x0d, *range(0x7f, 0xa0), 0x2028, 0x2029,
                                                       *range(0x202a, 0x202f), *range(0x2066, 0x206a))}
#: What Python literals, JSON and YAML write as \uXXXX: the unsafe characters and the line separators
#: (JSON and YAML: U+FEFF too, which a reader may take for a byte order mark).
_PYTHON_ESCAPES = {code: f'\\u{code:04x}' for code in (*_UNSAFE_CODES, 0x2028, 0x2029)}
_JSON_ESCAPES = {**_PYTHON_ESCAPES, 0xfeff: '\\ufeff'}


def _yaml_escaped(text: str) -> bool:
    """True if ``text`` holds a character a YAML or JSON writer must escape (:data:`_JSON_ESCAPES`)."""
    return not text.isprintable() and text.translate(_JSON_ESCAPES) != text


def visible(text: str, one_line: bool = False) -> str:
    """``text`` with every unsafe character written as a visible escape (``\\x1b``).

    With ``one_line``, tab, newline and U+2028/U+2029 are escaped too: what a diagnostic, a log
    line or a label must keep on one line.  A backslash is not doubled: this is for people to
    read (a terminal, a report, a rendered page), not a format to read back.
    """
    if not one_line and text.isascii() and text.isprintable():
        return text
    return text.translate(_ONE_LINE_ESCAPES if one_line else _VISIBLE_ESCAPES)


def xml_escape(text: str, quote: bool = False) -> str:
    """``text`` as XML 1.0 character data (with ``quote``, for an attribute in either quotes).

    ``&``, ``<`` and ``>`` (and the quotes) become entities; a character XML 1.0 forbids
    (C0 controls but tab, newline and CR) becomes a visible escape, since no reference
    can stand for it; CR, DEL, C1 controls, the bidi controls and the line separators become
    character references (``&#x202E;``), so the value is kept and the file shows them.
    """
    out = ''.join(_XML_MARKUP.get(c, c) for c in text) if any(c in text for c in '&<>') else text
    if quote:
        out = ''.join(_XML_QUOTES.get(c, c) for c in out)
    if out.isascii() and out.isprintable():
        return out
    out = ''.join(escape_character(c) if c in _NOT_XML else c for c in out)
    return out.translate(_XML_REFERENCES)


def python_escapes(text: str) -> str:
    """``text`` for the inside of a Python string literal or docstring that already escapes its
    backslashes and quotes: unsafe characters (and U+2028/U+2029, which some editors break lines
    at) become ``\\uXXXX`` escapes (the one escape pydocstyle allows in a docstring), so the
    literal keeps the value and its source shows them."""
    return text.translate(_PYTHON_ESCAPES)


def line_column(text: str, offset: int) -> tuple[int, int]:
    """The 1-based ``(line, column)`` of ``offset`` in ``text``, counting line breaks as YAML
    does (CR, LF, CRLF, NEL, U+2028, U+2029), as the source maps do."""
    if not any(c in text for c in '\r\x85\u2028\u2029'):
        return text.count('\n', 0, offset) + 1, offset - (text.rfind('\n', 0, offset) + 1) + 1
    line, start = 1, 0
    for match in _LINE_BREAKS.finditer(text, 0, offset):
        line, start = line + 1, match.end()
    return line, offset - start + 1


def offset_of(text: str, line: int, column: int) -> int:
    """The offset in ``text`` of a 1-based ``(line, column)`` as :func:`line_column` counts."""
    start = 0
    if line > 1:
        pattern = _LINE_BREAKS if any(c in text for c in '\r\x85\u2028\u2029') else re.compile('\n')
        for number, match in enumerate(pattern.finditer(text), 2):
            if number == line:
                start = match.end()
                break
        else:
            return -1
    return start + column - 1


def locate_unsafe(text: str, start: int, value: str) -> int:
    """Where in ``text`` the first unsafe character of ``value`` is written, given that the
    scalar holding ``value`` starts at offset ``start``: the raw character, or the backslash of
    the escape that makes it in a double-quoted YAML or JSON string.  -1 if it cannot be told
    (the caller keeps the value's own position)."""
    wanted = first_unsafe(value)
    if wanted < 0 or not 0 <= start < len(text):
        return -1
    char = value[wanted]
    if text[start] != '"':
        found = text.find(char, start)
        return found
    index = start + 1
    while index < len(text):
        current = text[index]
        if current == '"':
            return -1
        if current != '\\':
            if UNSAFE.match(current):
                return index
            index += 1
            continue
        letter = text[index + 1:index + 2]
        if letter in _HEX_ESCAPES:
            digits = text[index + 2:index + 2 + _HEX_ESCAPES[letter]]
            try:
                made = chr(int(digits, 16))
            except ValueError:
                return -1
            if UNSAFE.match(made):
                return index
            index += 2 + len(digits)
            continue
        made = _SIMPLE_ESCAPES.get(letter, '')
        if made and UNSAFE.match(made):
            return index
        index += 2
    return -1




def json_escapes(text: str) -> str:
    """JSON (or YAML double-quoted) text with what :data:`UNSAFE` holds and the line separators
    written as ``\\uXXXX``: for the output of ``json.dumps(..., ensure_ascii=False)``, where
    they can only be inside strings.  Both JSON and YAML read the escapes back as they were."""
    return text.translate(_JSON_ESCAPES)


def _needs_escapes(data: Any) -> bool:
    if isinstance(data, str):
        return _yaml_escaped(data)
    if isinstance(data, dict):
        return any(_needs_escapes(k) or _needs_escapes(v) for k, v in data.items())
    if isinstance(data, (list, tuple)):
        return any(_needs_escapes(v) for v in data)
    return False


_dumper: Any = None


def _escaping_dumper() -> Any:
    """A safe YAML dumper that writes a string holding an unsafe character or a line separator
    double-quoted with escapes (``\\e``, ``\\L``, ``\\u202E``): no reader sees it raw, and every
    YAML reader reads the same string back (a raw U+2028, NEL or CR inside a quoted scalar is a
    line break that folding turns into a space)."""
    global _dumper
    if _dumper is None:
        import yaml

        class EscapingDumper(yaml.SafeDumper):
            def analyze_scalar(self, scalar: str) -> Any:
                analysis = super().analyze_scalar(scalar)
                if _yaml_escaped(scalar):
                    analysis.allow_flow_plain = analysis.allow_block_plain = False
                    analysis.allow_single_quoted = analysis.allow_block = False
                return analysis

            def write_double_quoted(self, text: str, split: bool = True) -> None:
                unicode = self.allow_unicode
                if _yaml_escaped(text):
                    self.allow_unicode = False  # this scalar only: every non-ASCII escaped
                try:
                    super().write_double_quoted(text, split)
                finally:
                    self.allow_unicode = unicode

        _dumper = EscapingDumper
    return _dumper


def dump_yaml(data: Any, width: int = 100) -> str:
    """``data`` as block-style YAML in the toolkit's layout (keys in order, Unicode as is), with
    every string that holds an unsafe character or a line separator double-quoted and escaped,
    so the text shows them and reads back as the same strings."""
    import yaml

    dumper = _escaping_dumper() if _needs_escapes(data) else getattr(yaml, 'CSafeDumper', yaml.SafeDumper)
    text: str = yaml.dump(data, Dumper=dumper, sort_keys=False, default_flow_style=False,
                          allow_unicode=True, width=width)
    return text


def one_line(text: object) -> str:
    """``text`` for one line of a comment or a label: runs of white space and line breaks (YAML's
    NEL, U+2028 and U+2029 among them) become one space, other unsafe characters visible escapes.
    Nothing in it can end the comment's line."""
    return visible(' '.join(str(text).split()), one_line=True)


def xml_report_text(text: str) -> str:
    """``text`` for the character data of a report (JUnit): shown as :func:`visible` shows it,
    then XML-escaped (nothing left that XML 1.0 forbids)."""
    return xml_escape(visible(text))


def xml_report_attribute(text: str) -> str:
    """``text`` as a double-quoted attribute of a report (JUnit), quotes included, as
    :func:`xml.sax.saxutils.quoteattr` writes one (tab and newline as references, which keeps
    them through attribute normalisation), shown as :func:`visible` shows it."""
    escaped = xml_escape(visible(text), quote=True).replace('\n', '&#10;').replace('\t', '&#9;')
    return f'"{escaped}"'
