"""Unsafe characters and their per-format spellings: nodl.text_safety."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from nodl.text_safety import (
    describe_character,
    first_unsafe,
    line_column,
    locate_unsafe,
    offset_of,
    python_escapes,
    visible,
    xml_escape,
)

CONTROLS = [chr(c) for c in range(0x20) if chr(c) not in '\t\n'] + ['\x7f'] + [
    chr(c) for c in range(0x80, 0xa0)]
BIDI = [chr(c) for c in range(0x202a, 0x202f)] + [chr(c) for c in range(0x2066, 0x206a)]


def escaped(char: str) -> str:
    code = ord(char)
    return f'\\x{code:02x}' if code <= 0xff else f'\\u{code:04x}'


SAFE = ['\t', '\n', '\u200e', '\u200f', '\u061c', '\u2028', '\u2029', 'é', '日', ' ', '\\']


@pytest.mark.parametrize('char', CONTROLS + BIDI)
def test_every_control_and_bidi_character_is_unsafe_and_made_visible(char: str) -> None:
    assert first_unsafe(f'ab{char}c') == 2
    shown = visible(f'ab{char}c')
    assert shown.isascii() and shown.isprintable()
    assert shown == 'ab' + escaped(char) + 'c'
    assert describe_character(char).startswith(f'U+{ord(char):04X} ')


@pytest.mark.parametrize('char', SAFE)
def test_tab_newline_and_right_to_left_marks_are_safe(char: str) -> None:
    assert first_unsafe(f'a{char}b') == -1
    assert visible(f'a{char}b') == f'a{char}b'


def test_one_line_escapes_line_breaks_too() -> None:
    assert visible('a\tb\nc\u2028d\u2029e', one_line=True) == 'a\\x09b\\x0ac\\u2028d\\u2029e'


@pytest.mark.parametrize('char', CONTROLS + BIDI + SAFE + ['&', '<', '>', '"', "'"])
def test_xml_escape_always_parses_and_keeps_what_xml_can_hold(char: str) -> None:
    text = f'a{char}b'
    attribute = xml_escape(text, quote=True)
    element = ET.fromstring(f'<e a="{attribute}" b=\'{attribute}\'>{xml_escape(text)}</e>')
    assert UNSAFE_FREE(attribute)
    if char in '\x00\x01\x02\x03\x04\x05\x06\x07\x08\x0b\x0c\x0e\x0f' or '\x10' <= char < ' ':
        assert element.text == 'a' + escaped(char) + 'b'  # XML 1.0 cannot hold it at all
    else:
        assert element.text == text
        assert element.get('b') == (text if char not in '\t\n' else text.replace(char, ' '))


def UNSAFE_FREE(text: str) -> bool:
    return first_unsafe(text) == -1 and '\u2028' not in text and '\u2029' not in text


@pytest.mark.parametrize('char', CONTROLS + BIDI + ['\u2028', '\u2029'])
def test_python_escapes_keep_the_value_and_show_in_the_source(char: str) -> None:
    source = f"'x{python_escapes(char)}y'"
    assert source.isascii() and source.isprintable()
    assert eval(compile(source, '<test>', 'eval')) == f'x{char}y'


def test_line_column_counts_line_breaks_as_yaml_does() -> None:
    text = 'a\r\nb\u2028c\x85d\ne'
    for offset in range(len(text)):
        if text[offset - 1:offset + 1] == '\r\n':
            continue  # the middle of one line break
        line, column = line_column(text, offset)
        assert offset_of(text, line, column) == offset
    assert line_column(text, text.index('e')) == (5, 1)
    assert offset_of('a\nb', 3, 1) == -1


@pytest.mark.parametrize(('source', 'expected'), [
    ('"ab\\e[2J"', 3),          # an escape: its backslash
    ('"a\\u202Eb"', 2),
    ('"a\\x00"', 2),
    ('"a\\N"', 2),               # NEL
    ('"a\\"\\\\\\U0000202e"', 6),  # after escaped quote and backslash
    ('"a\u202eb"', 2),           # raw in quotes
    ("'a\u202eb'", 2),           # single quotes are raw
    ('a \u202e b', 2),           # plain
])
def test_locate_unsafe_finds_the_character_where_the_text_shows_it(source: str, expected: int) -> None:
    import yaml
    value = yaml.safe_load(source)
    assert locate_unsafe('k: ' + source, 3, value) == 3 + expected


def test_locate_unsafe_gives_up_rather_than_guess() -> None:
    assert locate_unsafe('"abc"', 0, 'abc') == -1            # nothing unsafe
    assert locate_unsafe('"a\\xZZ"', 0, 'a\x00') == -1       # not an escape it knows
    assert locate_unsafe('"ab" x: "\\e"', 0, 'a\x1b') == -1  # not inside this string
