"""Checks on the parameters a launch gives each node: ``unknown-parameter``,
``parameter-type``, ``parameter-invalid`` and ``missing-parameter``.

Types are checked as strictly as a real node checks its overrides (rclcpp and
rclpy raise ``InvalidParameterTypeException``): an integer for a ``double``
parameter, a boolean for a ``string``, a list of integers for a
``double_array`` are errors.  Values are checked against the built-in
validators of the declaration (the validator table; custom validators are
not evaluated).  A read-only parameter takes its launch value at declaration,
as rcl does, so overriding it at launch is no finding.

A node given parameters only the running launch knows (a parameter file whose path is a
run-time value, such as nav2's ``RewrittenYaml``: the launch reader's NODL513 warning says
so) has its known values checked as any other's; ``missing-parameter`` is not reported
for it, since the unknown source may set the parameter.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from nodl.composition.entities import EntityKind
from nodl.launch.params import RuntimeValue
from nodl.model.parameter_types import TypeSpec
from nodl.system.checks import CheckExtension
from nodl.system.context import AnalysisContext
from nodl.system.findings import Finding, make_finding
from nodl.validation.validators import value_problems
from nodl.wording import did_you_mean

__all__ = ['ParameterCheck', 'launch_value_fits', 'launch_value_verdict', 'value_type_words']


#: (resolved.parameters, without its EntityKind(kind) look-up per node)
_PARAMETER = EntityKind.PARAMETER


def _element_fits(value: Any, element: str) -> bool:
    if element == 'bool':
        return isinstance(value, bool)
    if element == 'int':
        return isinstance(value, int) and not isinstance(value, bool)
    if element == 'byte':
        # rcl's parameter YAML has no bytes and launch_ros sends integer lists as integer
        # arrays: a byte_array parameter refuses every launch value (real rclpy raises).
        return False
    if element == 'double':
        return isinstance(value, float)
    if element == 'string':
        return isinstance(value, str)
    return False


def launch_value_fits(value: Any, spec: TypeSpec) -> bool:
    """True if a node declaring a parameter of type ``spec`` accepts ``value`` as its
    override (no conversion: an int is not a double)."""
    element = spec.element  # (a property that parses the type name: asked once, not per item)
    if element == 'none':
        return True
    if spec.is_array:
        if not isinstance(value, list):
            return False
        if spec.size is not None and len(value) > spec.size:
            return False
        return all(_element_fits(v, element) for v in value)
    if spec.size is not None and isinstance(value, str) and len(value) > spec.size:
        return False
    return _element_fits(value, element)


def launch_value_verdict(value: Any, spec: TypeSpec) -> str:
    """What a node declaring a parameter of type ``spec`` makes of ``value`` as its override:
    ``accepted``, ``refused`` (rclcpp and rclpy raise ``InvalidParameterTypeException``) or
    ``unset`` (an empty list is no value for rcl: a statically typed parameter ends up
    unset, its default lost, and reading it raises ``ParameterUninitializedException``)."""
    if isinstance(value, list) and not value and spec.element != 'none':
        return 'unset'
    return 'accepted' if launch_value_fits(value, spec) else 'refused'


def value_type_words(value: Any) -> str:
    """What a value is, in parameter type words (``int``, ``double array``, ...)."""
    def scalar(v: Any) -> str:
        if isinstance(v, bool):
            return 'bool'
        if isinstance(v, int):
            return 'int'
        if isinstance(v, float):
            return 'double'
        if isinstance(v, str):
            return 'string'
        return type(v).__name__
    if isinstance(value, list):
        kinds = sorted({scalar(v) for v in value})
        return f'{kinds[0]} array' if len(kinds) == 1 else 'empty array' if not kinds \
            else 'mixed array'
    return scalar(value)


def _too_long(value: Any, spec: TypeSpec) -> bool:
    """True when ``value`` is refused only for holding more elements than the fixed-size
    array type ``spec`` allows (its first ``spec.size`` elements would fit)."""
    return (spec.size is not None and spec.is_array and isinstance(value, list)
            and len(value) > spec.size and launch_value_fits(value[:spec.size], spec))


def _show(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + '...'


def _declared_here(entity: Any) -> list[tuple[str, int, int, str]]:
    """The related location of a finding about a declared parameter (placed only when a
    finding needs it: placing is the costly part of an entity)."""
    where = entity.location
    return [(where.file, where.line, where.column,
             f"'{entity.name}' is declared here as {entity.type_name}")]


#: Values whose verdict depends on their type alone (see ParameterCheck.check).
_SCALARS = frozenset({bool, int, float})


def _needs_value(entity: Any) -> bool:
    """True for a declared parameter the launch must set: no default, and a type that takes
    a value."""
    return entity.default_value is None and not (
        isinstance(entity.type, TypeSpec) and entity.type.element == 'none')


class ParameterCheck(CheckExtension):
    """Parameters set for a node against the parameters its definition declares."""

    kinds = ('unknown-parameter', 'parameter-type', 'parameter-invalid', 'missing-parameter')

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """Findings about every node with a definition."""
        # Per resolved node (the nodes launched from one definition share it): its parameters
        # by name, and those the launch must set (no default, and a type that takes a value).
        known: dict[int, tuple[dict[str, Any], list[tuple[str, Any]]]] = {}
        # Per parameter entity (a shared base's are the same objects in every node): does the
        # launch have to set it.
        needed: dict[int, bool] = {}
        # (spec, type of value) -> launch_value_verdict, for a bool, int or float value (whose
        # verdict depends on nothing else): most launch values are, and many share a type.
        verdicts: dict[tuple[Any, type], str] = {}
        for node in context.analysed():
            assert node.instance is not None
            resolved = node.instance.resolved
            facts = known.get(id(resolved))
            if facts is None:
                by_name = {e.name: e for e in resolved.entities if e.kind is _PARAMETER}
                required = []
                for name, e in by_name.items():
                    need = needed.get(id(e))
                    if need is None:
                        need = needed[id(e)] = _needs_value(e)
                    if need:
                        required.append((name, e))
                facts = known[id(resolved)] = (by_name, required)
            declared, required = facts
            given = node.parameters
            fqn = node.fqn
            for name, setting in given.items():
                entity = declared.get(name)
                where = setting.location
                if entity is None:
                    hint = did_you_mean(name, declared)
                    yield make_finding(
                        'unknown-parameter', f"{fqn}: parameter '{name}' is set ({setting.origin}) "
                        f'but {node.executable_label} does not declare it{hint}', where, [fqn],
                        parameter=name)
                    continue
                spec = entity.type
                value = setting.value
                if not isinstance(spec, TypeSpec) or isinstance(value, RuntimeValue):
                    continue  # a value only the running launch knows is not checked
                if type(value) in _SCALARS:
                    verdict = verdicts.get((spec, type(value)))
                    if verdict is None:
                        verdict = verdicts[spec, type(value)] = launch_value_verdict(value, spec)
                else:
                    verdict = launch_value_verdict(value, spec)
                if verdict == 'unset':
                    yield make_finding(
                        'parameter-invalid', f"{fqn}: parameter '{name}' ({spec.category}) is set to "
                        'an empty list, which rcl passes as no value: the parameter ends up unset '
                        '(its default is lost) and the node fails when it reads it', where, [fqn],
                        parameter=name, related=_declared_here(entity))
                    continue
                if verdict == 'refused' and _too_long(setting.value, spec):
                    # the elements fit, their number does not (as nodl params check says it)
                    yield make_finding(
                        'parameter-type', f"{fqn}: parameter '{name}' = {_show(setting.value)} "
                        f'holds {len(setting.value)} elements; at most {spec.size} fit '
                        f'{spec.name}; the node would refuse it', where, [fqn], parameter=name,
                        related=_declared_here(entity))
                    continue
                if verdict == 'refused':
                    yield make_finding(
                        'parameter-type', f"{fqn}: parameter '{name}' is declared "
                        f'{spec.category} but is set to {_show(setting.value)} '
                        f'({value_type_words(setting.value)}); the node would refuse it',
                        where, [fqn], parameter=name, related=_declared_here(entity))
                    continue
                validation = getattr(entity.definition, 'validation', None)
                if not isinstance(validation, dict):
                    continue  # no validators to break (value_problems would find none)
                for key, why in value_problems(setting.value, entity.type_name, validation):
                    yield make_finding(
                        'parameter-invalid', f"{fqn}: parameter '{name}' = {_show(setting.value)} "
                        f'breaks {key}: {why}', where, [fqn], parameter=name,
                        related=_declared_here(entity))
            if required and node.entry.run_time and not node.entry.parameters_complete:
                continue  # a source known only at run time may set them: no claim either way
            for name, entity in required:
                if name in given:
                    continue
                where = entity.location
                yield make_finding(
                    'missing-parameter', f"{fqn}: parameter '{name}' ({entity.type_name}) has no "
                    'default and the launch does not set it; an rclcpp node throws when it declares '
                    'it, an rclpy node when it reads it',
                    node.location, [fqn], parameter=name,
                    related=[(where.file, where.line, where.column, f"'{name}' is declared here")])
