"""The language-neutral parameter plan: what every generator and the runtime declare and enforce.

From the parameters a node's implementation provides, :func:`plan_parameters`
derives, once, for every target:

* a tree of structs nested by dotted name (``camera.exposure.max`` ->
  struct ``camera`` -> struct ``exposure`` -> field ``max``), with
  identifiers from :mod:`nodl.plan.identifiers` (collision-free,
  keyword-free in the target language);
* per parameter: its parsed type (fixed sizes and ``byte_array`` included),
  its ROS parameter type, its default (or that it is required), its
  descriptor (description, read_only, additional constraints, an
  ``integer_range``/``floating_point_range`` derived from ``bounds``, ``gt``,
  ``lt``, ``gt_eq`` and ``lt_eq``) and its validators.

Validator semantics live in one place, the validator table
(:mod:`nodl.validation.validators`): :meth:`ValidatorPlan.check` and
:func:`value_problems` call its predicates.  Generated code that must not
depend on the toolkit carries a translation per built-in validator; the tests
keep each translation in agreement with the table's predicate.

Ranges are inclusive in ROS, so an exclusive bound becomes the next integer
for an ``int`` parameter and the bound itself for a ``double`` one (the
validator then rejects the bound with its own message).  The step is 0 (no
step: rclpy and rclcpp both skip the step test for 0).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from dataclasses import field as _field
from typing import Any

from nodl.model.parameter_types import TypeSpec, parse_type
from nodl.plan.identifiers import PYTHON_KEYWORDS, IdentifierScope
from nodl.validation.validators import ValidatorRule, lookup
from nodl.vocabulary import ROS_PARAMETER_TYPE_NAMES

__all__ = ['ROS_TYPES', 'INT64_MIN', 'INT64_MAX', 'DOUBLE_MAX', 'ValidatorPlan', 'RangePlan',
           'ParameterPlan', 'StructPlan', 'ParametersPlan', 'plan_parameters', 'plan_parameter',
           'ros_type_of', 'type_problem', 'value_problems']

#: Parameter type base -> the ROS parameter type (``rcl_interfaces/msg/ParameterType`` constant
#: name): the vocabulary's table.
ROS_TYPES: dict[str, str] = ROS_PARAMETER_TYPE_NAMES

#: The ROS parameter type in words, as messages use it: its rcl name in words
#: (``PARAMETER_INTEGER_ARRAY``: ``integer array``; ``PARAMETER_NOT_SET``: ``not set``).
_ROS_TYPE_WORDS: dict[str, str] = {
    name: name.removeprefix('PARAMETER_').lower().replace('_', ' ') for name in ROS_PARAMETER_TYPE_NAMES.values()}

INT64_MIN = -2 ** 63
INT64_MAX = 2 ** 63 - 1
DOUBLE_MAX = 1.7976931348623157e308

#: Validators that narrow a numeric range: name -> (side, exclusive).
_RANGE_VALIDATORS: dict[str, tuple[str, bool]] = {
    'gt': ('from', True), 'gt_eq': ('from', False), 'lt': ('to', True), 'lt_eq': ('to', False)}


@dataclass(frozen=True)
class ValidatorPlan:
    """One validator of a parameter, as written and as a target needs it."""

    #: The key as written (``bounds<>``, ``my_pkg::in_range``).
    key: str
    #: The built-in's name (``bounds``) or the custom validator's function name.
    name: str
    #: True for a built-in of the validator table.
    builtin: bool
    #: The arguments as written.
    raw: Any
    #: Built-ins: the normalized argument the predicate gets; custom: the arguments as written.
    argument: Any
    #: The rule in prose (``must be between 1 and 120``), the reason a rejection gives.
    requirement: str

    @property
    def rule(self) -> ValidatorRule | None:
        """The validator table's row (None for a custom validator)."""
        return lookup(self.key) if self.builtin else None

    def check(self, value: Any) -> str | None:
        """The requirement if ``value`` fails this built-in validator, else None (custom: None)."""
        rule = self.rule
        if rule is None:
            return None
        return None if rule.predicate(value, self.argument) else self.requirement


@dataclass(frozen=True)
class RangePlan:
    """The descriptor's range: ``integer`` or ``floating_point``, inclusive, step 0."""

    kind: str
    from_value: float | int
    to_value: float | int
    step: float | int = 0


@dataclass(frozen=True)
class ParameterPlan:
    """One parameter as every target declares it."""

    #: The full name (``camera.exposure.max``).
    name: str
    #: The struct identifiers from the root to the field, then the field (``('camera', 'exposure', 'max_')``).
    path: tuple[str, ...]
    #: The type as written and parsed.
    type_name: str
    type: TypeSpec
    #: ``PARAMETER_DOUBLE`` etc.
    ros_type: str
    #: The default value (None if required or of type ``none``).
    default: Any
    #: True if the parameter has no default: it must be given when the node starts.
    required: bool
    description: str
    read_only: bool
    additional_constraints: str
    range: RangePlan | None
    validators: tuple[ValidatorPlan, ...]

    @property
    def field(self) -> str:
        """The field identifier in its struct."""
        return self.path[-1]

    @property
    def builtin_validators(self) -> tuple[ValidatorPlan, ...]:
        """The built-in validators."""
        return tuple(v for v in self.validators if v.builtin)

    @property
    def custom_validators(self) -> tuple[ValidatorPlan, ...]:
        """The custom (``ns::fn``) validators: called through a hook the user provides."""
        return tuple(v for v in self.validators if not v.builtin)

    @property
    def dynamic_typing(self) -> bool:
        """True for type ``none`` (a parameter of any type)."""
        return bool(self.type.base == 'none')

    @property
    def size_requirement(self) -> str | None:
        """For a fixed-size type (``string_fixed_8``, ``int_array_fixed_3``): the maximum length as
        a requirement (``must hold at most 8 characters``); None for other types."""
        if self.type.size is None:
            return None
        return f'must hold at most {self.type.size} {"characters" if self.type.base == "string" else "elements"}'

    @property
    def constraints_text(self) -> str:
        """The descriptor's ``additional_constraints``: the definition's own text, then every
        validator's requirement, then a fixed size (what ``ros2 param describe`` shows)."""
        parts = [self.additional_constraints] if self.additional_constraints else []
        parts += [v.requirement for v in self.validators]
        if self.size_requirement is not None:
            parts.append(self.size_requirement)
        return '; '.join(parts)


@dataclass
class StructPlan:
    """A struct of the parameter object: fields and nested structs, in name order."""

    #: The identifier of this struct as a field of its parent ('' for the root).
    field: str
    #: The dotted prefix of its parameters ('' for the root, ``camera.exposure``).
    prefix: str
    #: The identifiers from the root (``('camera', 'exposure')``).
    path: tuple[str, ...]
    #: Fields: leaf parameters and nested structs, in name order.
    members: list[ParameterPlan | StructPlan] = _field(default_factory=list)

    @property
    def structs(self) -> list[StructPlan]:
        """The nested structs."""
        return [m for m in self.members if isinstance(m, StructPlan)]

    @property
    def parameters(self) -> list[ParameterPlan]:
        """The leaf parameters directly in this struct."""
        return [m for m in self.members if isinstance(m, ParameterPlan)]

    def walk(self) -> Iterable[StructPlan]:
        """This struct and every nested one, depth first, parents first."""
        yield self
        for struct in self.structs:
            yield from struct.walk()


@dataclass
class ParametersPlan:
    """Every parameter of a node's implementation and the struct tree holding them."""

    root: StructPlan
    #: Every parameter, in name order.
    parameters: list[ParameterPlan]

    def get(self, name: str) -> ParameterPlan | None:
        """The parameter called ``name`` or None."""
        return next((p for p in self.parameters if p.name == name), None)

    @property
    def required(self) -> list[ParameterPlan]:
        """The parameters without a default."""
        return [p for p in self.parameters if p.required]


def _requirement(key: str, rule: ValidatorRule | None, raw: Any) -> str:
    if rule is not None:
        return rule.describe(raw)
    return f'must pass the custom validator {key}'


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _range(spec: TypeSpec, validators: Sequence[ValidatorPlan]) -> RangePlan | None:
    if spec.is_array or spec.element not in ('int', 'double'):
        return None
    integer = spec.element == 'int'
    low: float = -math.inf
    high: float = math.inf
    for v in validators:
        if not v.builtin:
            continue
        if v.name == 'bounds' and all(_number(x) for x in v.argument):
            low, high = max(low, v.argument[0]), min(high, v.argument[1])
        elif v.name in _RANGE_VALIDATORS and _number(v.argument):
            side, exclusive = _RANGE_VALIDATORS[v.name]
            bound = v.argument
            if side == 'from':
                bound = (math.floor(bound) + 1 if exclusive else math.ceil(bound)) if integer else bound
                low = max(low, bound)
            else:
                bound = (math.ceil(bound) - 1 if exclusive else math.floor(bound)) if integer else bound
                high = min(high, bound)
    if low == -math.inf and high == math.inf:
        return None
    if integer:
        lo = INT64_MIN if low == -math.inf else max(INT64_MIN, math.ceil(low))
        hi = INT64_MAX if high == math.inf else min(INT64_MAX, math.floor(high))
        return RangePlan('integer', int(lo), int(hi), 0) if lo <= hi else None
    flo = -DOUBLE_MAX if low == -math.inf else float(low)
    fhi = DOUBLE_MAX if high == math.inf else float(high)
    return RangePlan('floating_point', flo, fhi, 0.0) if flo <= fhi else None


def plan_parameter(name: str, definition: Any, path: tuple[str, ...] = ()) -> ParameterPlan:
    """The plan of one parameter (``definition``: a ParameterDefinition); ValueError for an unknown type."""
    spec = parse_type(definition.type)
    if spec is None:
        raise ValueError(f'parameter {name!r} has the unknown type {definition.type!r}')
    validators = []
    for key, raw in (definition.validation or {}).items():
        rule = lookup(key)
        builtin = rule is not None and rule.accepts(raw)
        validators.append(ValidatorPlan(
            key, rule.name if rule is not None else key, builtin, raw,
            rule.argument(raw) if builtin and rule is not None else raw,
            _requirement(key, rule if builtin else None, raw)))
    default = definition.default_value
    return ParameterPlan(
        name, path or (name,), definition.type, spec, ROS_TYPES[spec.base],
        default, default is None and spec.base != 'none', definition.description or '',
        bool(definition.read_only), definition.additional_constraints or '',
        _range(spec, validators), tuple(validators))


def plan_parameters(parameters: Iterable[tuple[str, Any]] | Any,
                    keywords: Iterable[str] = PYTHON_KEYWORDS,
                    reserved: Iterable[str] = ()) -> ParametersPlan:
    """The plan of ``parameters``: ``(name, ParameterDefinition)`` pairs, or entities of a resolved node.

    ``keywords`` are the target language's (:data:`~nodl.plan.identifiers.KEYWORDS`);
    ``reserved`` identifiers no struct may use as a field (methods of the generated struct).
    """
    pairs: list[tuple[str, Any]] = []
    for item in parameters:
        if isinstance(item, tuple):
            pairs.append(item)
        else:  # an Entity
            pairs.append((item.name, item.definition))
    pairs.sort(key=lambda p: p[0])
    keyword_set = frozenset(keywords)
    reserved_set = frozenset(reserved)

    def build(prefix: str, path: tuple[str, ...], items: list[tuple[list[str], str, Any]],
              field_name: str) -> StructPlan:
        struct = StructPlan(field_name, prefix, path)
        scope = IdentifierScope(reserved_set, keyword_set)
        leaves = [(parts[0], full, d) for parts, full, d in items if len(parts) == 1]
        groups: dict[str, list[tuple[list[str], str, Any]]] = {}
        for parts, full, d in items:
            if len(parts) > 1:
                groups.setdefault(parts[0], []).append((parts[1:], full, d))
        leaf_ids = scope.assign([leaf for leaf, _, _ in leaves])
        group_ids = scope.assign(groups)
        members: list[tuple[str, ParameterPlan | StructPlan]] = []
        for leaf, full, d in leaves:
            members.append((leaf, plan_parameter(full, d, path + (leaf_ids[leaf],))))
        for group, sub in groups.items():
            sub_prefix = f'{prefix}.{group}' if prefix else group
            members.append((group, build(sub_prefix, path + (group_ids[group],), sub, group_ids[group])))
        members.sort(key=lambda m: (m[0], isinstance(m[1], StructPlan)))
        struct.members = [m for _, m in members]
        return struct

    root = build('', (), [(name.split('.'), name, d) for name, d in pairs], '')
    flat: list[ParameterPlan] = []
    for struct in root.walk():
        flat.extend(struct.parameters)
    flat.sort(key=lambda p: p.name)
    return ParametersPlan(root, flat)


# --------------------------------------------------------------------------
# Values: the type a real node sees, and the validators


def ros_type_of(value: Any) -> str:
    """The ROS parameter type a value has, as rclpy and the rcl YAML parser decide it.

    ``1`` is an integer (never a double); ``[]`` is an empty string array for
    rclpy; ``bytes`` is a byte array; a list of mixed kinds has no type ('').
    """
    if value is None:
        return 'PARAMETER_NOT_SET'
    if isinstance(value, bool):
        return 'PARAMETER_BOOL'
    if isinstance(value, int):
        return 'PARAMETER_INTEGER'
    if isinstance(value, float):
        return 'PARAMETER_DOUBLE'
    if isinstance(value, str):
        return 'PARAMETER_STRING'
    if isinstance(value, (bytes, bytearray)):
        return 'PARAMETER_BYTE_ARRAY'
    if isinstance(value, (list, tuple)):
        if not value:
            return 'PARAMETER_STRING_ARRAY'
        kinds = {ros_type_of(v) for v in value}
        if kinds == {'PARAMETER_BYTE_ARRAY'} and all(len(v) == 1 for v in value):
            return 'PARAMETER_BYTE_ARRAY'
        if len(kinds) == 1:
            scalar = kinds.pop()
            return {'PARAMETER_BOOL': 'PARAMETER_BOOL_ARRAY',
                    'PARAMETER_INTEGER': 'PARAMETER_INTEGER_ARRAY',
                    'PARAMETER_DOUBLE': 'PARAMETER_DOUBLE_ARRAY',
                    'PARAMETER_STRING': 'PARAMETER_STRING_ARRAY'}.get(scalar, '')
    return ''


def type_problem(plan: ParameterPlan, value: Any) -> str | None:
    """Why ``value`` is not a value of the parameter's type for a real node, or None.

    As strict as a node: an integer for a double parameter is an error; an
    empty list fits any array type; a fixed size is a maximum length.
    """
    if plan.dynamic_typing:
        return None
    actual = ros_type_of(value)
    fits = actual == plan.ros_type or (
        isinstance(value, (list, tuple)) and not value and plan.type.is_array)
    if not fits:
        got = _ROS_TYPE_WORDS.get(actual, 'a list of mixed types')
        return f'expected {_ROS_TYPE_WORDS[plan.ros_type]}, got {got}'
    if plan.type.size is not None and len(value) > plan.type.size:
        return f'holds {len(value)} elements; at most {plan.type.size} fit {plan.type_name}'
    return None


def value_problems(plan: ParameterPlan, value: Any) -> list[str]:
    """Why ``value`` cannot be the parameter's value: the type, then every failing built-in validator."""
    problem = type_problem(plan, value)
    if problem is not None:
        return [problem]
    if isinstance(value, (bytes, bytearray)):
        value = list(value)
    elif plan.type.base == 'byte_array':  # rclpy holds a byte array as one-byte ``bytes`` objects
        value = [v[0] if isinstance(v, (bytes, bytearray)) else v for v in value]
    return [why for why in (v.check(value) for v in plan.builtin_validators) if why is not None]


ParameterMember = ParameterPlan | StructPlan
