"""The parameter plan: struct tree, ROS types, ranges, validators; the Python translations agree."""

from __future__ import annotations

import itertools
from typing import Any

import pytest

from nodl.generate.python_text import VALIDATOR_EXPRESSIONS, docstring, literal, validator_expression
from nodl.model import ParameterDefinition
from nodl.plan.parameter_plan import (
    DOUBLE_MAX,
    INT64_MAX,
    INT64_MIN,
    plan_parameters,
    ros_type_of,
    type_problem,
    value_problems,
)
from nodl.validation.validators import VALIDATORS


def _plan(**parameters: dict[str, Any]) -> Any:
    return plan_parameters([(name.replace('__', '.'), ParameterDefinition.from_dict(d))
                            for name, d in parameters.items()])


def test_struct_tree_by_dotted_name_with_collisions_and_keywords() -> None:
    plan = _plan(a__b={'type': 'int', 'default_value': 1}, a={'type': 'int', 'default_value': 2},
                 a__c__d={'type': 'string', 'default_value': 'x'}, **{'class': {'type': 'bool', 'default_value': True}})
    assert [p.name for p in plan.parameters] == ['a', 'a.b', 'a.c.d', 'class']
    assert plan.get('a').path == ('a',)
    assert plan.get('a.b').path == ('a_2', 'b')  # the group yields to the leaf 'a'
    assert plan.get('a.c.d').path == ('a_2', 'c', 'd')
    assert plan.get('class').path == ('class_',)


def test_types_defaults_and_required() -> None:
    plan = _plan(x={'type': 'double'}, y={'type': 'byte_array', 'default_value': [1, 2]},
                 z={'type': 'string_array_fixed_2', 'default_value': ['a']}, n={'type': 'none'})
    assert plan.get('x').required and plan.get('x').ros_type == 'PARAMETER_DOUBLE'
    assert [p.name for p in plan.required] == ['x']
    assert plan.get('y').ros_type == 'PARAMETER_BYTE_ARRAY'
    assert plan.get('z').type.size == 2 and not plan.get('n').required and plan.get('n').dynamic_typing


@pytest.mark.parametrize('type_name,validation,expected', [
    ('int', {'bounds<>': [1, 120]}, ('integer', 1, 120)),
    ('int', {'gt<>': [0], 'lt<>': 10}, ('integer', 1, 9)),
    ('int', {'gt_eq<>': [2.5]}, ('integer', 3, INT64_MAX)),
    ('int', {'lt_eq<>': [-1]}, ('integer', INT64_MIN, -1)),
    ('double', {'gt<>': [0.0], 'lt<>': [1.0]}, ('floating_point', 0.0, 1.0)),
    ('double', {'bounds<>': [0, 2], 'lt_eq<>': [1.5]}, ('floating_point', 0.0, 1.5)),
    ('double', {'gt_eq<>': [0.5]}, ('floating_point', 0.5, DOUBLE_MAX)),
    ('double', {'one_of<>': [[1.0, 2.0]]}, None),
    ('int_array', {'element_bounds<>': [0, 1]}, None),
])
def test_ranges_from_validators(type_name: str, validation: dict[str, Any], expected: Any) -> None:
    plan = _plan(p={'type': type_name, 'default_value': None, 'validation': validation})
    rng = plan.get('p').range
    assert (rng and (rng.kind, rng.from_value, rng.to_value)) == expected
    if rng is not None:
        assert rng.step == 0


def test_types_as_strict_as_a_node() -> None:
    plan = _plan(d={'type': 'double', 'default_value': 1.0}, s={'type': 'string_fixed_3', 'default_value': 'a'},
                 a={'type': 'int_array', 'default_value': [1]}, b={'type': 'byte_array', 'default_value': [1]})
    assert type_problem(plan.get('d'), 1) == 'expected double, got integer'
    assert type_problem(plan.get('d'), 1.0) is None
    assert type_problem(plan.get('s'), 'abcd') is not None
    assert type_problem(plan.get('a'), []) is None
    assert type_problem(plan.get('a'), [1, 'x']) == 'expected integer array, got a list of mixed types'
    assert ros_type_of([b'\x01', b'\x02']) == 'PARAMETER_BYTE_ARRAY'
    assert value_problems(plan.get('b'), b'\x01\x02') == []


def test_custom_validators_are_kept_apart() -> None:
    plan = _plan(c={'type': 'int', 'default_value': 2, 'validation': {'my_pkg::is_even': [], 'gt<>': [0]}})
    param = plan.get('c')
    assert [v.name for v in param.custom_validators] == ['my_pkg::is_even']
    assert [v.name for v in param.builtin_validators] == ['gt']
    assert value_problems(param, 0) == ['must be greater than 0']


SAMPLES: dict[str, list[Any]] = {
    'numeric': [-5, -1, 0, 1, 2, 2.5, 10, 11, 120, 1e9],
    'scalar': [0, 1, 2, 1.0, 'a', 'b', 'fast', True, False],
    'sized': ['', 'a', 'abc', [], [1], [1, 2], [1, 1], ['a', 'b', 'c']],
    'array': [[], [1], [1, 2], [1, 1], ['a', 'b'], ['a', 'z'], [0.5, 3.0]],
    'numeric_array': [[], [0], [1, 2], [-1, 5], [0.5, 3.0], [255, 7]],
}
ARGUMENTS: dict[str, list[Any]] = {
    'bounds': [[0, 10], [0.5, 2.5]],
    'comparison': [[0], 2, [2.5]],
    'size': [[0], 1, [2]],
    'one_of': [[[1, 2, 'fast']], [['a', 'b']]],
    'subset_of': [[['a', 'b', 1]], [[1, 2]]],
    'no_arg': [None],
}


@pytest.mark.parametrize('name', sorted(VALIDATORS))
def test_python_translation_agrees_with_the_validator_table(name: str) -> None:
    """The generated code carries its own copy of each predicate: this keeps the copies equal."""
    rule = VALIDATORS[name]
    assert name in VALIDATOR_EXPRESSIONS
    for raw, value in itertools.product(ARGUMENTS[rule.shape], SAMPLES[rule.applies]):
        argument = rule.argument(raw)
        expression = validator_expression(name, argument)
        try:
            expected = bool(rule.predicate(value, argument))
        except TypeError:
            continue  # a value of another type than the validator applies to
        assert eval(f'lambda v: {expression}')(value) == expected, (name, raw, value, expression)


def test_literals_and_docstrings_are_escaped() -> None:
    assert literal([1.0, 'a', b'\x01', float('inf')]) == "[1.0, 'a', b'\\x01', float('inf')]"
    text = docstring('ends with a quote" and has """ and \\ inside')
    assert eval(text) == 'ends with a quote" and has """ and \\ inside'
