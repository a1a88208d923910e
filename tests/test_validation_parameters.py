"""Parameter semantics: nodl.validation.parameters.

Types and their defaults, fixed sizes, validator names, validators against
types, conflicting validators, validator arguments and defaults against
validators.  Documents are checked with the whole engine (structure, then
semantics), as a user's file is.
"""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nodl.diagnostics import Diagnostic, Severity
from nodl.model.parameter_types import ARRAY_TYPES, FIXED_BASES, SCALAR_TYPES
from nodl.validation import Kind, validate_data
from nodl.validation.parameters import BUILTIN_VALIDATORS, check_parameter, check_parameter_type, check_validator_name


def diagnostics(param: dict[str, Any]) -> list[Diagnostic]:
    return validate_data(param, Kind.PARAMETER)


def errors(param: dict[str, Any]) -> list[Diagnostic]:
    return [d for d in diagnostics(param) if d.severity is Severity.ERROR]


def warnings(param: dict[str, Any]) -> list[Diagnostic]:
    return [d for d in diagnostics(param) if d.severity is Severity.WARNING]


def messages(found: list[Diagnostic]) -> list[str]:
    return [d.message for d in found]


def param(type_: str, default: Any = ..., **validation: Any) -> dict[str, Any]:
    out: dict[str, Any] = {'type': type_, 'description': 'test'}
    if default is not ...:
        out['default_value'] = default
    if validation:
        out['validation'] = {k.replace('__', '::').replace('_LTGT', '<>'): v
                             for k, v in validation.items()}
    return out


def with_validators(type_: str, default: Any, validators: dict[str, Any]) -> dict[str, Any]:
    out = param(type_, default)
    out['validation'] = validators
    return out


# -- types and defaults ------------------------------------------------------

GOOD_DEFAULTS = {
    'bool': [True, False],
    'int': [0, -7, 2**40],
    'double': [0.5, -1e10, 3],          # an integer literal is a valid double
    'string': ['', 'map', '\u00e9t\u00e9'],
    'bool_array': [[], [True, False]],
    'int_array': [[], [1, -2, 3]],
    'double_array': [[], [0.5, 2]],
    'string_array': [[], ['a', '']],
    'byte_array': [[], [0, 1, 127, 255]],
}


def test_every_type_is_covered() -> None:
    assert set(GOOD_DEFAULTS) | {'none'} == set(SCALAR_TYPES + ARRAY_TYPES)


@pytest.mark.parametrize(('type_', 'default'), [
    (t, d) for t, defaults in GOOD_DEFAULTS.items() for d in defaults])
def test_good_defaults(type_: str, default: Any) -> None:
    assert diagnostics(param(type_, default)) == []


@pytest.mark.parametrize('type_', SCALAR_TYPES + ARRAY_TYPES + tuple(
    f'{base}_fixed_3' for base in FIXED_BASES))
def test_every_type_without_a_default(type_: str) -> None:
    assert diagnostics(param(type_)) == []


BAD_DEFAULTS = [
    ('int', 'hello',
     "default_value of an int parameter must be an integer, not a string ('hello')"),
    ('int', 1.5, 'default_value of an int parameter must be an integer, not a number (1.5)'),
    ('int', True, 'default_value of an int parameter must be an integer, not a boolean (true)'),
    ('bool', 1, 'default_value of a bool parameter must be a boolean, not an integer (1)'),
    ('bool', 'true', "default_value of a bool parameter must be a boolean, not a string ('true')"),
    ('double', 'x', "default_value of a double parameter must be a number, not a string ('x')"),
    ('double', False,
     'default_value of a double parameter must be a number, not a boolean (false)'),
    ('string', 5, 'default_value of a string parameter must be a string, not an integer (5)'),
    ('string', ['a'], "default_value of a string parameter must be a string, not a list (['a'])"),
    ('string', {'a': 1}, 'default_value of a string parameter must be a string, not a mapping'),
    ('int_array', 5, 'default_value of an int_array parameter must be a list of int values, '
                     'not an integer (5)'),
    ('string_array', 'a', "default_value of a string_array parameter must be a list of string "
                          "values, not a string ('a')"),
    ('string_fixed_3', 5, 'default_value of a string_fixed_3 parameter must be a string, '
                          'not an integer (5)'),
]


@pytest.mark.parametrize(('type_', 'default', 'message'), BAD_DEFAULTS)
def test_default_of_the_wrong_type(type_: str, default: Any, message: str) -> None:
    found = diagnostics(param(type_, default))
    assert [(d.severity, d.path, d.message) for d in found] == [
        (Severity.ERROR, ('default_value',), message)]


@pytest.mark.parametrize(('type_', 'default', 'index', 'message'), [
    ('int_array', [1, 'a'], 1, "element 1 of default_value must be an integer, not a string ('a')"),
    ('int_array', [1.5], 0, 'element 0 of default_value must be an integer, not a number (1.5)'),
    ('double_array', [1.0, True], 1,
     'element 1 of default_value must be a number, not a boolean (true)'),
    ('bool_array', [1], 0, 'element 0 of default_value must be a boolean, not an integer (1)'),
    ('string_array', ['a', None], 1, 'element 1 of default_value must be a string, not null'),
    ('byte_array', ['a'], 0,
     "element 0 of default_value must be an integer from 0 to 255, not a string ('a')"),
])
def test_array_default_with_a_bad_element(type_: str, default: list, index: int,
                                          message: str) -> None:
    found = diagnostics(param(type_, default))
    assert [(d.severity, d.path, d.message) for d in found] == [
        (Severity.ERROR, ('default_value', index), message)]


def test_every_bad_element_is_reported() -> None:
    found = errors(param('int_array', ['a', 2, 'b', 4.5]))
    assert [d.path for d in found] == [('default_value', 0), ('default_value', 2),
                                       ('default_value', 3)]


@pytest.mark.parametrize('value', [0, 1, 128, 254, 255])
def test_byte_array_accepts_0_to_255(value: int) -> None:
    assert diagnostics(param('byte_array', [value])) == []


@pytest.mark.parametrize('value', [256, -1, 1000, -256])
def test_byte_array_rejects_values_outside_0_to_255(value: int) -> None:
    found = diagnostics(param('byte_array', [0, value, 255]))
    assert [(d.severity, d.path, d.message) for d in found] == [
        (Severity.ERROR, ('default_value', 1),
         f'element 1 of default_value is {value}; a byte_array holds integers from 0 to 255')]


@pytest.mark.parametrize('value', [True, 1.0, 'x'])
def test_byte_array_rejects_non_integers(value: Any) -> None:
    found = errors(param('byte_array', [value]))
    assert len(found) == 1
    assert 'must be an integer from 0 to 255' in found[0].message


def test_null_default_is_an_error() -> None:
    found = diagnostics(param('string', None))
    assert [(d.severity, d.path) for d in found] == [(Severity.ERROR, ('default_value',))]
    assert found[0].message == ('default_value is null; a string parameter needs a string (leave '
                                'default_value out to make the parameter required at start-up)')


@pytest.mark.parametrize('type_', ['int', 'bool', 'double_array', 'byte_array', 'string_fixed_4'])
def test_null_default_is_an_error_for_every_type(type_: str) -> None:
    found = errors(param(type_, None))
    assert len(found) == 1 and found[0].message.startswith('default_value is null')


@pytest.mark.parametrize('default', [3, None, 'x', [1]])
def test_none_type_with_a_default_is_a_warning(default: Any) -> None:
    found = diagnostics(param('none', default))
    assert [(d.severity, d.path, d.anchor) for d in found] == [
        (Severity.WARNING, ('default_value',), 'key')]
    assert found[0].message == ("a parameter of type 'none' holds no value; its default_value is "
                                'ignored')


def test_none_type_takes_no_validators() -> None:
    found = diagnostics(param('none', not_empty_LTGT=None))
    assert [(d.severity, d.path) for d in found] == [(Severity.ERROR, ('validation',))]
    assert 'takes no validators' in found[0].message


# -- fixed-size types ----------------------------------------------------------

@pytest.mark.parametrize('size', [1, 3, 10])
def test_string_fixed_length_limit(size: int) -> None:
    type_ = f'string_fixed_{size}'
    assert diagnostics(param(type_, 'x' * size)) == []
    assert diagnostics(param(type_, '')) == []
    found = diagnostics(param(type_, 'x' * (size + 1)))
    assert [(d.severity, d.path, d.message) for d in found] == [
        (Severity.ERROR, ('default_value',),
         f'default_value has {size + 1} characters; {type_} holds at most {size}')]


_ELEMENT = {'int_array': 7, 'double_array': 0.5, 'string_array': 's'}


@pytest.mark.parametrize('size', [1, 2, 10])
@pytest.mark.parametrize('base', ['int_array', 'double_array', 'string_array'])
def test_array_fixed_element_count_limit(base: str, size: int) -> None:
    type_ = f'{base}_fixed_{size}'
    element = _ELEMENT[base]
    assert diagnostics(param(type_, [element] * size)) == []
    assert diagnostics(param(type_, [])) == []
    found = diagnostics(param(type_, [element] * (size + 1)))
    assert [(d.severity, d.path, d.message) for d in found] == [
        (Severity.ERROR, ('default_value',),
         f'default_value has {size + 1} elements; {type_} holds at most {size}')]


def test_fixed_array_checks_elements_too() -> None:
    found = errors(param('int_array_fixed_2', ['a', 1, 2]))
    assert [d.path for d in found] == [('default_value', 0), ('default_value',)]


@pytest.mark.parametrize('type_', ['bool_array_fixed_3', 'bool_array_fixed_1'])
def test_fixed_bool_arrays_are_rejected(type_: str) -> None:
    found = diagnostics(param(type_))
    assert [(d.severity, d.path) for d in found] == [(Severity.ERROR, ('type',))]
    assert found[0].message == (f"'{type_}' is not supported: there are no fixed-size bool arrays "
                                '(use bool_array)')


@pytest.mark.parametrize('type_', ['string_fixed_0', 'int_array_fixed_00', 'string_fixed_03'])
def test_fixed_size_must_be_positive_without_leading_zeros(type_: str) -> None:
    found = errors(param(type_))
    assert len(found) == 1
    assert 'positive number without leading zeros' in found[0].message


@pytest.mark.parametrize(('type_', 'suggestion'), [
    ('integer', 'int'), ('boolean', 'bool'), ('String', 'string'), ('doubles', 'double'),
    ('int_arrays', 'int_array'), ('bytearray', 'byte_array')])
def test_unknown_type_suggests_the_closest(type_: str, suggestion: str) -> None:
    found = errors(param(type_))
    assert len(found) == 1 and found[0].path == ('type',)
    assert found[0].message.startswith(f"unknown parameter type '{type_}'; expected one of: bool, ")
    assert 'string_fixed_N' in found[0].message
    assert found[0].message.endswith(f"did you mean '{suggestion}'?")


@pytest.mark.parametrize('type_', ['int_fixed_3', 'double_fixed_2', 'float', 'byte_array_fixed_2',
                                   'none_array'])
def test_unknown_types(type_: str) -> None:
    found = errors(param(type_))
    assert len(found) == 1 and found[0].message.startswith('unknown parameter type')


def test_non_string_type() -> None:
    out: list = []
    check_parameter_type(5, ('type',), out)
    assert messages(out) == ["'type' must be a string, not an integer (5)"]


def test_unknown_type_skips_the_default_checks() -> None:
    # The default cannot be judged against an unknown type: one error only.
    assert len(errors(param('integer', 'x', bounds_LTGT=[0, 1]))) == 1


# -- validator names ---------------------------------------------------------

# A use of every built-in validator that a fitting default satisfies.
BUILTIN_USES: dict[str, tuple[str, Any, Any]] = {
    'bounds': ('int', 5, [0, 10]),
    'lt': ('double', 0.5, [1.0]),
    'gt': ('double', 2.0, [1.0]),
    'lt_eq': ('int', 10, [10]),
    'gt_eq': ('int', 0, [0]),
    'one_of': ('string', 'b', [['a', 'b']]),
    'not_empty': ('string', 'x', None),
    'fixed_size': ('int_array', [1, 2], [2]),
    'size_gt': ('string', 'abc', [2]),
    'size_lt': ('string_array', ['a'], [2]),
    'unique': ('string_array', ['a', 'b'], None),
    'subset_of': ('int_array', [1, 3], [[1, 2, 3]]),
    'element_bounds': ('double_array', [0.0, 1.0], [0.0, 1.0]),
    'lower_element_bounds': ('int_array', [0, 5], [0]),
    'upper_element_bounds': ('byte_array', [0, 5], [5]),
}


def test_every_builtin_is_covered() -> None:
    assert set(BUILTIN_USES) == set(BUILTIN_VALIDATORS)


@pytest.mark.parametrize('suffix', ['<>', ''])
@pytest.mark.parametrize('name', sorted(BUILTIN_USES))
def test_every_builtin_with_and_without_angle_brackets(name: str, suffix: str) -> None:
    type_, default, args = BUILTIN_USES[name]
    assert diagnostics(with_validators(type_, default, {name + suffix: args})) == []
    out: list = []
    check_validator_name(name + suffix, ('validation', name + suffix), out)
    assert out == []


@pytest.mark.parametrize(('name', 'scalar'), [
    ('lt', 1.0), ('gt', 1.0), ('lt_eq', 10), ('gt_eq', 0), ('fixed_size', 2), ('size_gt', 2),
    ('size_lt', 2), ('lower_element_bounds', 0), ('upper_element_bounds', 5)])
def test_single_argument_validators_take_a_bare_value_too(name: str, scalar: Any) -> None:
    type_, default, _ = BUILTIN_USES[name]
    assert diagnostics(with_validators(type_, default, {name + '<>': scalar})) == []


@pytest.mark.parametrize('name', ['not_empty', 'unique'])
def test_no_argument_validators_take_null_or_an_empty_list(name: str) -> None:
    type_, default, _ = BUILTIN_USES[name]
    for args in (None, []):
        assert diagnostics(with_validators(type_, default, {name + '<>': args})) == []


@pytest.mark.parametrize('name', ['my_ns::positive', 'my_ns::positive<>', 'a::b::c<>',
                                  'is_positive', 'is_positive<>', '_check', 'Check2<>'])
@pytest.mark.parametrize('args', [None, [], [1, 'a'], 3, 'text', True, 0.5])
def test_custom_validators_are_accepted(name: str, args: Any) -> None:
    assert diagnostics(with_validators('int', 1, {name: args})) == []


def test_custom_validator_arguments_cannot_be_a_mapping() -> None:
    found = diagnostics(with_validators('int', 1, {'my_ns::check': {'a': 1}}))
    assert [(d.severity, d.path) for d in found] == [
        (Severity.ERROR, ('validation', 'my_ns::check'))]
    assert found[0].message.startswith("'my_ns::check' must be null, a list, a number, a string or")


@pytest.mark.parametrize(('name', 'suggestion'), [
    ('bonds<>', 'bounds<>'), ('bonds', 'bounds'), ('one_off<>', 'one_of<>'),
    ('Bounds<>', 'bounds<>'), ('notempty<>', 'not_empty<>'), ('element_bound', 'element_bounds'),
    ('lt_equal<>', 'lt_eq<>')])
def test_bare_name_close_to_a_builtin_is_a_warning(name: str, suggestion: str) -> None:
    found = diagnostics(with_validators('int', 1, {name: [0, 10]}))
    assert [(d.severity, d.path, d.anchor) for d in found] == [
        (Severity.WARNING, ('validation', name), 'key')]
    assert found[0].message == (f"'{name}' is not a built-in validator and will be called as a "
                                f"custom function, did you mean '{suggestion}'?")


@pytest.mark.parametrize('name', ['finite<>', 'is_odd', 'in_range<>', 'my_pkg::bonds<>',
                                  'my_pkg::bounds'])
def test_unrelated_or_qualified_names_get_no_suggestion(name: str) -> None:
    # A qualified name is plainly a custom function; '<>' alone must not make
    # two names look alike ('finite<>' and 'unique<>').
    assert diagnostics(with_validators('int', 1, {name: None})) == []


@pytest.mark.parametrize('name', ['bad-name', '::leading', 'trailing::', 'a b', 'bounds<><>',
                                  '<>', 'ns:::f', '1st', 'f<int>'])
def test_invalid_validator_names(name: str) -> None:
    found = diagnostics(with_validators('int', 1, {name: None}))
    assert [(d.severity, d.path, d.anchor) for d in found] == [
        (Severity.ERROR, ('validation', name), 'key')]
    assert found[0].message.startswith(f"'{name}' is not a validator name: use a built-in "
                                       'validator (bounds<>, lt<>,')
    assert 'C++ function name (my_namespace::my_check)' in found[0].message


# -- validators against types --------------------------------------------------

NOT_FITTING = [
    ('string', 'x', 'bounds<>', [0, 1], 'a string', 'int and double parameters'),
    ('string', 'x', 'lt', 3, 'a string', 'int and double parameters'),
    ('bool', True, 'gt_eq<>', [0], 'a bool', 'int and double parameters'),
    ('int_array', [1], 'bounds', [0, 1], 'an int array', 'int and double parameters'),
    ('double', 1.0, 'element_bounds<>', [0, 2], 'a double', 'int, double and byte arrays'),
    ('string_array', ['a'], 'element_bounds', [0, 2], 'a string array',
     'int, double and byte arrays'),
    ('bool_array', [True], 'lower_element_bounds<>', [0], 'a bool array',
     'int, double and byte arrays'),
    ('int', 1, 'upper_element_bounds', 3, 'an int', 'int, double and byte arrays'),
    ('int', 1, 'not_empty<>', None, 'an int', 'string and array parameters'),
    ('bool', True, 'size_gt', [1], 'a bool', 'string and array parameters'),
    ('double', 1.0, 'fixed_size<>', 1, 'a double', 'string and array parameters'),
    ('double_array', [1.0], 'one_of<>', [[1.0]], 'a double array',
     'bool, int, double and string parameters'),
    ('string', 'a', 'unique<>', None, 'a string', 'array parameters'),
    ('int', 1, 'subset_of<>', [[1]], 'an int', 'array parameters'),
    ('string_fixed_5', 'a', 'bounds<>', [0, 1], 'a string', 'int and double parameters'),
    ('int_array_fixed_2', [1], 'one_of', [[1]], 'an int array',
     'bool, int, double and string parameters'),
]


@pytest.mark.parametrize(('type_', 'default', 'key', 'args', 'kind', 'applies'), NOT_FITTING)
def test_validator_that_does_not_fit_the_type(type_: str, default: Any, key: str, args: Any,
                                              kind: str, applies: str) -> None:
    found = diagnostics(with_validators(type_, default, {key: args}))
    assert [(d.severity, d.path, d.anchor, d.message) for d in found] == [
        (Severity.ERROR, ('validation', key), 'key',
         f"'{key}' does not apply to {kind} parameter; it is for {applies}")]


@pytest.mark.parametrize(('type_', 'default'), [
    ('string_fixed_8', 'abc'), ('string_array_fixed_3', ['a']), ('byte_array', [1])])
def test_sized_validators_apply_to_strings_and_arrays(type_: str, default: Any) -> None:
    validators = {'not_empty<>': None, 'size_gt<>': [0], 'size_lt': 5}
    assert diagnostics(with_validators(type_, default, validators)) == []


# -- conflicts -----------------------------------------------------------------

@pytest.mark.parametrize('suffix', ['', '<>'])
@pytest.mark.parametrize('other', ['gt', 'lt', 'gt_eq', 'lt_eq'])
def test_bounds_conflicts_with_comparisons(other: str, suffix: str) -> None:
    found = diagnostics(with_validators('double', 1.0, {'bounds<>': [0.0, 2.0],
                                                        other + suffix: [0.5 if other[0] == 'g'
                                                                         else 1.5]}))
    assert [(d.severity, d.path, d.anchor, d.message) for d in found] == [
        (Severity.ERROR, ('validation', other + suffix), 'key',
         f"'bounds<>' conflicts with '{other + suffix}': give the range with one or the other, "
         'not both')]


@pytest.mark.parametrize('other', ['lower_element_bounds', 'upper_element_bounds<>'])
def test_element_bounds_conflicts_with_lower_and_upper(other: str) -> None:
    found = diagnostics(with_validators('int_array', [1], {'element_bounds': [0, 2], other: [1]}))
    assert [(d.severity, d.path, d.message) for d in found] == [
        (Severity.ERROR, ('validation', other),
         f"'element_bounds' conflicts with '{other}': give the range with one or the other, "
         'not both')]


def test_comparisons_without_bounds_do_not_conflict() -> None:
    validators = {'gt<>': [0], 'lt<>': [10], 'gt_eq': 0, 'lt_eq': 10}
    assert diagnostics(with_validators('int', 5, validators)) == []
    validators = {'lower_element_bounds<>': [0], 'upper_element_bounds<>': [10]}
    assert diagnostics(with_validators('int_array', [5], validators)) == []


@pytest.mark.parametrize('name', sorted(BUILTIN_USES))
def test_same_validator_with_and_without_angle_brackets(name: str) -> None:
    type_, default, args = BUILTIN_USES[name]
    found = diagnostics(with_validators(type_, default, {name: args, name + '<>': args}))
    assert [(d.severity, d.path, d.anchor, d.message) for d in found] == [
        (Severity.ERROR, ('validation', name + '<>'), 'key',
         f"'{name}' and '{name}<>' are the same validator; keep one")]


# -- validator arguments -------------------------------------------------------

@pytest.mark.parametrize(('type_', 'key', 'values', 'bad', 'word'), [
    ('int', 'one_of<>', [1, 'a'], [(1, "'a'")], 'an integer'),
    ('int', 'one_of<>', [1, 1.5, True], [(1, '1.5'), (2, 'true')], 'an integer'),
    ('bool', 'one_of', [True, 1], [(1, '1')], 'a boolean'),
    ('string', 'one_of<>', ['a', 1, None], [(1, '1'), (2, 'null')], 'a string'),
    ('double', 'one_of<>', ['x', 2], [(0, "'x'")], 'a number'),
])
def test_one_of_values_of_the_wrong_type(type_: str, key: str, values: list, bad: list,
                                         word: str) -> None:
    found = errors(param(type_) | {'validation': {key: [values]}})
    assert [(d.path, d.message) for d in found] == [
        (('validation', key, 0, index),
         f'{key} value {shown} is not {word}, so {"an" if type_ == "int" else "a"} {type_} '
         'parameter can never equal it')
        for index, shown in bad]


@pytest.mark.parametrize(('type_', 'values', 'index', 'word'), [
    ('int_array', [1, 'a'], 1, 'an integer'),
    ('string_array', ['scan', 3], 1, 'a string'),
    ('double_array', [True], 0, 'a number'),
    ('byte_array', [1, 300], 1, 'an integer from 0 to 255'),
])
def test_subset_of_values_of_the_wrong_type(type_: str, values: list, index: int,
                                            word: str) -> None:
    found = errors(param(type_) | {'validation': {'subset_of<>': [values]}})
    assert [d.path for d in found] == [('validation', 'subset_of<>', 0, index)]
    article = 'an' if type_[0] in 'aeiou' else 'a'
    assert found[0].message.endswith(
        f'is not {word}, so no element of {article} {type_} parameter can equal it')


@pytest.mark.parametrize('key', ['bounds<>', 'element_bounds'])
def test_lower_bound_greater_than_upper(key: str) -> None:
    type_ = 'int' if key == 'bounds<>' else 'int_array'
    found = diagnostics(param(type_) | {'validation': {key: [10, 0]}})
    assert [(d.severity, d.path, d.message) for d in found] == [
        (Severity.ERROR, ('validation', key),
         f'{key}: the lower bound 10 is greater than the upper bound 0')]


def test_equal_bounds_are_fine() -> None:
    assert diagnostics(with_validators('int', 5, {'bounds<>': [5, 5]})) == []


@pytest.mark.parametrize(('key', 'args'), [
    ('bounds<>', [0.5, 10]), ('gt<>', [0.5]), ('lt_eq', 2.5)])
def test_fractional_arguments_for_an_integer_parameter(key: str, args: Any) -> None:
    found = errors(param('int', 1) | {'validation': {key: args}})
    assert len(found) == 1 and found[0].path == ('validation', key)
    assert found[0].message.startswith(f'{key} of an integer parameter must use integers, not ')


def test_fractional_arguments_are_fine_for_a_double_and_integral_floats_for_an_int() -> None:
    assert diagnostics(with_validators('double', 1.0, {'bounds<>': [0.5, 10.5]})) == []
    assert diagnostics(with_validators('int', 1, {'bounds<>': [0.0, 10.0]})) == []


@pytest.mark.parametrize(('key', 'args'), [
    ('bounds<>', [1]), ('bounds<>', [1, 2, 3]), ('bounds', ['a', 'b']), ('bounds', 5),
    ('lt<>', [1, 2]), ('gt', 'high'), ('gt_eq<>', [True]), ('lt_eq', None),
    ('one_of<>', [1, 2]), ('one_of<>', []), ('one_of<>', [[]]),
])
def test_malformed_arguments_are_structural_errors(key: str, args: Any) -> None:
    found = errors(param('int') | {'validation': {key: args}})
    assert found, f'{key}: {args!r} was accepted'
    assert all(d.path[:2] == ('validation', key) for d in found)


@pytest.mark.parametrize(('key', 'args'), [
    ('fixed_size<>', -1), ('size_gt', [1.5]), ('size_lt<>', 'a'), ('unique<>', [1]),
    ('not_empty', 0), ('subset_of<>', [1]), ('element_bounds<>', [0])])
def test_malformed_arguments_of_array_validators(key: str, args: Any) -> None:
    found = errors(param('int_array') | {'validation': {key: args}})
    assert found, f'{key}: {args!r} was accepted'
    assert all(d.path[:2] == ('validation', key) for d in found)


# -- defaults against validators ---------------------------------------------

# (type, validator, args, a default that passes, a default that fails, the reason)
BREAKS = [
    ('int', 'bounds<>', [0, 10], 10, 500, 'it is outside [0, 10]'),
    ('int', 'bounds', [0, 10], 0, -1, 'it is outside [0, 10]'),
    ('double', 'lt<>', [5.0], 4.9, 5.0, 'it must be less than 5.0'),
    ('int', 'gt', 0, 1, 0, 'it must be greater than 0'),
    ('int', 'lt_eq<>', [10], 10, 11, 'it must be at most 10'),
    ('double', 'gt_eq', [0], 0.0, -0.5, 'it must be at least 0'),
    ('string', 'one_of<>', [['red', 'green']], 'green', 'purple',
     "it must be one of 'red' or 'green'"),
    ('int', 'one_of', [[1, 2, 3]], 3, 4, 'it must be one of 1, 2 or 3'),
    ('double', 'one_of<>', [[1, 2.5]], 1.0, 2.0, 'it must be one of 1 or 2.5'),
    ('bool', 'one_of<>', [[True]], True, False, 'it must be one of true'),
    ('string', 'not_empty<>', None, 'x', '', 'it must not be empty'),
    ('int_array', 'not_empty', [], [1], [], 'it must not be empty'),
    ('double_array', 'fixed_size<>', [3], [1.0, 2.0, 3.0], [1.0, 2.0],
     'its size must be exactly 3'),
    ('string', 'fixed_size', 2, 'ab', 'abc', 'its size must be exactly 2'),
    ('int_array', 'size_gt<>', [1], [1, 2], [1], 'its size must be greater than 1'),
    ('string', 'size_lt', 3, 'ab', 'abcdef', 'its size must be less than 3'),
    ('string_array', 'unique<>', [], ['a', 'b'], ['a', 'b', 'a'], "'a' appears more than once"),
    ('string_array', 'subset_of<>', [['scan', 'odom']], ['odom'], ['scan', 'gps'],
     "'gps' is not one of the allowed values"),
    ('double_array', 'element_bounds<>', [0.0, 1.0], [0.0, 1.0], [0.5, 2.5],
     'element 2.5 is outside [0.0, 1.0]'),
    ('int_array', 'lower_element_bounds<>', [0], [0, 3], [3, -1], 'element -1 is below 0'),
    ('byte_array', 'upper_element_bounds', 100, [100], [1, 200], 'element 200 is above 100'),
]


def test_every_builtin_is_checked_against_defaults() -> None:
    checked = {validator.rstrip('<>') for _, validator, *_ in BREAKS}
    assert checked == set(BUILTIN_VALIDATORS)


@pytest.mark.parametrize(('type_', 'key', 'args', 'good', 'bad', 'reason'), BREAKS)
def test_default_that_breaks_a_validator(type_: str, key: str, args: Any, good: Any, bad: Any,
                                         reason: str) -> None:
    assert diagnostics(with_validators(type_, good, {key: args})) == []
    found = diagnostics(with_validators(type_, bad, {key: args}))
    assert [(d.severity, d.path, d.anchor) for d in found] == [
        (Severity.ERROR, ('default_value',), 'value')]
    assert found[0].message.startswith('default_value ')
    assert f' breaks {key} ' in found[0].message
    assert found[0].message.endswith(': ' + reason)


def test_breaking_default_message_in_full() -> None:
    found = diagnostics(with_validators('int', 500, {'bounds<>': [0, 10]}))
    assert messages(found) == ['default_value 500 breaks bounds<> [0, 10]: it is outside [0, 10]']


def test_every_broken_validator_is_reported() -> None:
    found = errors(with_validators('int_array', [5, 5], {
        'unique<>': None, 'fixed_size<>': [3], 'upper_element_bounds<>': [4]}))
    assert len(found) == 3
    assert all(d.path == ('default_value',) for d in found)


def test_no_breaks_check_when_the_default_has_the_wrong_type() -> None:
    found = errors(with_validators('int', 'hello', {'bounds<>': [0, 10]}))
    assert messages(found) == [
        "default_value of an int parameter must be an integer, not a string ('hello')"]


def test_no_breaks_check_when_the_arguments_are_unusable() -> None:
    found = errors(with_validators('int', 500, {'bounds<>': [10, 0]}))
    assert messages(found) == ['bounds<>: the lower bound 10 is greater than the upper bound 0']


def test_no_breaks_check_for_a_validator_that_does_not_apply() -> None:
    found = errors(with_validators('string', 'abc', {'bounds<>': [0, 1]}))
    assert len(found) == 1 and 'does not apply' in found[0].message


def test_custom_validators_are_not_evaluated() -> None:
    assert diagnostics(with_validators('int', -5, {'my_ns::positive<>': None})) == []


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.integers(-1000, 1000), st.integers(-1000, 1000), st.integers(-2000, 2000))
def test_property_bounds_agree_with_arithmetic(a: int, b: int, value: int) -> None:
    low, high = min(a, b), max(a, b)
    found = errors(with_validators('int', value, {'bounds<>': [low, high]}))
    assert bool(found) == (not low <= value <= high)


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.sampled_from(['lt', 'gt', 'lt_eq', 'gt_eq']),
       st.floats(-1e6, 1e6, allow_nan=False), st.floats(-1e6, 1e6, allow_nan=False))
def test_property_comparisons_agree_with_arithmetic(name: str, limit: float, value: float) -> None:
    expected = {'lt': value < limit, 'gt': value > limit, 'lt_eq': value <= limit,
                'gt_eq': value >= limit}[name]
    found = errors(with_validators('double', value, {name + '<>': [limit]}))
    assert bool(found) == (not expected)


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.lists(st.integers(0, 255), max_size=6), st.integers(0, 255), st.integers(0, 255))
def test_property_byte_array_element_bounds(values: list[int], a: int, b: int) -> None:
    low, high = min(a, b), max(a, b)
    found = errors(with_validators('byte_array', values, {'element_bounds<>': [low, high]}))
    assert bool(found) == any(not low <= v <= high for v in values)


# -- the function itself ---------------------------------------------------------

def test_check_parameter_ignores_what_the_structure_check_reports() -> None:
    for value in (None, 5, 'int', ['int']):
        out: list = []
        check_parameter(value, (), out)
        assert out == []
    out = []
    check_parameter({'type': 'integer', 'default_value': 'x'}, (), out)
    assert out == []  # the unknown type is the structural check's to report


def test_check_parameter_prefixes_paths() -> None:
    out: list = []
    check_parameter({'type': 'int', 'default_value': 'x', 'validation': {'bounds': [2, 1]}},
                    ('main', 'parameters', 'gain'), out)
    assert sorted(d.path for d in out) == [
        ('main', 'parameters', 'gain', 'default_value'),
        ('main', 'parameters', 'gain', 'validation', 'bounds')]


def test_all_problems_of_a_parameter_are_reported_at_once() -> None:
    found = errors({'type': 'int', 'default_value': 'x', 'read_only': 'no', 'validation': {
        'bounds<>': [5, 1], 'not_empty<>': None, 'bad-name': None, 'gt': [1]}})
    paths = sorted(str(d.path) for d in found)
    assert paths == sorted(str(p) for p in [
        ('default_value',), ('read_only',), ('validation', 'bounds<>'),
        ('validation', 'not_empty<>'), ('validation', 'bad-name'), ('validation', 'gt')])


@pytest.mark.parametrize('param', [
    {'type': 'int', 'default_value': 2**63},
    {'type': 'int', 'default_value': -2**63 - 1},
    {'type': 'int_array', 'default_value': [0, 2**63]},
])
def test_int_defaults_outside_int64_are_errors(param: dict) -> None:
    from nodl.validation import Kind, validate_data

    errors = [d for d in validate_data(param, Kind.PARAMETER) if d.severity == 'error']
    assert len(errors) == 1 and 'int64' in errors[0].message


def test_int64_limits_are_accepted() -> None:
    from nodl.validation import Kind, validate_data

    for value in (2**63 - 1, -2**63):
        assert not validate_data({'type': 'int', 'default_value': value}, Kind.PARAMETER)
