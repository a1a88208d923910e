"""The runtime's parameter behaviour, on the generators' parameter plan.

The same behaviour as generated code: each parameter declared with its
descriptor (description, read_only, additional constraints, the range derived
from its validators), required parameters and every validator checked at
start-up, every batch of changes validated in the on-set callback (the whole
batch rejected with the validators' words in ``reason``) and committed in the
post-set callback into a new typed snapshot.  Validators are the validator
table's predicates (:meth:`~nodl.plan.parameter_plan.ValidatorPlan.check`);
custom validators are called through functions the user gives.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from types import SimpleNamespace
from typing import Any

from nodl.generate.python_text import python_value
from nodl.plan.parameter_plan import ParameterPlan, ParametersPlan, StructPlan
from nodl.runtime.errors import RuntimeDefinitionError

__all__ = ['ParameterSnapshot', 'normalized', 'build_snapshot', 'descriptor_of', 'problems_of',
           'custom_validator_problems', 'required_message']

#: A custom validator: ``(value, arguments as written) -> None if valid, else why not``.
CustomValidator = Callable[[Any, Any], 'str | None']


class ParameterSnapshot(SimpleNamespace):
    """A typed snapshot of a node's parameters: fields by identifier, nested by dotted name."""


def normalized(value: Any) -> Any:
    """A parameter value as the snapshot holds it: arrays as lists, byte arrays as bytes."""
    if isinstance(value, (list, tuple)) or type(value).__name__ == 'array':
        items = list(value)
        if items and all(isinstance(item, bytes) for item in items):
            return b''.join(items)
        return items
    return value


def build_snapshot(plan: ParametersPlan, values: Mapping[str, Any], stamp: int) -> ParameterSnapshot:
    """The snapshot of ``values`` (name -> value) in the plan's struct tree."""
    def build(struct: StructPlan) -> ParameterSnapshot:
        fields: dict[str, Any] = {}
        for member in struct.members:
            if isinstance(member, StructPlan):
                fields[member.field] = build(member)
            else:
                fields[member.field] = values.get(member.name)
        return ParameterSnapshot(**fields)
    snapshot = build(plan.root)
    object.__setattr__(snapshot, '_nodl_stamp', stamp)
    return snapshot


def descriptor_of(parameter: ParameterPlan) -> Any:
    """The rcl_interfaces ParameterDescriptor of ``parameter``."""
    from rcl_interfaces.msg import (
        FloatingPointRange,
        IntegerRange,
        ParameterDescriptor,
        ParameterType,
    )

    descriptor = ParameterDescriptor(
        type=getattr(ParameterType, parameter.ros_type), description=parameter.description,
        additional_constraints=parameter.constraints_text, read_only=parameter.read_only,
        dynamic_typing=parameter.dynamic_typing)
    if parameter.dynamic_typing:
        descriptor.type = ParameterType.PARAMETER_NOT_SET
    rng = parameter.range
    if rng is not None and rng.kind == 'integer':
        descriptor.integer_range = [IntegerRange(from_value=int(rng.from_value), to_value=int(rng.to_value),
                                                 step=0)]
    elif rng is not None:
        descriptor.floating_point_range = [FloatingPointRange(
            from_value=float(rng.from_value), to_value=float(rng.to_value), step=0.0)]
    return descriptor


def custom_validator_problems(plan: ParametersPlan, given: Mapping[str, CustomValidator]) -> list[str]:
    """One line per custom validator the definition uses that ``given`` does not implement."""
    out = []
    for parameter in plan.parameters:
        for validator in parameter.custom_validators:
            if validator.name not in given:
                out.append(f'parameter {parameter.name!r} uses the custom validator {validator.name!r}: '
                           f'pass custom_validators={{{validator.name!r}: function}}')
    return out


def problems_of(plan: ParametersPlan, values: Mapping[str, Any], changed: Mapping[str, Any],
                custom: Mapping[str, CustomValidator]) -> list[str]:
    """Why the ``changed`` values (within all ``values``) are invalid: every failing validator."""
    problems = []
    for name in sorted(changed):
        parameter = plan.get(name)
        if parameter is None:
            continue
        value = values[name]
        checked = list(value) if isinstance(value, (bytes, bytearray)) else value
        if parameter.size_requirement is not None and len(checked) > parameter.type.size:
            problems.append(f'parameter {name!r} = {value!r}: {parameter.size_requirement}')
        for validator in parameter.validators:
            why = validator.check(checked) if validator.builtin else custom[validator.name](value, validator.raw)
            if why:
                problems.append(f'parameter {name!r} = {value!r}: {why}')
    return problems


def python_default(parameter: ParameterPlan) -> Any:
    """The default as rclpy declares it (doubles as floats, byte arrays as one-byte bytes)."""
    return python_value(parameter.default, parameter.type.base)


def required_message(node_name: str, name: str, type_name: str) -> str:
    """The one line a node that cannot start without the parameter ``name`` reports."""
    return (f'{node_name}: required parameter {name!r} ({type_name}) is not set: pass it with '
            f'--ros-args -p {name}:=VALUE or a parameter file')


def check_required(node_name: str, missing: list[tuple[str, str]]) -> None:
    """Raise for required parameters (``(name, type)``) that were not given: one line each."""
    if missing:
        raise RuntimeDefinitionError('\n'.join(required_message(node_name, name, type_name)
                                               for name, type_name in missing))
