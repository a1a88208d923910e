"""The built-in validator table: every validator once, and every consumer agreeing with it."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
import yaml

from nodl.model.parameter_types import parse_type
from nodl.validation.parameters import check_parameter
from nodl.validation.validators import (
    APPLICABILITY,
    ARGUMENT_SHAPES,
    BUILTIN_NAMES,
    VALIDATORS,
    applicable_types,
    bare_name,
    lookup,
    value_problems,
)

ROOT = Path(__file__).resolve().parent.parent
CASES: dict[str, Any] = yaml.safe_load(
    (Path(__file__).parent / 'fixtures' / 'validators' / 'cases.yaml').read_text())
SCHEMA = json.loads((ROOT / 'nodl' / 'schemas' / 'parameter.schema.json').read_text())


def test_every_validator_has_a_case() -> None:
    assert list(CASES) == list(BUILTIN_NAMES)


def test_table_rows_are_complete() -> None:
    for rule in VALIDATORS.values():
        assert rule.applies in APPLICABILITY, rule.name
        assert rule.shape in ARGUMENT_SHAPES, rule.name
        assert callable(rule.predicate) and callable(rule.requirement) and callable(rule.failure)


def test_schema_lists_the_same_validators_with_the_same_shapes() -> None:
    properties = SCHEMA['definitions']['validation']['properties']
    assert set(properties) == set(BUILTIN_NAMES) | {n + '<>' for n in BUILTIN_NAMES}
    for key, ref in properties.items():
        rule = VALIDATORS[bare_name(key)]
        assert ref == {'$ref': f'#/definitions/{rule.shape}_validator'}, key
    for shape in ARGUMENT_SHAPES:
        assert f'{shape}_validator' in SCHEMA['definitions'], shape


def test_readme_names_every_validator() -> None:
    from site_pages import docs_text

    readme = docs_text()
    for name in BUILTIN_NAMES:
        assert f'`{name}`' in readme, name


@pytest.mark.parametrize('name', list(CASES))
def test_applicability(name: str) -> None:
    assert applicable_types(VALIDATORS[name]) == tuple(CASES[name]['applies_to'])


@pytest.mark.parametrize('name', list(CASES))
def test_arguments_of_the_cases_have_the_right_shape(name: str) -> None:
    assert VALIDATORS[name].accepts(CASES[name]['args'])


@pytest.mark.parametrize(('shape', 'bad'), [
    ('bounds', [1]), ('bounds', [1, 'x']), ('bounds', 3), ('comparison', 'x'),
    ('comparison', [1, 2]), ('comparison', [True]), ('size', -1), ('size', [1.5]),
    ('one_of', [1, 2]), ('one_of', [[]]), ('subset_of', 'a'), ('no_arg', [1]),
])
def test_shapes_refuse_bad_arguments(shape: str, bad: Any) -> None:
    assert not ARGUMENT_SHAPES[shape].accepts(bad)


@pytest.mark.parametrize('name', list(CASES))
def test_predicate_and_wording(name: str) -> None:
    case, rule = CASES[name], VALIDATORS[name]
    for value in case['pass']:
        assert rule.check(value, case['args']) is None, value
    for value in case['fail']:
        assert rule.check(value, case['args']) is not None, value
    assert rule.check(case['fail'][0], case['args']) == case['failure']
    assert rule.describe(case['args']) == case['requirement']


@pytest.mark.parametrize('name', list(CASES))
def test_default_value_check_uses_the_table(name: str) -> None:
    """The definition check words a bad default exactly as the table does."""
    case = CASES[name]
    for value in case['pass']:
        out: list[Any] = []
        check_parameter({'type': case['type'], 'default_value': value,
                         'validation': {name + '<>': case['args']}}, (), out)
        assert out == [], (value, [d.message for d in out])
    bad = case['fail'][0]
    out = []
    check_parameter({'type': case['type'], 'default_value': bad,
                     'validation': {name + '<>': case['args']}}, (), out)
    assert [d.message.rsplit(': ', 1)[-1] for d in out] == [case['failure']]


def test_one_of_compares_kinds() -> None:
    rule = VALIDATORS['one_of']
    assert rule.check(1, [[1.0, 2.0]]) is None
    assert rule.check(True, [[1, 2]]) is not None
    assert rule.check('1', [[1]]) is not None


def test_lookup_and_bare_names() -> None:
    assert lookup('bounds<>') is VALIDATORS['bounds'] is lookup('bounds')
    assert lookup('my_ns::check') is None and lookup(3) is None
    assert bare_name('lt_eq<>') == 'lt_eq'


def test_value_problems_skips_what_does_not_apply() -> None:
    validation = {'bounds<>': [0, 10], 'size_gt': [3], 'my_ns::check': None, 'lt': 'bad'}
    assert value_problems(11, 'int', validation) == [('bounds<>', 'it is outside [0, 10]')]
    assert value_problems(5, 'int', validation) == []
    assert value_problems(5, 'no_such_type', validation) == []
    assert value_problems([1, 1], 'int_array_fixed_4', {'unique': None}) == [
        ('unique', '1 appears more than once')]


def test_applicability_words_cover_their_types() -> None:
    for applicability in APPLICABILITY.values():
        members = [n for n in ('bool', 'int', 'double', 'string', 'int_array', 'byte_array')
                   if applicability(parse_type(n))]
        assert members, applicability.name
