"""The YAML/JSON frontend (nodl.frontends.yaml_json).

YAML and JSON give the same data, JSON keeps JSON semantics, problems that
YAML loaders hide (duplicate keys) or handle badly (tabs, several documents,
tags) are one clear diagnostic each, scalars resolve as PyYAML's SafeLoader
resolves them, and ``ParsedDocument.position`` turns a document path into
the right 1-based line and column.
"""

from __future__ import annotations

import io
import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml

from nodl import ValidationError, check_source, load_nodl
from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.source import SourceText, read_source
from nodl.frontends.yaml_json import MAX_ALIAS_NODES, MAX_DEPTH, ParsedDocument, parse_document

REPO = Path(__file__).resolve().parent.parent
FRONTENDS = Path(__file__).parent / 'fixtures' / 'frontends'

EMPTY = ('document is empty; a NoDL document is a mapping that starts with nodl_version: 2 '
         '(or, for a single parameter definition, type: ...)')
TAB = 'tab character used for indentation; YAML allows only spaces'
MULTI = ('the file holds more than one YAML document; '
         'put each definition in a file of its own')


def parse(text: str, file: str = 'doc.yaml') -> ParsedDocument:
    return parse_document(SourceText(text, file))


def parse_file(name: str) -> ParsedDocument:
    text, problem = read_source(FRONTENDS / name)
    assert problem is None and text is not None
    return parse_document(text)


def only(doc: ParsedDocument) -> Diagnostic:
    """The one diagnostic of ``doc``."""
    assert len(doc.diagnostics) == 1, [str(d) for d in doc.diagnostics]
    diagnostic = doc.diagnostics[0]
    assert diagnostic.severity is Severity.ERROR
    assert '\n' not in str(diagnostic)
    assert not doc.ok
    return diagnostic


def clean(doc: ParsedDocument) -> Any:
    assert doc.diagnostics == [], [str(d) for d in doc.diagnostics]
    return doc.data


def safe_load(text: str) -> Any:
    """PyYAML's pure-Python SafeLoader: the reference for scalar resolution."""
    return yaml.load(text, Loader=yaml.SafeLoader)


# --- YAML and JSON --------------------------------------------------------------

def test_yaml_and_json_give_equal_data() -> None:
    from_yaml = parse_file('same_data.yaml')
    from_json = parse_file('same_data.json')
    assert clean(from_yaml) == clean(from_json)
    assert from_yaml.is_json is False
    assert from_json.is_json is True
    assert from_yaml.ok and from_json.ok
    data = from_json.data
    assert data['description'] == 'Café — unicode survives'
    assert data['parameters']['nothing']['default_value'] is None
    assert data['parameters']['speed']['read_only'] is False
    assert type(data['parameters']['offset']['default_value']) is int
    assert type(data['parameters']['speed']['default_value']) is float


def test_yaml_and_json_agree_with_the_reference_loaders() -> None:
    yaml_text = (FRONTENDS / 'same_data.yaml').read_text(encoding='utf-8')
    json_text = (FRONTENDS / 'same_data.json').read_text(encoding='utf-8')
    assert parse(yaml_text).data == safe_load(yaml_text)
    assert parse(json_text).data == json.loads(json_text)


def test_json_is_chosen_by_a_json_file_name_or_a_leading_brace() -> None:
    json_text = (FRONTENDS / 'same_data.json').read_text(encoding='utf-8')
    yaml_text = (FRONTENDS / 'same_data.yaml').read_text(encoding='utf-8')
    # JSON text starting with '{' is JSON whatever the file is called.
    assert parse(json_text, 'misnamed.yaml').is_json is True
    assert parse(json_text, 'misnamed.yaml').data == parse(yaml_text, 'right.yaml').data
    # A .json file is strict JSON: YAML text in it is a JSON error, not silently YAML.
    problem = only(parse(yaml_text, 'misnamed.json'))
    assert problem.message.startswith('JSON syntax error: ')
    assert (problem.code, problem.line, problem.column) == ('NODL016', 1, 1)
    assert parse(json_text, 'UPPER.JSON').is_json is True


@pytest.mark.parametrize('text, expected', [
    ('{"v": 1e5}', 100000.0),
    ('{"v": 1E5}', 100000.0),
    ('{"v": 1e-2}', 0.01),
    ('{"v": 2.0}', 2.0),
    ('{"v": -0.0}', -0.0),
    ('{"v": 10}', 10),
    ('{"v": -7}', -7),
    ('{"v": 12345678901234567890123}', 12345678901234567890123),
])
def test_json_numbers_keep_json_semantics(text: str, expected: Any) -> None:
    doc = parse(text)
    assert doc.is_json
    value = clean(doc)['v']
    assert value == expected
    assert type(value) is type(expected)


def test_the_same_number_in_yaml_follows_yaml_1_1() -> None:
    # YAML 1.1 (and PyYAML) need a dot for a float: 1e5 is text there.
    assert clean(parse('v: 1e5\n'))['v'] == safe_load('v: 1e5\n')['v'] == '1e5'
    assert clean(parse('v: 1.0e+5\n'))['v'] == 100000.0


def test_json_literals() -> None:
    assert clean(parse('{"t": true, "f": false, "n": null, "s": "yes"}')) == \
        {'t': True, 'f': False, 'n': None, 's': 'yes'}


def test_json_with_tabs_for_indentation_is_fine() -> None:
    doc = parse('{\n\t"type": "int",\n\t"default_value": 3\n}\n')
    assert doc.is_json
    assert clean(doc) == {'type': 'int', 'default_value': 3}


def test_yaml_flow_style_that_is_not_json_is_a_json_error_not_yaml() -> None:
    doc = parse('{type: int, default_value: 0x10}')
    assert doc.is_json is True and doc.data is None
    problem = only(doc)
    assert problem.message.startswith('JSON syntax error: Expecting property name enclosed in '
                                      'double quotes')
    assert (problem.line, problem.column) == (1, 2)
    # The same mapping under a key, or in block style, is YAML.
    assert clean(parse('x: {type: int, default_value: 0x10}')) == \
        {'x': {'type': 'int', 'default_value': 16}}


# --- strict JSON -----------------------------------------------------------------

NOT_JSON = FRONTENDS / 'not_json'

#: fixture -> (line, column, what the message says): JSON's own line and column.
NOT_JSON_CASES = {
    'trailing_comma.json': (5, 3, 'JSON allows no trailing comma'),
    'comment.json': (3, 3, 'JSON has no comments'),
    'single_quotes.json': (3, 18, 'JSON strings and keys take double quotes'),
    'unquoted_key.json': (4, 5, 'JSON keys and strings are quoted'),
    'nan.json': (4, 49, 'NaN is not a JSON value'),
    'infinity.json': (1, 80, '-Infinity is not a JSON value'),
}


def assert_json_error(doc: ParsedDocument, case: str) -> Diagnostic:
    line, column, says = NOT_JSON_CASES[case]
    problem = only(doc)
    assert doc.is_json is True and doc.data is None
    assert problem.message.startswith('JSON syntax error: ')
    assert says in problem.message and 'strict JSON' in problem.message
    assert (problem.code, problem.line, problem.column) == ('NODL016', line, column)
    return problem


def test_every_not_json_fixture_is_a_case() -> None:
    assert sorted(p.name for p in NOT_JSON.iterdir()) == sorted(NOT_JSON_CASES)


@pytest.mark.parametrize('case', sorted(NOT_JSON_CASES))
def test_a_json_file_that_is_not_strict_json_is_a_json_error(case: str) -> None:
    problem = assert_json_error(parse_file(f'not_json/{case}'), case)
    assert problem.file == str(NOT_JSON / case)
    # YAML would have read every one of them: the error is not a silent fallback.
    assert isinstance(safe_load((NOT_JSON / case).read_text(encoding='utf-8').replace(
        '//', '#')), dict)


@pytest.mark.parametrize('case', sorted(NOT_JSON_CASES))
def test_text_starting_with_a_brace_is_strict_json_from_stdin_too(case: str) -> None:
    text = (NOT_JSON / case).read_text(encoding='utf-8')
    assert_json_error(parse(text, '<stdin>'), case)
    assert_json_error(parse(text, '-'), case)
    report = check_source(io.StringIO(text), file='<stdin>')
    assert [(d.code, d.line, d.column) for d in report.diagnostics] == \
        [('NODL016',) + NOT_JSON_CASES[case][:2]]


@pytest.mark.parametrize('case', ['trailing_comma.json', 'nan.json'])
def test_the_command_line_reports_json_errors_at_json_positions(case: str) -> None:
    line, column, says = NOT_JSON_CASES[case]
    text = (NOT_JSON / case).read_text(encoding='utf-8')
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '-'], input=text,
                            cwd=REPO, capture_output=True, text=True, timeout=60)
    assert result.returncode == 1, result.stdout + result.stderr
    assert f'<stdin>:{line}:{column}: error: JSON syntax error: ' in result.stdout
    assert says in result.stdout and 'Traceback' not in result.stderr


def test_leading_json_whitespace_does_not_hide_the_brace() -> None:
    doc = parse(' \r\n\t\n{"a": 1,}\n', 'doc')
    problem = only(doc)
    assert (problem.code, problem.line, problem.column) == ('NODL016', 3, 9)
    # A comment first makes it YAML: its first character is not '{'.
    assert clean(parse('# c\n{a: 1}\n')) == {'a': 1}


def test_a_json_file_is_strict_whatever_its_first_character() -> None:
    problem = only(parse('nodl_version: 2\n', 'node.JSON'))
    assert (problem.code, problem.line, problem.column) == ('NODL016', 1, 1)
    assert only(parse('', 'empty.json')).code == 'NODL016'


def test_a_list_document_is_still_yaml() -> None:
    doc = parse('[1, 2,]\n')
    assert doc.is_json is False
    assert only(doc).message.startswith('document is a list, not a mapping')


def test_valid_json_with_a_nan_inside_a_string_is_fine() -> None:
    assert clean(parse('{"a": "NaN \\" Infinity", "b": 1}')) == {'a': 'NaN " Infinity', 'b': 1}


# --- duplicate keys --------------------------------------------------------------

def test_duplicate_key_in_yaml_file() -> None:
    problem = only(parse_file('duplicate_keys.yaml'))
    assert (problem.line, problem.column) == (8, 3)
    assert "duplicate key 'speed'" in problem.message
    assert '(first defined at line 3)' in problem.message
    assert problem.path == ('parameters',)
    assert problem.file == str(FRONTENDS / 'duplicate_keys.yaml')


def test_duplicate_key_in_json_file() -> None:
    doc = parse_file('duplicate_keys.json')
    problem = only(doc)
    assert (problem.line, problem.column) == (6, 5)
    assert "duplicate key 'speed'" in problem.message
    assert '(first defined at line 4)' in problem.message
    assert problem.path == ('parameters',)


@pytest.mark.parametrize('text, line, column, first', [
    ('a: 1\nb: 2\na: 3\n', 3, 1, 1),
    ('a: {x: 1, y: 2, x: 3}\n', 1, 17, 1),
    ('{"a": 1, "a": 2}', 1, 10, 1),
    ('{"a": {"b": 1,\n "b": 2}}', 2, 2, 1),
    ('outer:\n  - k: 1\n    j: 2\n    k: 3\n', 4, 5, 2),
    ('"a": 1\n\'a\': 2\n', 2, 1, 1),
], ids=['block', 'flow', 'json', 'json-nested', 'in-list', 'quoted'])
def test_duplicate_keys_give_the_second_key_and_the_first_line(
        text: str, line: int, column: int, first: int) -> None:
    problem = only(parse(text))
    assert (problem.line, problem.column) == (line, column)
    assert problem.message.startswith('duplicate key ')
    assert f'(first defined at line {first})' in problem.message


def test_every_repeat_of_a_key_is_reported() -> None:
    doc = parse('a: 1\nb: 2\na: 3\na: 4\n')
    assert [(d.line, d.column) for d in doc.diagnostics] == [(3, 1), (4, 1)]
    assert all('(first defined at line 1)' in d.message for d in doc.diagnostics)


def test_duplicate_keys_are_errors_from_the_public_api() -> None:
    with pytest.raises(ValidationError) as info:
        load_nodl(FRONTENDS / 'duplicate_keys.yaml')
    errors = info.value.errors
    assert len(errors) == 1
    assert (errors[0].line, errors[0].column) == (8, 3)
    assert "duplicate key 'speed'" in errors[0].message


def test_duplicate_key_messages_stay_on_one_line() -> None:
    problem = only(parse('"a\\nb": 1\n"a\\nb": 2\n'))
    assert problem.message.startswith("duplicate key 'a\\nb' (first defined at line 1)")
    long_key = 'k' * 500
    problem = only(parse(f'{long_key}: 1\n{long_key}: 2\n'))
    assert len(problem.message) < 200
    assert problem.message.startswith("duplicate key 'kkk")


def test_equal_keys_in_different_mappings_are_not_duplicates() -> None:
    assert clean(parse('a: {k: 1}\nb: {k: 2}\nk: 3\n')) == {'a': {'k': 1}, 'b': {'k': 2}, 'k': 3}


# --- merge keys -----------------------------------------------------------------

def test_merge_keys_are_expanded_and_not_duplicates() -> None:
    # The YAML merge-key specification decides, not the installed PyYAML (6.0.4 lets the
    # later mapping of '<<: [*best_effort, *reliable]' win: reliability RELIABLE).
    data = clean(parse_file('merge_keys.yaml'))
    first, second = data['publishers']
    # An explicit key overrides the merged one without being a duplicate.
    assert first['qos'] == {'history': 'KEEP_LAST', 'depth': 5, 'reliability': 'RELIABLE'}
    # In a list of merges, the earlier mapping wins.
    assert second['qos'] == {'reliability': 'BEST_EFFORT', 'durability': 'VOLATILE',
                             'history': 'KEEP_LAST', 'depth': 10}
    assert '<<' not in first['qos'] and '<<' not in second['qos']


def test_a_merged_value_is_placed_where_the_winning_mapping_writes_it() -> None:
    doc = parse_file('merge_order.yaml')
    expected = json.loads((FRONTENDS / 'merge_order.expected.json').read_text(encoding='utf-8'))
    assert doc.diagnostics == [] and doc.data == expected
    assert doc.position(('first_wins', 'reliability')) == (8, 16)  # *fast's, not *base's
    assert doc.position(('own_wins', 'depth')) == (18, 10)  # written in the mapping itself
    assert doc.position(('twice', 'durability')) == (11, 15)  # *nested merges *latched


def test_anchors_aliases_and_merge_keys_are_kept_with_their_places() -> None:
    doc = parse('a: &x {k: 1}\nb:\n  <<: *x\nc: *x\n')
    assert doc.aliasing == [('anchor', 1, 4), ('merge', 3, 3), ('alias', 3, 7), ('alias', 4, 4)]
    assert parse('a: 1\n').aliasing == []


def test_two_merge_keys_in_one_mapping_are_not_duplicates() -> None:
    text = 'x: &x {a: 1}\ny: &y {a: 2, b: 2}\nz:\n  <<: *x\n  <<: *y\n'
    assert clean(parse(text))['z'] == {'a': 1, 'b': 2}


def test_merging_something_that_is_not_a_mapping_is_an_error() -> None:
    problem = only(parse('s: &s text\nz:\n  <<: *s\n'))
    assert problem.message == 'a merge key (<<) must refer to a mapping'
    assert (problem.line, problem.column) == (1, 4)
    doc = parse('list: &l [1, 2]\nz:\n  <<: *l\n')
    assert doc.diagnostics
    assert all(d.message == 'a merge key (<<) must refer to a mapping' for d in doc.diagnostics)


# --- empty and non-mapping documents ------------------------------------------------

@pytest.mark.parametrize('text', ['', '\n\n', '   \n', '# only a comment\n', '---\n', '--- # c\n'],
                         ids=['empty', 'newlines', 'spaces', 'comment', 'marker', 'marker-comment'])
def test_empty_documents_are_one_clear_error(text: str) -> None:
    problem = only(parse(text))
    assert problem.message == EMPTY
    assert (problem.line, problem.column) == (1, 1)


def test_comment_only_file() -> None:
    problem = only(parse_file('comments_only.yaml'))
    assert problem.message == EMPTY
    assert problem.file == str(FRONTENDS / 'comments_only.yaml')


@pytest.mark.parametrize('text, kind', [
    ('- a\n- b\n', 'a list'),
    ('[1, 2]', 'a list'),
    ('[]', 'a list'),
    ('just text\n', 'a string'),
    ('"quoted"', 'a string'),
    ('42\n', 'a number'),
    ('4.5', 'a number'),
    ('true\n', 'a boolean'),
], ids=['block-list', 'json-list', 'empty-list', 'plain', 'json-string', 'int', 'float', 'bool'])
def test_non_mapping_documents_are_one_clear_error(text: str, kind: str) -> None:
    problem = only(parse(text))
    assert problem.message.startswith(f'document is {kind}, not a mapping')
    assert (problem.line, problem.column) == (1, 1)


@pytest.mark.parametrize('name, kind', [('list.yaml', 'a list'), ('scalar.yaml', 'a string')])
def test_non_mapping_files(name: str, kind: str) -> None:
    problem = only(parse_file(name))
    assert problem.message.startswith(f'document is {kind}, not a mapping')
    report = check_source(FRONTENDS / name)
    assert len(report.diagnostics) == 1 and report.kind is None


def test_non_mapping_after_leading_blank_lines_points_at_the_content() -> None:
    problem = only(parse('\n\n  - a\n  - b\n'))
    assert (problem.line, problem.column) == (3, 3)


# --- tabs -----------------------------------------------------------------------

def test_tabs_for_indentation_in_a_file() -> None:
    problem = only(parse_file('tabs.yaml'))
    assert problem.message == TAB
    assert (problem.line, problem.column) == (3, 1)


@pytest.mark.parametrize('text, line, column', [
    ('\ta: 1\n', 1, 1),
    ('a:\n\tb: 1\n', 2, 1),
    ('a: 1\n\tb: 2\n', 2, 1),
    ('a:\n  b: 1\n\tc: 2\n', 3, 1),
    ('a:\n  \tb: 1\n', 2, 3),
    ('a:\n\t- 1\n', 2, 1),
    ('a:\n - 1\n\t- 2\n', 3, 1),
    ('-\tx\n', 1, 2),
    ('a: |\n\tx\n', 2, 1),
], ids=['first-line', 'mapping', 'sibling', 'nested', 'after-spaces', 'sequence',
        'sequence-sibling', 'after-dash', 'block-scalar'])
def test_tabs_for_indentation_name_the_line(text: str, line: int, column: int) -> None:
    problem = only(parse(text))
    assert problem.message == TAB
    assert (problem.line, problem.column) == (line, column)


@pytest.mark.parametrize('text, expected', [
    ('a: "x\ty"\n', {'a': 'x\ty'}),
    ('a: b\tc\n', {'a': 'b\tc'}),
    ('a: 1\t# comment\n', {'a': 1}),
    ('a: [\n\t1]\n', {'a': [1]}),
])
def test_tabs_that_are_not_indentation_are_fine(text: str, expected: Any) -> None:
    assert clean(parse(text)) == expected


# --- several documents -------------------------------------------------------------

def test_more_than_one_document_in_a_file() -> None:
    problem = only(parse_file('multi_document.yaml'))
    assert problem.message == MULTI
    assert problem.line == 3


@pytest.mark.parametrize('text, line', [
    ('a: 1\n---\nb: 2\n', 2),
    ('--- a\n--- b\n', 2),
    ('a: 1\n...\n---\nb: 2\n', 3),
])
def test_more_than_one_document_is_an_error(text: str, line: int) -> None:
    problem = only(parse(text))
    assert problem.message == MULTI
    assert problem.line == line


@pytest.mark.parametrize('text', ['---\na: 1\n', 'a: 1\n...\n', '%YAML 1.1\n---\na: 1\n'])
def test_one_document_with_markers_is_fine(text: str) -> None:
    assert clean(parse(text)) == {'a': 1}


# --- tags -----------------------------------------------------------------------

@pytest.mark.parametrize('text, tag', [
    ('a: !foo x\n', '!foo'),
    ('a: !foo {x: 1}\n', '!foo'),
    ('a: !foo [1]\n', '!foo'),
    ('a: !!binary aGVsbG8=\n', 'tag:yaml.org,2002:binary'),
    ('a: !!set {x, y}\n', 'tag:yaml.org,2002:set'),
    ('a: !!omap [{x: 1}]\n', 'tag:yaml.org,2002:omap'),
    ('a: !!python/object/apply:os.system ["echo pwned"]\n',
     'tag:yaml.org,2002:python/object/apply:os.system'),
], ids=['local', 'local-map', 'local-seq', 'binary', 'set', 'omap', 'python'])
def test_unsupported_tags_are_errors(text: str, tag: str) -> None:
    problem = only(parse(text))
    assert problem.message.startswith(f"unsupported YAML tag '{tag}'")
    assert (problem.line, problem.column) == (1, 4)


def test_unsupported_tag_is_an_error_from_the_public_api() -> None:
    with pytest.raises(ValidationError) as info:
        load_nodl('type: string\ndefault_value: !!binary aGVsbG8=\n')
    assert len(info.value.errors) == 1
    assert 'unsupported YAML tag' in str(info.value)


@pytest.mark.parametrize('text, expected', [
    ('a: !!str 1\n', '1'),
    ('a: !!int "12"\n', 12),
    ('a: !!float "1"\n', 1.0),
    ('a: !!bool "yes"\n', True),
    ('a: !!null ""\n', None),
    ('!!map {a: 1}\n', None),
])
def test_standard_tags_on_matching_values_are_fine(text: str, expected: Any) -> None:
    data = clean(parse(text))
    if text.startswith('!!map'):
        assert data == {'a': 1}
    else:
        assert data['a'] == expected and type(data['a']) is type(expected)


@pytest.mark.parametrize('text', [
    'a: !!int abc\n', 'a: !!int ""\n', 'a: !!int 0x\n', 'a: !!int 09\n', 'a: !!float abc\n',
    'a: !!float ""\n', 'a: !!bool maybe\n', 'a: !!bool ""\n',
    'a: !<tag:yaml.org,2002:int> zz\n',
])
def test_standard_tags_on_values_they_cannot_hold_are_one_error(text: str) -> None:
    problem = only(parse(text))
    assert (problem.line, problem.column) == (1, 4)
    assert 'tagged' in problem.message and 'remove the tag or fix the value' in problem.message
    report = check_source(text)
    assert len(report.errors) == 1


# --- scalars ----------------------------------------------------------------------

def test_timestamps_stay_strings() -> None:
    data = clean(parse_file('timestamps.yaml'))
    assert data == {
        'date': '2001-12-14',
        'canonical': '2001-12-15T02:59:43.1Z',
        'iso8601': '2001-12-14t21:59:43.10-05:00',
        'spaced': '2001-12-14 21:59:43.10 -5',
        'in_list': ['2002-12-14', '2003-01-01'],
    }
    assert all(isinstance(v, str) for v in data.values() if not isinstance(v, list))


@pytest.mark.parametrize('literal', [
    '0x1F', '0o17', '017', '1_000', '0b101', '-0x1F', '+12', '-0', '0', '00', '0_7',
    '190:20:30', '-1_000', '1__0', '12', '0xff_ff', '9' * 30,
])
def test_yaml_1_1_integers_match_pyyaml_safeloader(literal: str) -> None:
    text = f'v: {literal}\n'
    value = clean(parse(text))['v']
    expected = safe_load(text)['v']
    assert value == expected
    assert type(value) is type(expected)


def test_the_integers_of_the_brief() -> None:
    data = clean(parse('a: 0x1F\nb: 0o17\nc: 017\nd: 1_000\n'))
    # 0o17 is YAML 1.2 only: text in YAML 1.1, as in PyYAML.
    assert data == {'a': 31, 'b': '0o17', 'c': 15, 'd': 1000}


@pytest.mark.parametrize('literal', [
    '1.5', '-1.5', '1.0e+5', '1.5E-3', '.5', '1_000.5', '190:20:30.15', '.inf', '-.Inf',
    '+.INF', '1e5', '1.', '6.8523015e+5',
])
def test_yaml_floats_match_pyyaml_safeloader(literal: str) -> None:
    text = f'v: {literal}\n'
    value = clean(parse(text))['v']
    expected = safe_load(text)['v']
    assert value == expected
    assert type(value) is type(expected)


def test_nan_is_a_float() -> None:
    value = clean(parse('v: .nan\n'))['v']
    assert isinstance(value, float) and math.isnan(value)


@pytest.mark.parametrize('literal', [
    'yes', 'Yes', 'YES', 'no', 'No', 'on', 'On', 'OFF', 'true', 'True', 'FALSE', 'y', 'n',
    'null', 'Null', '~', '', 'NULL', 'nil', 'None', '"true"', "'1'",
])
def test_booleans_nulls_and_strings_match_pyyaml_safeloader(literal: str) -> None:
    text = f'v: {literal}\n'
    value = clean(parse(text))['v']
    expected = safe_load(text)['v']
    assert value == expected
    assert type(value) is type(expected)


def test_keys_are_resolved_like_values() -> None:
    text = '1: one\nfalse: yes\nnull: x\n"2": two\n0x10: hex\n'
    assert clean(parse(text)) == safe_load(text) == \
        {1: 'one', False: True, None: 'x', '2': 'two', 16: 'hex'}


def test_collection_keys_are_an_error_not_a_crash() -> None:
    problem = only(parse('? [1, 2]\n: x\n'))
    assert 'keys must be plain scalars' in problem.message


# --- positions ------------------------------------------------------------------------

@pytest.fixture(scope='module')
def positions() -> ParsedDocument:
    doc = parse_file('positions.yaml')
    assert doc.ok
    return doc


@pytest.mark.parametrize('path, anchor, expected', [
    ((), 'value', (1, 1)),
    (('nodl_version',), 'key', (1, 1)),
    (('nodl_version',), 'value', (1, 15)),
    (('parameters',), 'key', (2, 1)),
    (('parameters',), 'value', (3, 3)),
    (('parameters', 'speed'), 'key', (3, 3)),
    (('parameters', 'speed', 'type'), 'key', (4, 5)),
    (('parameters', 'speed', 'type'), 'value', (4, 11)),
    (('parameters', 'speed', 'default_value'), 'value', (5, 20)),
    (('parameters', 'quoted key'), 'key', (6, 3)),
    (('parameters', 'quoted key', 'type'), 'value', (6, 24)),
], ids=lambda v: repr(v))
def test_positions_of_keys_and_values(positions: ParsedDocument, path: tuple[Any, ...],
                                      anchor: str, expected: tuple[int, int]) -> None:
    assert positions.position(path, anchor) == expected


@pytest.mark.parametrize('path, anchor, expected', [
    (('publishers', 0), 'value', (8, 5)),
    (('publishers', 1), 'value', (10, 5)),
    (('publishers', 1), 'key', (10, 5)),  # a list item has no key: its value
    (('publishers', 0, 'type'), 'value', (9, 11)),
    (('publishers', 1, 'name'), 'key', (10, 5)),
    (('publishers', 1, 'name'), 'value', (10, 11)),
])
def test_positions_in_lists(positions: ParsedDocument, path: tuple[Any, ...], anchor: str,
                            expected: tuple[int, int]) -> None:
    assert positions.position(path, anchor) == expected


@pytest.mark.parametrize('path, anchor, expected', [
    (('parameters', 'speed', 'missing'), 'value', (4, 5)),
    (('parameters', 'speed', 'missing'), 'key', (3, 3)),
    (('parameters', 'speed', 'missing', 'deeper'), 'value', (4, 5)),
    (('publishers', 7), 'value', (8, 3)),
    (('publishers', 7, 'name'), 'key', (7, 1)),
    (('publishers', -1), 'value', (8, 3)),
    (('publishers', 'name'), 'value', (8, 3)),
    (('nope',), 'value', (1, 1)),
    (('nope',), 'key', (1, 1)),
    (('nodl_version', 'below_a_scalar'), 'value', (1, 15)),
])
def test_a_missing_path_falls_back_to_its_deepest_existing_parent(
        positions: ParsedDocument, path: tuple[Any, ...], anchor: str,
        expected: tuple[int, int]) -> None:
    assert positions.position(path, anchor) == expected


def test_positions_of_non_string_keys(positions: ParsedDocument) -> None:
    assert positions.data['flags'] == {True: True, 42: 'answer'}
    assert positions.position(('flags', True), 'key') == (13, 3)
    assert positions.position(('flags', True), 'value') == (13, 9)
    assert positions.position(('flags', 42), 'value') == (14, 7)


def test_positions_of_keys_reached_through_a_merge(positions: ParsedDocument) -> None:
    assert positions.data['inherited'] == {'type': 'string', 'description': 'shared',
                                           'default_value': 'x'}
    # Merged keys point where they are written: in the anchored mapping.
    assert positions.position(('inherited', 'type'), 'key') == (16, 3)
    assert positions.position(('inherited', 'type'), 'value') == (16, 9)
    assert positions.position(('inherited', 'description'), 'value') == (17, 16)
    # Keys of the mapping itself point at the mapping.
    assert positions.position(('inherited', 'default_value'), 'key') == (20, 3)


def test_an_explicit_key_wins_over_a_merged_one_in_positions() -> None:
    doc = parse('d: &d\n  k: merged\nm:\n  <<: *d\n  k: own\n')
    assert clean(doc)['m'] == {'k': 'own'}
    assert doc.position(('m', 'k'), 'value') == (5, 6)


@pytest.mark.parametrize('path, anchor, expected', [
    ((), 'value', (1, 1)),
    (('nodl_version',), 'key', (2, 3)),
    (('nodl_version',), 'value', (2, 19)),
    (('parameters', 'speed', 'type'), 'key', (5, 7)),
    (('parameters', 'speed', 'type'), 'value', (5, 15)),
    (('publishers', 1), 'value', (11, 5)),
    (('publishers', 1, 'name'), 'key', (11, 6)),
    (('publishers', 1, 'name'), 'value', (11, 14)),
    (('parameters', 'speed', 'nope'), 'value', (4, 14)),
])
def test_positions_in_json(path: tuple[Any, ...], anchor: str, expected: tuple[int, int]) -> None:
    doc = parse_file('positions.json')
    assert doc.is_json and doc.ok
    assert doc.position(path, anchor) == expected


def test_positions_in_json_with_a_duplicate_key() -> None:
    # JSON with a duplicate key stays JSON (the last value wins); positions still work.
    doc = parse('{"a": {"b": 1},\n "a": {"c": [10, 20]}}')
    assert doc.is_json is True
    assert doc.data == {'a': {'c': [10, 20]}}
    assert [(d.code, d.line, d.column) for d in doc.diagnostics] == [('NODL006', 2, 2)]
    assert doc.position(('a', 'c', 1)) == (2, 18)


def test_position_of_an_unparseable_document_is_unknown() -> None:
    doc = ParsedDocument(SourceText('a: [\n', 'bad.yaml'))
    assert doc.position(('a',)) == (0, 0)
    doc = ParsedDocument(SourceText('a: \ud800\n', 'bad.yaml'))
    assert doc.position(('a',)) == (0, 0)


def test_positions_come_from_the_source_map_the_parse_kept(monkeypatch: pytest.MonkeyPatch) -> None:
    """Existing paths with string keys are placed without parsing the text again."""
    doc = parse_file('positions.yaml')

    def no_second_parse(*args: Any, **kwargs: Any) -> None:
        raise AssertionError('the text was parsed again to place a path')

    monkeypatch.setattr(yaml, 'compose', no_second_parse)
    assert doc.position(('parameters', 'speed', 'type'), 'key') == (4, 5)
    assert doc.position(('parameters', 'quoted key', 'type'), 'value') == (6, 24)
    assert doc.position(('publishers', 1, 'name'), 'value') == (10, 11)
    assert doc.position(('publishers', 1), 'key') == (10, 5)
    assert doc.position(('defaults', 'description'), 'value') == (17, 16)
    assert doc.position((), 'value') == (1, 1)
    # an alias is placed where its anchor is written, as the node tree places it
    aliased = parse('a: &x\n  k: v\nb: *x\n')
    assert aliased.position(('b', 'k'), 'value') == (2, 6)
    assert aliased.position(('b',), 'key') == (3, 1)


def _composed_position(root: Any, path: tuple[Any, ...], anchor: str) -> tuple[int, int]:
    """The reference: the position PyYAML's node tree ``root`` gives an existing path."""
    node, key_node = root, None
    for part in path:
        if isinstance(node, yaml.MappingNode):
            key_node, node = [(k, v) for k, v in node.value if k.value == part][-1]
        else:
            key_node, node = None, node.value[part]
    mark = key_node.start_mark if anchor == 'key' and key_node is not None else node.start_mark
    return (mark.line + 1, mark.column + 1)


def _paths(data: Any, prefix: tuple[Any, ...] = ()) -> Any:
    yield prefix
    items = data.items() if isinstance(data, dict) else enumerate(data) if isinstance(data, list) else ()
    for key, value in items:
        yield from _paths(value, prefix + (key,))


def test_the_source_map_places_every_path_as_the_node_tree_does() -> None:
    from nodl.frontends import yaml_events

    files = sorted(p for p in (REPO / 'tests' / 'fixtures').rglob('*.yaml') if p.is_file())
    placed = 0
    for file in files:
        text = file.read_text(encoding='utf-8', errors='replace')
        spans: dict[Any, Any] = {}
        try:
            data, problems = yaml_events.build(yaml_events.event_source(text), spans)
        except (yaml.YAMLError, yaml_events.Stop, UnicodeEncodeError):
            continue
        if problems:
            continue
        root = yaml.compose(text, Loader=getattr(yaml, 'CSafeLoader', yaml.SafeLoader))
        for path in _paths(data):
            for anchor in ('key', 'value'):
                found = yaml_events.span_position(spans, path, anchor)
                if found is not None:
                    placed += 1
                    assert found == _composed_position(root, path, anchor), (file, path, anchor)
    assert placed > 1000  # the fixtures hold plenty of paths the map places


def test_place_fills_in_file_line_and_column(positions: ParsedDocument) -> None:
    loose = Diagnostic(Severity.WARNING, 'w', ('parameters', 'speed', 'type'), anchor='key')
    placed = positions.place(loose)
    assert (placed.file, placed.line, placed.column) == (str(FRONTENDS / 'positions.yaml'), 4, 5)
    assert placed.message == 'w' and placed.severity is Severity.WARNING
    already = Diagnostic(Severity.ERROR, 'e', ('parameters',), 'x.yaml', 9, 9)
    assert positions.place(already) is already


def test_check_source_places_validation_errors() -> None:
    report = check_source(FRONTENDS / 'positions.yaml', kind='interface')
    by_path = {d.path: d for d in report.errors}
    unknown = by_path[('flags',)]
    assert (unknown.line, unknown.column) == (12, 1)


# --- limits are exported and sane -------------------------------------------------------

def test_limits() -> None:
    assert MAX_DEPTH == 100
    assert MAX_ALIAS_NODES == 10_000


def test_a_lone_surrogate_given_straight_to_the_parser_is_an_error() -> None:
    problem = only(parse('a: \ud800\n'))
    assert 'not valid Unicode' in problem.message
    # Raw JSON text with a lone surrogate parses; its positions are unknown, not a crash.
    doc = parse('{"a": "\ud800"}')
    assert doc.data == {'a': '\ud800'}
    assert doc.position(('a',)) == (0, 0)


def test_parse_document_never_raises_on_syntax_errors() -> None:
    cases = {
        'a: [': (2, 1), 'a: b: c': (1, 5), '{"a" 1}': (1, 6), '{"a": 1,, }': (1, 9),
        'a: *missing': (1, 4), ']': (1, 1), 'a: "unterminated': (1, 17),
        '%FOO\n---\na: 1': (1, 5), '\x00': (1, 1), 'a: \x01': (1, 4),
        'a: 1\nb: "\x7f\x1b"': (2, 5),
    }
    for text, where in cases.items():
        problem = only(parse(text))
        assert (problem.line, problem.column) == where, text
        assert problem.message


def test_control_characters_are_placed() -> None:
    problem = only(parse('type: int\ndescription: "é€\x07"\n'))
    assert problem.message.startswith('document contains a character that is not allowed (#x0007)')
    assert (problem.line, problem.column) == (2, 17)


def test_an_anchor_defined_twice_is_one_clear_error() -> None:
    problem = only(parse('a: &x 1\nb: &x 2\nc: *x\n'))
    assert problem.message.startswith('YAML anchor defined twice (first defined at line 1)')
    assert (problem.line, problem.column) == (2, 4)
