"""The event pass's own rules (nodl.frontends.yaml_events): the nesting limit
applied before any parser's limit, merge keys by the YAML specification, and the list of
anchors, aliases and merge keys it keeps for readers that refuse them."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from nodl.frontends import yaml_events
from nodl.frontends.yaml_events import MAX_DEPTH, TOO_DEEP, Stop

FRONTENDS = Path(__file__).parent / 'fixtures' / 'frontends'
DEEP = f'document nests deeper than {MAX_DEPTH} levels; NoDL documents are never this deep'


def stop_of(text: str) -> Stop:
    with pytest.raises(Stop) as info:
        yaml_events.read(text)
    return info.value


def where(stop: Stop) -> tuple[int, int]:
    return (stop.mark.line + 1, stop.mark.column + 1)


# --- the nesting limit comes before libyaml's -------------------------------------------

@pytest.mark.parametrize('levels', [101, 150, 999, 1000, 1001, 1100, 5000, 1_000_000])
@pytest.mark.parametrize('opener', ['[', '{'])
def test_flow_nesting_on_one_line_is_the_toolkits_error_at_level_101(
        levels: int, opener: str) -> None:
    # libyaml's scanner reads up to 1,024 characters of a line ahead of its events and has
    # a limit of its own (1,000 levels in PyYAML 6.0.4): the toolkit's comes first
    # (the mapping or list the flow collections are in is level 1)
    for text, column in (('a: ' + opener * levels, 4 + MAX_DEPTH - 1),
                         ('- ' + opener * levels, 3 + MAX_DEPTH - 1),
                         ('x: 1\ny: [' + opener * levels, 5 + MAX_DEPTH - 2)):
        stop = stop_of(text)
        assert (stop.code, stop.message) == (TOO_DEEP, DEEP), text[:20]
        assert where(stop) == (text.count('\n') + 1, column), text[:20]


@pytest.mark.parametrize('levels', [101, 1001, 100_000])
def test_balanced_flow_nesting_at_the_document_level(levels: int) -> None:
    stop = stop_of('[' * levels + ']' * levels)
    assert (stop.code, where(stop)) == (TOO_DEEP, (1, 101))


def test_json_nesting_is_placed_at_the_collection_that_crosses() -> None:
    stop = stop_of('{"a": ' + '[' * 5000 + ']' * 5000 + '}')
    assert (stop.code, where(stop)) == (TOO_DEEP, (1, 7 + MAX_DEPTH - 1))
    stop = stop_of('{"a": ' * 5000 + '1' + '}' * 5000)
    assert (stop.code, where(stop)) == (TOO_DEEP, (1, 6 * MAX_DEPTH + 1))


def test_exactly_the_limit_is_read() -> None:
    data, problems = yaml_events.read('a: ' + '[' * 99 + '1' + ']' * 99)
    assert problems == []
    for _ in range(MAX_DEPTH):
        (data,) = data.values() if isinstance(data, dict) else data
    assert data == 1
    assert stop_of('a: ' + '[' * 100 + ']' * 100).code == TOO_DEEP


@pytest.mark.parametrize('text, expected', [
    ('a: "' + '[' * 3000 + '"\n', {'a': '[' * 3000}),
    ("a: '" + '{' * 3000 + "'\n", {'a': '{' * 3000}),
    ("a: ['x''" + '[' * 3000 + "']\n", {'a': ["x'" + '[' * 3000]}),
    ('a: 1 # ' + '[' * 3000 + '\n', {'a': 1}),
    ('a: x' + '[' * 3000 + '\n', {'a': 'x' + '[' * 3000}),
    ('a: |\n  ' + '[' * 3000 + '\nb: 1\n', {'a': '[' * 3000 + '\n', 'b': 1}),
    ('- k: >-\n    ' + '{' * 3000 + '\n  j: 2\n', [{'k': '{' * 3000, 'j': 2}]),
    ('a: !!str "' + '[' * 3000 + '"\n', {'a': '[' * 3000}),
    ('a: &x "' + '[' * 3000 + '"\nb: *x\n', {'a': '[' * 3000, 'b': '[' * 3000}),
], ids=['double-quoted', 'single-quoted', 'quote-escape', 'comment', 'plain', 'literal',
        'folded-in-list', 'tagged', 'anchored'])
def test_brackets_in_scalars_and_comments_are_no_nesting(text: str, expected: Any) -> None:
    data, problems = yaml_events.read(text)
    assert (data, problems) == (expected, [])


@pytest.mark.parametrize('text, at', [
    # a quote the scan takes for the start of a quoted scalar, that is not one ('tis in a
    # plain scalar's next line): the parser's limit is then met first, and it is still the
    # toolkit's error, at the collection that crosses the limit
    ("a: word\n  'tis\nb: " + '[' * 3000, (3, 4 + MAX_DEPTH - 1)),
    ("a: word\n  'tis\nb: " + '[' * 5_000_000, (3, 4 + MAX_DEPTH - 1)),
], ids=['3000', '5m'])
def test_nesting_the_scan_cannot_see_is_still_the_toolkits_error(text: str, at: tuple[int, int]
                                                                  ) -> None:
    assert yaml_events._flow_crossing(text) == -1  # (the case this test is about)
    stop = stop_of(text)
    assert (stop.code, stop.message, where(stop)) == (TOO_DEEP, DEEP, at)


def test_the_scan_never_counts_too_few() -> None:
    # ']' in a plain scalar outside every flow collection takes nothing off
    text = 'a: x]]]]]\nb: ' + '[' * 101
    assert yaml_events._flow_crossing(text) == text.index('[') + MAX_DEPTH
    # a closing bracket inside a quoted scalar in a flow collection does not close it
    text = 'b: [ "]]]]", ' + '[' * 100
    assert yaml_events._flow_crossing(text) == len(text) - 1


def test_multi_line_nesting_stops_at_level_101() -> None:
    for text in ('[\n' * 5000, ''.join(' ' * i + 'k:\n' for i in range(2000)),
                 ''.join(' ' * i + '-\n' for i in range(2000))):
        stop = stop_of(text)
        assert stop.code == TOO_DEEP and stop.mark.line + 1 == MAX_DEPTH + 1


# --- merge keys by the specification ------------------------------------------------------

def test_merge_keys_follow_the_specification() -> None:
    text = (FRONTENDS / 'merge_order.yaml').read_text(encoding='utf-8')
    expected = json.loads((FRONTENDS / 'merge_order.expected.json').read_text(encoding='utf-8'))
    data, problems = yaml_events.read(text)
    assert problems == []
    assert data == expected


def test_a_key_written_after_or_before_the_merge_wins() -> None:
    text = 'a: &a {k: 1, m: 1}\nb: &b {k: 2, n: 2}\nc: {k: 0, <<: [*a, *b]}\nd: {<<: [*b, *a], k: 0}\n'
    data, _ = yaml_events.read(text)
    assert data['c'] == {'k': 0, 'm': 1, 'n': 2}
    assert data['d'] == {'k': 0, 'm': 1, 'n': 2}
    text = 'a: &a {long_key: 1}\nb: &b {long_key: 2}\nc: {<<: [*a, *b]}\nd: {<<: [*b, *a]}\n'
    data, _ = yaml_events.read(text)
    assert (data['c'], data['d']) == ({'long_key': 1}, {'long_key': 2})


# --- anchors, aliases and merge keys, listed ------------------------------------------------

def test_anchors_aliases_and_merge_keys_are_listed_in_order() -> None:
    seen: list[tuple[str, Any]] = []
    yaml_events.read('a: &x 1\nb: *x\nc: &m {k: 1}\nd:\n  <<: *m\ne: [&y 2]\n', None, seen)
    assert [(kind, mark.line + 1, mark.column + 1) for kind, mark in seen] == [
        ('anchor', 1, 4), ('alias', 2, 4), ('anchor', 3, 4), ('merge', 5, 3), ('alias', 5, 7),
        ('anchor', 6, 5)]


def test_nothing_is_listed_without_anchors() -> None:
    seen: list[tuple[str, Any]] = []
    yaml_events.read('a: 1\nb: [1, 2]\nc: {"<<": 1}\n', None, seen)
    assert seen == []

