"""The built-in parameter validators of generate_parameter_library, each defined once.

One row per validator: the parameter types it applies to, the shape of its
arguments (named after the schema definition ``<shape>_validator`` that
checks it), its predicate and its wording.  Every consumer reads this
table: the validation of definitions (a default value against its
validators), the live value check of ``nodl check``, and generators,
documentation and parameter-file checks to come.

Arguments are given to a predicate *normalized* (:meth:`ValidatorRule.argument`):
``bounds`` and ``element_bounds`` get ``(lower, upper)``; comparisons and
sizes get one number (``[x]`` and ``x`` are both accepted spellings);
``one_of`` and ``subset_of`` get the list of values; the others get None.
Values are Python values as YAML, JSON or rclpy give them; arrays may be
any sequence.
"""

from __future__ import annotations

from collections import namedtuple
from typing import TYPE_CHECKING

from nodl.model.parameter_types import element_fits, parse_type
from nodl.vocabulary import PARAMETER_TYPES
from nodl.wording import one_of, show

if TYPE_CHECKING:
    from typing import Any

    from nodl.model.parameter_types import TypeSpec

__all__ = ['Applicability', 'APPLICABILITY', 'ArgumentShape', 'ARGUMENT_SHAPES', 'ValidatorRule',
           'VALIDATORS', 'BUILTIN_NAMES', 'bare_name', 'lookup', 'value_problems',
           'applicable_types']


# --------------------------------------------------------------------------
# Which parameter types a validator applies to

class Applicability(namedtuple('Applicability', ['name', 'words', 'test'])):
    """A class of parameter types: ``test(spec)`` is true for its members; ``words`` name them."""

    __slots__ = ()

    def __call__(self, spec: TypeSpec) -> bool:
        """True if a parameter of type ``spec`` belongs to the class."""
        result: bool = self.test(spec)
        return result


APPLICABILITY: dict[str, Applicability] = {a.name: a for a in (
    Applicability('numeric', 'int and double parameters',
                  lambda s: not s.is_array and s.element in ('int', 'double')),
    Applicability('scalar', 'bool, int, double and string parameters',
                  lambda s: not s.is_array and s.element != 'none'),
    Applicability('sized', 'string and array parameters',
                  lambda s: s.is_array or s.element == 'string'),
    Applicability('array', 'array parameters', lambda s: s.is_array),
    Applicability('numeric_array', 'int, double and byte arrays',
                  lambda s: s.is_array and s.numeric),
)}


# --------------------------------------------------------------------------
# The shape of a validator's arguments

def _number(value: Any) -> bool:
    return element_fits(value, 'double')


def _one(args: Any) -> Any:
    """``[x]`` or ``x`` -> x (the two spellings generate_parameter_library accepts)."""
    if isinstance(args, list) and len(args) == 1:
        return args[0]
    return args


def _size(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= 0


def _values(args: Any) -> bool:
    return isinstance(args, list) and len(args) == 1 and isinstance(args[0], list) and bool(args[0])


class ArgumentShape(namedtuple('ArgumentShape', ['name', 'words', 'accepts', 'normalize'])):
    """How a validator's arguments are written.

    ``accepts(raw)`` is true for a usable argument; ``normalize(raw)`` is what
    a predicate gets.  The schema checks the same shape in its definition
    ``<name>_validator`` (a test keeps the two in agreement).
    """

    __slots__ = ()


ARGUMENT_SHAPES: dict[str, ArgumentShape] = {s.name: s for s in (
    ArgumentShape('bounds', 'two numbers [lower, upper]',
                  lambda a: isinstance(a, list) and len(a) == 2 and all(_number(x) for x in a),
                  lambda a: (a[0], a[1])),
    ArgumentShape('comparison', 'one number: [value] or value',
                  lambda a: _number(_one(a)), _one),
    ArgumentShape('size', 'one non-negative integer: [size] or size',
                  lambda a: _size(_one(a)), _one),
    ArgumentShape('one_of', 'the allowed values: [[a, b, ...]]', _values, lambda a: a[0]),
    ArgumentShape('subset_of', 'the allowed elements: [[a, b, ...]]', _values, lambda a: a[0]),
    ArgumentShape('no_arg', 'no arguments: null or []',
                  lambda a: a is None or a == [], lambda a: None),
)}


# --------------------------------------------------------------------------
# The validators

class ValidatorRule(namedtuple('ValidatorRule', ['name', 'applies', 'shape', 'predicate',
                                                 'requirement', 'failure'])):
    """One built-in validator.

    * ``name``: without the ``<>`` suffix (``bounds``);
    * ``applies``: a key of :data:`APPLICABILITY`;
    * ``shape``: a key of :data:`ARGUMENT_SHAPES`;
    * ``predicate(value, argument)``: true if the value passes;
    * ``requirement(argument)``: the rule in prose (``must be between 0 and 10``);
    * ``failure(value, argument)``: why a value that fails does (``it is outside [0, 10]``).
    """

    __slots__ = ()

    @property
    def applicability(self) -> Applicability:
        """The types this validator applies to."""
        return APPLICABILITY[self.applies]

    @property
    def argument_shape(self) -> ArgumentShape:
        """How its arguments are written."""
        return ARGUMENT_SHAPES[self.shape]

    def applies_to(self, spec: TypeSpec) -> bool:
        """True if it may validate a parameter of type ``spec``."""
        return self.applicability(spec)

    def accepts(self, raw: Any) -> bool:
        """True if ``raw`` (the arguments as written) has the right shape."""
        accepted: bool = self.argument_shape.accepts(raw)
        return accepted

    def argument(self, raw: Any) -> Any:
        """The arguments as written -> what the predicate gets (``raw`` must be accepted)."""
        return self.argument_shape.normalize(raw)

    def check(self, value: Any, raw: Any) -> str | None:
        """Why ``value`` fails with arguments ``raw`` as written, or None if it passes."""
        argument = self.argument(raw)
        if self.predicate(value, argument):
            return None
        message: str = self.failure(value, argument)
        return message

    def describe(self, raw: Any) -> str:
        """The rule in prose for arguments ``raw`` as written."""
        text: str = self.requirement(self.argument(raw))
        return text


def _same(a: Any, b: Any) -> bool:
    """Equal and of one kind (``1`` is not ``True``; ``1`` equals ``1.0``)."""
    if _number(a) and _number(b):
        return bool(a == b)
    return type(a) is type(b) and bool(a == b)


def _first_duplicate(values: Any) -> Any:
    seen: list[Any] = []
    for item in values:
        if item in seen:
            return item
        seen.append(item)
    return None


def _has_duplicate(values: Any) -> bool:
    seen: list[Any] = []
    for item in values:
        if item in seen:
            return True
        seen.append(item)
    return False


def _words(values: Any) -> str:
    return one_of(map(show, values))


VALIDATORS: dict[str, ValidatorRule] = {v.name: v for v in (
    ValidatorRule('bounds', 'numeric', 'bounds',
                  lambda v, a: a[0] <= v <= a[1],
                  lambda a: f'must be between {a[0]} and {a[1]}',
                  lambda v, a: f'it is outside [{a[0]}, {a[1]}]'),
    ValidatorRule('lt', 'numeric', 'comparison',
                  lambda v, a: v < a,
                  lambda a: f'must be less than {a}',
                  lambda v, a: f'it must be less than {a}'),
    ValidatorRule('gt', 'numeric', 'comparison',
                  lambda v, a: v > a,
                  lambda a: f'must be greater than {a}',
                  lambda v, a: f'it must be greater than {a}'),
    ValidatorRule('lt_eq', 'numeric', 'comparison',
                  lambda v, a: v <= a,
                  lambda a: f'must be at most {a}',
                  lambda v, a: f'it must be at most {a}'),
    ValidatorRule('gt_eq', 'numeric', 'comparison',
                  lambda v, a: v >= a,
                  lambda a: f'must be at least {a}',
                  lambda v, a: f'it must be at least {a}'),
    ValidatorRule('one_of', 'scalar', 'one_of',
                  lambda v, a: any(_same(v, x) for x in a),
                  lambda a: f'must be one of {_words(a)}',
                  lambda v, a: f'it must be one of {_words(a)}'),
    ValidatorRule('not_empty', 'sized', 'no_arg',
                  lambda v, a: len(v) > 0,
                  lambda a: 'must not be empty',
                  lambda v, a: 'it must not be empty'),
    ValidatorRule('fixed_size', 'sized', 'size',
                  lambda v, a: len(v) == a,
                  lambda a: f'must have a size of exactly {a}',
                  lambda v, a: f'its size must be exactly {a}'),
    ValidatorRule('size_gt', 'sized', 'size',
                  lambda v, a: len(v) > a,
                  lambda a: f'must have a size greater than {a}',
                  lambda v, a: f'its size must be greater than {a}'),
    ValidatorRule('size_lt', 'sized', 'size',
                  lambda v, a: len(v) < a,
                  lambda a: f'must have a size less than {a}',
                  lambda v, a: f'its size must be less than {a}'),
    ValidatorRule('unique', 'array', 'no_arg',
                  lambda v, a: not _has_duplicate(v),
                  lambda a: 'must not hold any value twice',
                  lambda v, a: f'{show(_first_duplicate(v))} appears more than once'),
    ValidatorRule('subset_of', 'array', 'subset_of',
                  lambda v, a: all(item in a for item in v),
                  lambda a: f'may only hold {_words(a)}',
                  lambda v, a: f'{show(next(i for i in v if i not in a))} is not one of the '
                               'allowed values'),
    ValidatorRule('element_bounds', 'numeric_array', 'bounds',
                  lambda v, a: all(a[0] <= item <= a[1] for item in v),
                  lambda a: f'every element must be between {a[0]} and {a[1]}',
                  lambda v, a: f'element {show(next(i for i in v if not a[0] <= i <= a[1]))} is '
                               f'outside [{a[0]}, {a[1]}]'),
    ValidatorRule('lower_element_bounds', 'numeric_array', 'comparison',
                  lambda v, a: all(item >= a for item in v),
                  lambda a: f'every element must be at least {a}',
                  lambda v, a: f'element {show(next(i for i in v if i < a))} is below {a}'),
    ValidatorRule('upper_element_bounds', 'numeric_array', 'comparison',
                  lambda v, a: all(item <= a for item in v),
                  lambda a: f'every element must be at most {a}',
                  lambda v, a: f'element {show(next(i for i in v if i > a))} is above {a}'),
)}

#: The built-in validator names (without ``<>``), in table order.
BUILTIN_NAMES: tuple[str, ...] = tuple(VALIDATORS)


def bare_name(key: str) -> str:
    """``bounds<>`` -> ``bounds`` (a validator key without its suffix)."""
    return key[:-2] if key.endswith('<>') else key


def lookup(key: Any) -> ValidatorRule | None:
    """The built-in validator a ``validation`` key names (with or without ``<>``), or None."""
    if not isinstance(key, str):
        return None
    return VALIDATORS.get(bare_name(key))


def applicable_types(rule: ValidatorRule) -> tuple[str, ...]:
    """The parameter type names (without fixed sizes) a validator applies to."""
    specs = [(name, parse_type(name)) for name in PARAMETER_TYPES]
    return tuple(name for name, spec in specs if spec is not None and rule.applies_to(spec))


def value_problems(value: Any, type_name: str, validation: Any) -> list[tuple[str, str]]:
    """``(key, why)`` for every built-in validator of ``validation`` that ``value`` fails.

    Only validators that apply to the type and whose arguments have the right
    shape are evaluated (a definition that passed validation has no others);
    custom validators are C++ functions and are not evaluated.  ``value`` must
    be a value of the type.
    """
    spec = parse_type(type_name)
    if spec is None or not isinstance(validation, dict):
        return []
    problems: list[tuple[str, str]] = []
    for key, raw in validation.items():
        rule = lookup(key)
        if rule is None or not rule.applies_to(spec) or not rule.accepts(raw):
            continue
        problem = rule.check(value, raw)
        if problem is not None:
            problems.append((key, problem))
    return problems
