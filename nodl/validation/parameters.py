"""Parameter checks the JSON Schema cannot express.

* the type name (with suggestions);
* validator names: built-ins with or without ``<>``, custom C++ functions;
* the default value against the type (scalar kinds, byte range, fixed sizes);
* validators against the type (``bounds`` on a string is an error);
* conflicting validators, as generate_parameter_library rejects them;
* validator arguments of the parameter's type (``one_of``, ``subset_of``);
* the default value against the validators (500 with ``bounds<>: [0, 10]``).
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.model.parameter_types import ALL_TYPE_WORDS, ARRAY_TYPES, SCALAR_TYPES, TypeSpec, element_fits, parse_type
from nodl.validation.characters import check_text, check_text_fields
from nodl.validation.validators import APPLICABILITY, VALIDATORS
from nodl.wording import article, described, did_you_mean, show

__all__ = ['BUILTIN_VALIDATORS', 'check_parameter_type', 'check_validator_name', 'check_parameter']

#: Built-in validators of generate_parameter_library and what they apply to (from the table in
#: :mod:`nodl.validation.validators`).
BUILTIN_VALIDATORS: dict[str, str] = {name: rule.applies for name, rule in VALIDATORS.items()}
_APPLIES_WORDS = {name: applicability.words for name, applicability in APPLICABILITY.items()}
_CONFLICTS = [
    ('bounds', ('lt', 'gt', 'lt_eq', 'gt_eq')),
    ('element_bounds', ('lower_element_bounds', 'upper_element_bounds')),
]
_FUNCTION_NAME = re.compile(r'[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)*(<>)?')
_ELEMENT_WORDS = {'bool': 'a boolean', 'int': 'an integer', 'double': 'a number',
                  'string': 'a string', 'byte': 'an integer from 0 to 255'}


def _error(message: str, path: DocPath, code: str, anchor: str = 'value') -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, path, anchor=anchor, code=code)


def check_parameter_type(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """Format check ``nodl-parameter-type``."""
    if not isinstance(value, str):
        out.append(_error(f"'type' must be a string, not {described(value)}", path, 'NODL103'))
        return
    if parse_type(value) is not None:
        return
    if value.startswith('bool_array_fixed_'):
        out.append(_error(f'{show(value)} is not supported: there are no fixed-size bool arrays '
                          '(use bool_array)', path, 'NODL206'))
        return
    if re.fullmatch(r'\w+_fixed_0*', value) or re.fullmatch(r'\w+_fixed_0[0-9]+', value):
        out.append(_error(f'{show(value)}: the size of a fixed-size type is a positive number '
                          'without leading zeros', path, 'NODL206'))
        return
    out.append(_error(f'unknown parameter type {show(value)}; expected one of: '
                      f'{", ".join(ALL_TYPE_WORDS)}{did_you_mean(value, SCALAR_TYPES + ARRAY_TYPES)}',
                      path, 'NODL206'))


def check_validator_name(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """Format check ``nodl-validator-name`` (applied to keys of ``validation``)."""
    if not isinstance(value, str) or check_text(value, 'validator name', path, out, 'key'):
        return
    bare = value[:-2] if value.endswith('<>') else value
    if bare in BUILTIN_VALIDATORS:
        return
    if not _FUNCTION_NAME.fullmatch(value):
        out.append(_error(
            f'{show(value)} is not a validator name: use a built-in validator '
            f'({", ".join(n + "<>" for n in BUILTIN_VALIDATORS)}) or a C++ function name '
            '(my_namespace::my_check)', path, 'NODL207', 'key'))
        return
    if '::' not in bare:
        # Compare without the '<>' suffix: two shared characters would make
        # unrelated names look close ('finite<>' and 'unique<>').
        close = did_you_mean(bare, list(BUILTIN_VALIDATORS))
        suffix = '<>' if value.endswith('<>') else ''
        hint = close.replace("'?", f"{suffix}'?") if close else ''
        if hint:
            out.append(Diagnostic(
                Severity.WARNING,
                f'{show(value)} is not a built-in validator and will be called as a custom '
                f'function{hint.replace(";", ",", 1)}', path, anchor='key', code='NODL208'))


def check_parameter(param: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """Semantic checks of one parameter definition found at ``path``."""
    if not isinstance(param, dict):
        return
    check_text_fields(param, path, out)
    spec = parse_type(param.get('type'))
    if spec is None:
        return  # the structural check has reported the type
    has_default = 'default_value' in param
    default = param.get('default_value')
    default_path = path + ('default_value',)
    default_ok = False
    if spec.base == 'none':
        if has_default:
            out.append(Diagnostic(Severity.WARNING, "a parameter of type 'none' holds no value; "
                                  'its default_value is ignored', default_path, anchor='key',
                                  code='NODL214'))
    elif has_default:
        default_ok = _check_default(default, spec, default_path, out)

    validation = param.get('validation')
    if not isinstance(validation, dict):
        return
    vpath = path + ('validation',)
    builtins: dict[str, tuple[str, Any]] = {}
    for key, args in validation.items():
        if not isinstance(key, str):
            continue
        bare = key[:-2] if key.endswith('<>') else key
        if bare not in BUILTIN_VALIDATORS:
            continue
        if bare in builtins:
            out.append(_error(f"'{builtins[bare][0]}' and '{key}' are the same validator; keep one",
                              vpath + (key,), 'NODL212', 'key'))
            continue
        builtins[bare] = (key, args)

    if spec.base == 'none' and validation:
        out.append(_error("a parameter of type 'none' holds no value, so it takes no validators",
                          vpath, 'NODL211', 'key'))
        return

    fitting: dict[str, tuple[str, Any]] = {}
    for bare, (key, args) in builtins.items():
        applies = BUILTIN_VALIDATORS[bare]
        if not _applies(applies, spec):
            out.append(_error(f"'{key}' does not apply to {article(spec.category)} parameter; it is for "
                              f'{_APPLIES_WORDS[applies]}', vpath + (key,), 'NODL211', 'key'))
            continue
        fitting[bare] = (key, args)

    for first, others in _CONFLICTS:
        if first in builtins:
            for other in others:
                if other in builtins:
                    key = builtins[other][0]
                    out.append(_error(f"'{builtins[first][0]}' conflicts with '{key}': give the range "
                                      f'with one or the other, not both', vpath + (key,), 'NODL212',
                                      'key'))

    args_ok = True
    for bare, (key, args) in fitting.items():
        if not _check_arguments(bare, key, args, spec, vpath + (key,), out):
            args_ok = False
    if default_ok and args_ok:
        for bare, (key, args) in fitting.items():
            problem = _default_breaks(bare, args, default, spec)
            if problem:
                out.append(_error(f'default_value {show(default)} breaks {key} '
                                  f'{show(args)}: {problem}', default_path, 'NODL210'))


def _applies(applies: str, spec: TypeSpec) -> bool:
    return APPLICABILITY[applies](spec)


def _check_default(value: Any, spec: TypeSpec, path: DocPath, out: list[Diagnostic]) -> bool:
    if value is None:
        out.append(_error(f'default_value is null; {article(spec.name)} parameter needs '
                          f'{_expected(spec)} (leave default_value out to make the parameter '
                          'required at start-up)', path, 'NODL209'))
        return False
    if spec.is_array:
        if not isinstance(value, list):
            out.append(_error(f'default_value of {article(spec.name)} parameter must be a list of '
                              f'{spec.element} values, not {described(value)}', path, 'NODL209'))
            return False
        ok = True
        for index, item in enumerate(value):
            if (spec.element == 'byte' and element_fits(item, 'int')
                    and not element_fits(item, 'byte')):
                out.append(_error(f'element {index} of default_value is {item}; a byte_array holds '
                                  'integers from 0 to 255', path + (index,), 'NODL209'))
                ok = False
            elif not element_fits(item, spec.element):
                out.append(_error(f'element {index} of default_value must be '
                                  f'{_ELEMENT_WORDS[spec.element]}, not {described(item)}',
                                  path + (index,), 'NODL209'))
                ok = False
            elif spec.element == 'int' and not _in_int64(item):
                out.append(_error(f'element {index} of default_value is {item}, outside the int64 '
                                  f'range [{INT64_MIN}, {INT64_MAX}] a ROS 2 integer parameter holds',
                                  path + (index,), 'NODL209'))
                ok = False
        if spec.size is not None and len(value) > spec.size:
            out.append(_error(f'default_value has {len(value)} elements; {spec.name} holds at most '
                              f'{spec.size}', path, 'NODL209'))
            ok = False
        return ok
    if not element_fits(value, spec.element):
        out.append(_error(f'default_value of {article(spec.name)} parameter must be {_expected(spec)}, '
                          f'not {described(value)}', path, 'NODL209'))
        return False
    if spec.element == 'int' and not _in_int64(value):
        out.append(_error(f'default_value {value} is outside the int64 range [{INT64_MIN}, '
                          f'{INT64_MAX}] a ROS 2 integer parameter holds', path, 'NODL209'))
        return False
    if spec.size is not None and len(value) > spec.size:
        out.append(_error(f'default_value has {len(value)} characters; {spec.name} holds at most '
                          f'{spec.size}', path, 'NODL209'))
        return False
    return True


#: The range of a ROS 2 integer parameter (rcl_interfaces ParameterValue.integer_value is int64).
INT64_MIN = -2**63
INT64_MAX = 2**63 - 1


def _in_int64(value: Any) -> bool:
    return bool(INT64_MIN <= value <= INT64_MAX)


def _expected(spec: TypeSpec) -> str:
    if spec.is_array:
        return f'a list of {spec.element} values'
    return _ELEMENT_WORDS.get(spec.element, 'a value')


def _check_arguments(bare: str, key: str, args: Any, spec: TypeSpec, path: DocPath,
                     out: list[Diagnostic]) -> bool:
    """Arguments of the parameter's kind; False if they are unusable."""
    rule = VALIDATORS[bare]
    if not rule.accepts(args):
        return False  # the structural check reported the shape
    argument = rule.argument(args)
    if rule.shape == 'bounds':
        if argument[0] > argument[1]:
            out.append(_error(f'{key}: the lower bound {show(argument[0])} is greater than the upper '
                              f'bound {show(argument[1])}', path, 'NODL213'))
            return False
        return _integral(list(argument), key, spec, path, out)
    if rule.shape == 'comparison':
        return _integral([argument], key, spec, path, out)
    if rule.shape in ('one_of', 'subset_of'):
        ok = True
        for index, item in enumerate(argument):
            if not element_fits(item, spec.element):
                never = (f'no element of {article(spec.name)} parameter can equal it'
                         if bare == 'subset_of' else
                         f'{article(spec.name)} parameter can never equal it')
                out.append(_error(f'{key} value {show(item)} is not {_ELEMENT_WORDS[spec.element]}, '
                                  f'so {never}', path + (0, index), 'NODL213'))
                ok = False
        return ok
    return True


def _integral(values: list[Any], key: str, spec: TypeSpec, path: DocPath,
              out: list[Diagnostic]) -> bool:
    if spec.element in ('int', 'byte'):
        for value in values:
            if isinstance(value, float) and not value.is_integer():
                out.append(_error(f'{key} of an integer parameter must use integers, not '
                                  f'{show(value)}', path, 'NODL213'))
                return False
    return True


def _default_breaks(bare: str, args: Any, value: Any, spec: TypeSpec) -> str | None:
    """Why ``value`` fails the validator, or None (None too for unusable arguments)."""
    rule = VALIDATORS.get(bare)
    if rule is None or not rule.accepts(args):
        return None
    return rule.check(value, args)
