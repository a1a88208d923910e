"""The C++ side of the parameter plan: the parameter struct, declarations, validation, updates.

Everything here renders :mod:`nodl.plan.parameter_plan` (the
language-neutral plan, shared with the Python generator and the runtime)
as C++ for rclcpp.  The one C++-specific table is :data:`CPP_PREDICATES`:
each built-in validator of :mod:`nodl.validation.validators`
written as a C++ condition (a test keeps it complete, and one compiles and
runs every entry against the table's own predicate).  The reason a
rejected value gives is the table's ``requirement`` prose.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from nodl.generate import GenerationError
from nodl.generate.cpp.text import comment_lines, cpp_type, cpp_value, element_value, string_literal
from nodl.plan.identifiers import CPP_KEYWORDS, IdentifierScope, is_identifier, pascal_case
from nodl.plan.parameter_plan import ParameterPlan, ParametersPlan, StructPlan, ValidatorPlan, plan_parameters

__all__ = ['CPP_PREDICATES', 'cpp_parameter_plan', 'field_type', 'struct_lines', 'predicate',
           'custom_signature', 'custom_declarations', 'declare_lines', 'validate_lines',
           'assign_lines', 'read_lines', 'helper_lines', 'custom_definitions', 'REVISION_FIELD', 'DETAIL_NAMESPACE']

#: The field of the parameter struct counting committed changes (``is_old``); no parameter
#: field can end with ``_``, so it never collides.
REVISION_FIELD = 'revision_'
#: The namespace of the helper functions in a generated source file.
DETAIL_NAMESPACE = 'nodl_detail'


def _number(value: Any) -> str:
    return element_value(value, 'double' if isinstance(value, float) else 'int')


def _size(value: Any) -> str:
    return f'static_cast<std::size_t>({int(value)})'


def _each(v: str, condition: str) -> str:
    return (f'std::all_of({v}.begin(), {v}.end(), [](const auto & element) '
            f'{{return {condition};}})')


def _any_equal(x: str, values: Any, element: str) -> str:
    return '(' + ' || '.join(f'{x} == {element_value(a, element)}' for a in values) + ')'


#: Built-in validator -> ``f(value_expression, argument, element_kind) -> C++ condition`` that is
#: true when the value passes (``argument`` normalized as the validator table's predicate gets it).
CPP_PREDICATES: dict[str, Callable[[str, Any, str], str]] = {
    'bounds': lambda v, a, e: f'({v} >= {_number(a[0])} && {v} <= {_number(a[1])})',
    'lt': lambda v, a, e: f'({v} < {_number(a)})',
    'gt': lambda v, a, e: f'({v} > {_number(a)})',
    'lt_eq': lambda v, a, e: f'({v} <= {_number(a)})',
    'gt_eq': lambda v, a, e: f'({v} >= {_number(a)})',
    'one_of': lambda v, a, e: _any_equal(v, a, e),
    'not_empty': lambda v, a, e: f'(!{v}.empty())',
    'fixed_size': lambda v, a, e: f'({v}.size() == {_size(a)})',
    'size_gt': lambda v, a, e: f'({v}.size() > {_size(a)})',
    'size_lt': lambda v, a, e: f'({v}.size() < {_size(a)})',
    'unique': lambda v, a, e: f'{DETAIL_NAMESPACE}::all_unique({v})',
    'subset_of': lambda v, a, e: _each(v, _any_equal('element', a, e)),
    'element_bounds': lambda v, a, e: _each(
        v, f'element >= {_number(a[0])} && element <= {_number(a[1])}'),
    'lower_element_bounds': lambda v, a, e: _each(v, f'element >= {_number(a)}'),
    'upper_element_bounds': lambda v, a, e: _each(v, f'element <= {_number(a)}'),
}


def cpp_parameter_plan(parameters: Any) -> ParametersPlan:
    """The plan with C++ identifiers (keywords and the revision field avoided)."""
    return plan_parameters(parameters, keywords=CPP_KEYWORDS, reserved=(REVISION_FIELD,))


def field_type(plan: ParameterPlan) -> str:
    """The C++ type of a parameter's field (``rclcpp::ParameterValue`` for type ``none``)."""
    if plan.dynamic_typing:
        return 'rclcpp::ParameterValue'
    return cpp_type(plan.type.base)


def _struct_type_names(struct: StructPlan) -> dict[str, str]:
    scope = IdentifierScope((), CPP_KEYWORDS)
    return {s.field: scope.unique(pascal_case(s.field)) for s in struct.structs}


def struct_lines(struct: StructPlan, name: str, indent: str = '') -> list[str]:
    """``struct NAME { ... };`` with a field per parameter and a nested struct per dotted prefix."""
    lines = [f'{indent}struct {name}', f'{indent}{{']
    inner = indent + '  '
    types = _struct_type_names(struct)
    for member in struct.members:
        if isinstance(member, StructPlan):
            lines += comment_lines(f'Parameters {member.prefix}.*', inner)
            nested = struct_lines(member, types[member.field], inner)
            nested[-1] = f'{inner}}} {member.field};'
            lines += nested
            continue
        text = member.description or ''
        note = f'{member.name} ({member.type_name}' + (', read-only' if member.read_only else '') + \
            (', required' if member.required else '') + ')'
        lines += comment_lines(f'{text}\n{note}' if text else note, inner)
        if member.default is None or member.dynamic_typing:
            lines.append(f'{inner}{field_type(member)} {member.field}{{}};')
        else:
            lines.append(f'{inner}{field_type(member)} {member.field}{{'
                         f'{cpp_value(member.default, member.type.base)}}};')
    if not indent:
        lines += comment_lines('Counts the committed changes (see is_old() and try_update()).',
                               inner)
        lines.append(f'{inner}uint64_t {REVISION_FIELD}{{0}};')
    lines.append(f'{indent}}};')
    return lines


def access(plan: ParameterPlan, root: str) -> str:
    """``params.camera.exposure``: the expression of a parameter's field."""
    return '.'.join((root,) + plan.path)


def predicate(validator: ValidatorPlan, value: str, plan: ParameterPlan) -> str:
    """The C++ condition that ``value`` passes the built-in ``validator``."""
    element = plan.type.element
    return CPP_PREDICATES[validator.name](value, validator.argument, element)


def _reason(plan: ParameterPlan, requirement: str) -> str:
    return string_literal(f"invalid value for parameter '{plan.name}': it {requirement}")


def _custom_function(validator: ValidatorPlan) -> str:
    name = validator.name[:-2] if validator.name.endswith('<>') else validator.name
    parts = name.split('::')
    if not all(is_identifier(p) and p not in CPP_KEYWORDS for p in parts):
        raise GenerationError(f'custom validator {validator.key!r} is not a C++ function name '
                              '(namespace::function)')
    return name


def _custom_args(validator: ValidatorPlan) -> list[Any]:
    raw = validator.raw
    if raw is None:
        return []
    return list(raw) if isinstance(raw, list) else [raw]


def _arg_type(value: Any) -> tuple[str, str]:
    """(C++ parameter type, element kind) of a custom validator's argument."""
    if isinstance(value, bool):
        return 'bool', 'bool'
    if isinstance(value, int):
        return 'int64_t', 'int'
    if isinstance(value, float):
        return 'double', 'double'
    if isinstance(value, str):
        return 'const std::string &', 'string'
    if isinstance(value, list):
        kinds = {_arg_type(v)[1] for v in value}
        if len(kinds) == 1 and 'list' not in kinds:
            kind = kinds.pop()
            if kind == 'string':
                return 'const std::vector<std::string> &', 'string_array'
            return f'const std::vector<{cpp_type(kind)}> &', f'{kind}_array'
    raise GenerationError(f'cannot pass {value!r} to a C++ custom validator (use numbers, strings, '
                          'booleans or lists of one kind)')


def custom_signature(validator: ValidatorPlan) -> tuple[str, tuple[str, ...]]:
    """(function name, argument types) of a custom validator's hook."""
    return _custom_function(validator), tuple(_arg_type(a)[0] for a in _custom_args(validator))


def _custom_hooks(plan: ParametersPlan) -> list[tuple[list[str], str, int, str]]:
    """One entry per distinct custom validator signature, sorted: (namespaces, function name,
    number of arguments, parameter list of the C++ function)."""
    seen: dict[tuple[str, tuple[str, ...]], None] = {}
    for parameter in plan.parameters:
        for validator in parameter.custom_validators:
            seen[custom_signature(validator)] = None
    hooks = []
    for name, args in sorted(seen):
        *namespaces, function = name.split('::')
        params = ', '.join(['const rclcpp::Parameter & parameter'] + [
            f'{t} arg{i}' for i, t in enumerate(args)])
        hooks.append((namespaces, function, len(args), params))
    return hooks


def _in_namespaces(namespaces: list[str], body: list[str]) -> list[str]:
    if not namespaces:
        return body
    joined = '::'.join(namespaces)
    return [f'namespace {joined}', '{'] + body + [f'}}  // namespace {joined}']


def custom_declarations(plan: ParametersPlan) -> list[str]:
    """Declarations of the custom validator functions the user defines (one per signature)."""
    lines: list[str] = []
    for namespaces, function, _, params in _custom_hooks(plan):
        lines += _in_namespaces(namespaces, [f'std::string {function}({params});'])
    return lines


def custom_definitions(plan: ParametersPlan) -> list[str]:
    """Placeholder definitions of the custom validators (accept every value), for a user stub."""
    lines: list[str] = []
    for namespaces, function, count, params in _custom_hooks(plan):
        body = ['{', '  (void)parameter;'] + [f'  (void)arg{i};' for i in range(count)] + [
            '  return std::string();  // TODO: return why the value is rejected, if it is', '}']
        lines += _in_namespaces(namespaces, [f'std::string {function}({params})'] + body)
    return lines


def _descriptor_lines(plan: ParameterPlan, indent: str) -> list[str]:
    lines = [f'{indent}rcl_interfaces::msg::ParameterDescriptor descriptor;']
    if plan.description:
        lines.append(f'{indent}descriptor.description = {string_literal(plan.description)};')
    if plan.constraints_text:
        lines.append(f'{indent}descriptor.additional_constraints = '
                     f'{string_literal(plan.constraints_text)};')
    if plan.read_only:
        lines.append(f'{indent}descriptor.read_only = true;')
    if plan.dynamic_typing:
        lines.append(f'{indent}descriptor.dynamic_typing = true;')
    if plan.range is not None:
        kind = plan.range.kind
        element = 'int' if kind == 'integer' else 'double'
        lines += [f'{indent}descriptor.{kind}_range.resize(1);',
                  f'{indent}descriptor.{kind}_range[0].from_value = '
                  f'{element_value(plan.range.from_value, element)};',
                  f'{indent}descriptor.{kind}_range[0].to_value = '
                  f'{element_value(plan.range.to_value, element)};',
                  f'{indent}descriptor.{kind}_range[0].step = '
                  f'{element_value(plan.range.step, element if kind == "floating_point" else "int")};']
    return lines


def declare_lines(plan: ParametersPlan, indent: str) -> list[str]:
    """Declarations of every parameter with its descriptor; required ones collected, then reported."""
    lines = [f'{indent}std::vector<std::string> missing;']
    for parameter in plan.parameters:
        lines.append(f'{indent}{{')
        inner = indent + '  '
        lines += comment_lines(parameter.name, inner, '//')
        lines += _descriptor_lines(parameter, inner)
        name = string_literal(parameter.name)
        if parameter.dynamic_typing:
            lines.append(f'{inner}this->declare_parameter({name}, rclcpp::ParameterValue(), '
                         'descriptor);')
        elif parameter.required:
            lines += [f'{inner}try {{',
                      f'{inner}  this->declare_parameter({name}, '
                      f'rclcpp::ParameterType::{parameter.ros_type}, descriptor);',
                      f'{inner}}} catch (const rclcpp::exceptions::NoParameterOverrideProvided &) {{',
                      f'{inner}  missing.push_back({name});',
                      f'{inner}}}']
        else:
            lines.append(f'{inner}this->declare_parameter({name}, rclcpp::ParameterValue('
                         f'{cpp_value(parameter.default, parameter.type.base)}), descriptor);')
        lines.append(f'{indent}}}')
    lines += [f'{indent}if (!missing.empty()) {{',
              f'{indent}  std::string names;',
              f'{indent}  for (const auto & name : missing) {{',
              f'{indent}    names += (names.empty() ? "" : ", ") + name;',
              f'{indent}  }}',
              f'{indent}  throw std::runtime_error(',
              f'{indent}    "required parameters have no value: " + names + '
              '"; give each a value (--ros-args -p NAME:=VALUE, or a parameter file)");',
              f'{indent}}}']
    return lines


def _get_value(parameter: ParameterPlan, source: str) -> str:
    if parameter.dynamic_typing:
        return f'{source}.get_parameter_value()'
    return f'{source}.get_value<{field_type(parameter)}>()'


def read_lines(plan: ParametersPlan, target: str, indent: str) -> list[str]:
    """Reads every declared parameter into the struct ``target``."""
    return [f'{indent}{access(p, target)} = '
            f'{_get_value(p, f"this->get_parameter({string_literal(p.name)})")};'
            for p in plan.parameters]


def assign_lines(plan: ParametersPlan, target: str, source: str, indent: str) -> list[str]:
    """Statements assigning parameter ``source`` to its field of ``target`` (sets ``known``)."""
    lines = []
    keyword = 'if'
    for p in plan.parameters:
        lines += [f'{indent}{keyword} ({source}.get_name() == {string_literal(p.name)}) {{',
                  f'{indent}  {access(p, target)} = {_get_value(p, source)};',
                  f'{indent}  known = true;']
        keyword = '} else if'
    if lines:
        lines.append(f'{indent}}}')
    return lines


def validate_lines(plan: ParametersPlan, params: str, indent: str) -> list[str]:
    """Statements returning the reason of the first parameter that fails, in name order."""
    lines: list[str] = []
    for p in plan.parameters:
        value = access(p, params)
        if p.type.size is not None and p.size_requirement is not None:
            lines += [f'{indent}if ({value}.size() > {_size(p.type.size)}) {{',
                      f'{indent}  return {_reason(p, p.size_requirement)};',
                      f'{indent}}}']
        for validator in p.builtin_validators:
            lines += [f'{indent}if (!{predicate(validator, value, p)}) {{',
                      f'{indent}  return {_reason(p, validator.requirement)};',
                      f'{indent}}}']
        for validator in p.custom_validators:
            name, _ = custom_signature(validator)
            args = [f'rclcpp::Parameter({string_literal(p.name)}, {value})']
            for arg in _custom_args(validator):
                kind = _arg_type(arg)[1]
                args.append(cpp_value(arg, kind) if kind.endswith('_array')
                            else element_value(arg, kind))
            lines += [f'{indent}{{',
                      f'{indent}  const std::string reason = {name}({", ".join(args)});',
                      f'{indent}  if (!reason.empty()) {{',
                      f'{indent}    return std::string({_reason(p, "is rejected by " + validator.key)}) '
                      '+ ": " + reason;',
                      f'{indent}  }}',
                      f'{indent}}}']
    lines.append(f'{indent}return std::string();')
    return lines


def uses_unique(plan: ParametersPlan) -> bool:
    """True if a parameter uses ``unique<>`` (the source then needs its helper)."""
    return any(v.name == 'unique' for p in plan.parameters for v in p.builtin_validators)


def helper_lines() -> list[str]:
    """The helper functions :data:`CPP_PREDICATES` calls (``unique<>``)."""
    return [f'namespace {DETAIL_NAMESPACE}',
            '{',
            'template<typename T>',
            'bool all_unique(const std::vector<T> & values)',
            '{',
            '  for (std::size_t i = 0; i < values.size(); ++i) {',
            '    for (std::size_t j = i + 1; j < values.size(); ++j) {',
            '      if (values[i] == values[j]) {',
            '        return false;',
            '      }',
            '    }',
            '  }',
            '  return true;',
            '}',
            f'}}  // namespace {DETAIL_NAMESPACE}']
