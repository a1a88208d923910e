"""Control characters and bidi controls in names and descriptions: nodl.validation.characters."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl.diagnostics import Severity
from nodl.loading import check_source
from nodl.validation import Kind, validate_data

FIXTURES = Path(__file__).parent / 'fixtures' / 'text_safety'
HOSTILE = FIXTURES / 'hostile.nodl.yaml'

#: (line, column of the offending character, code, path) of every error in the fixture.
EXPECTED = [
    (6, 31, 'NODL219', 'main.description'),
    (11, 26, 'NODL220', 'main.parameters.gain.description'),
    (12, 41, 'NODL219', 'main.parameters.gain.additional_constraints'),
    (13, 10, 'NODL220', 'main.parameters["rate\\u2066x"]'),
    (22, 22, 'NODL220', 'main.parameters.fine.validation["my_ns::check\\u202d"]'),
    (24, 18, 'NODL220', 'main.publishers[0].name'),
    (26, 29, 'NODL219', 'main.publishers[0].description'),
]


def test_every_name_and_description_is_checked_at_the_character() -> None:
    report = check_source(HOSTILE)
    found = [(d.line, d.column, d.code, d.path_text) for d in report.diagnostics]
    assert found == EXPECTED
    assert all(d.severity is Severity.ERROR for d in report.diagnostics)
    # the message names the character; a diagnostic line holds no unsafe character itself
    for diagnostic in report.diagnostics:
        assert str(diagnostic).isprintable()
        assert 'U+' in diagnostic.message


def test_raw_characters_are_placed_where_they_are(tmp_path: Path) -> None:
    text = HOSTILE.read_text(encoding='utf-8')
    raw = (text.replace('"Gain \\u202E txt.exe"', 'Gain \u202e txt.exe')
           .replace('"rate\\u2066x"', "'rate\u2066x'"))
    path = tmp_path / 'raw.nodl.yaml'
    path.write_text(raw, encoding='utf-8')
    placed = {d.path_text: (d.line, d.column) for d in check_source(path).diagnostics}
    assert placed['main.parameters.gain.description'] == (11, 25)
    assert placed['main.parameters["rate\\u2066x"]'] == (13, 10)


def test_json_escapes_are_placed_at_the_character(tmp_path: Path) -> None:
    path = tmp_path / 'p.json'
    path.write_text('{"type": "int",\n "description": "a \\u001b[31m red"}', encoding='utf-8')
    (diagnostic,) = check_source(path).diagnostics
    assert (diagnostic.line, diagnostic.column, diagnostic.code) == (2, 20, 'NODL219')


@pytest.mark.parametrize('description', [
    'tab\tand newline\n', 'RLM \u200f and LRM \u200e', 'line\u2028separator', 'عربي', '',
])
def test_ordinary_text_is_allowed(description: str) -> None:
    assert validate_data({'type': 'int', 'description': description}, Kind.PARAMETER) == []


@pytest.mark.parametrize(('char', 'code'), [('\x00', 'NODL219'), ('\r', 'NODL219'),
                                            ('\x9b', 'NODL219'), ('\u2069', 'NODL220')])
def test_a_name_with_such_a_character_is_one_error(char: str, code: str) -> None:
    data = {'nodl_version': 2, 'publishers': [
        {'name': f'a{char}', 'type': 'std_msgs/msg/String', 'description': 'x', 'qos': {
            'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'RELIABLE', 'durability': 'VOLATILE'}}]}
    found = validate_data(data, Kind.INTERFACE)
    assert [d.code for d in found] == [code]  # not also the generic invalid-name error
