"""Setting a parameter of a node's entry, checked at once against its declaration.

The value is typed as launch types a ``<param value=...>`` (:func:`nodl.composer.values.typed_value`),
then checked with the parameter plan every consumer shares (:mod:`nodl.plan`): the declared
type as a real node checks it, then each built-in validator.  A value that breaks them is
refused (nothing changes) with what the parameter accepts.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from nodl.composer.change import Change
from nodl.composer.model import ComposedNode, Kept, Param
from nodl.composer.values import typed_value
from nodl.diagnostics import Diagnostic, Severity
from nodl.plan.parameter_plan import plan_parameters, value_problems
from nodl.wording import did_you_mean

if TYPE_CHECKING:
    from nodl.composer.composition import Composition

__all__ = ['check_value', 'parameter_plans', 'set_parameter']


def parameter_plans(resolved: Any) -> Any:
    """The parameter plan of a resolved node (:class:`nodl.plan.ParametersPlan`)."""
    return plan_parameters(list(resolved.parameters))


def check_value(plan: Any, value: Any) -> list[str]:
    """Why ``value`` cannot be the parameter's (its type, then its validators); empty: it can."""
    return list(value_problems(plan, value))


def set_parameter(composition: Composition, ref: ComposedNode | str, name: str,
                  text: str) -> Change:
    """:meth:`Composition.set_parameter`."""
    node = composition._node_to_edit(ref)
    if isinstance(node, Change):
        return node
    path, line = composition.path, node.line
    column = len(node.indent) + 1 if line else 0
    try:
        value = typed_value(text)
    except ValueError as exc:
        return Change([Diagnostic(Severity.ERROR, f'{name}: {exc}', code='NODL977', file=path,
                                  line=line, column=column)], node.id)
    diagnostics: list[Diagnostic] = []
    resolved = composition.definition_of(node)
    if resolved is None:
        diagnostics.append(Diagnostic(
            Severity.WARNING, f'{node.label}: no definition is found, so {name} = {text} is '
            'written unchecked', code='NODL985', file=path, line=line, column=column))
    else:
        plans = parameter_plans(resolved)
        plan = plans.get(name)
        if plan is None:
            declared = [p.name for p in plans.parameters]
            return Change([Diagnostic(
                Severity.ERROR, f"{composition.fqn(node)} ({node.label}) declares no parameter "
                f"'{name}'{did_you_mean(name, declared)} (it declares: "
                f"{', '.join(declared) or 'none'})", code='NODL978', file=path, line=line, column=column)], node.id)
        if plan.ros_type == 'PARAMETER_STRING' and not isinstance(value, str):
            value = text  # a string parameter: the text is the string ('3', 'true')
        problems = check_value(plan, value)
        if problems:
            hint = ''
            if plan.ros_type == 'PARAMETER_DOUBLE' and isinstance(value, int) \
                    and not isinstance(value, bool):
                hint = f' (write {value}.0 for a double)'
            return Change([Diagnostic(
                Severity.ERROR, f'{name} = {text} is refused: {"; ".join(problems)}{hint}',
                code='NODL977', file=path, line=line, column=column)], node.id)
    _write(node, name, value)
    composition._changed(node)
    return Change(diagnostics, node.id)


def _write(node: ComposedNode, name: str, value: Any) -> None:
    """Set ``name`` in the entry: in place when no kept source after it may set it again,
    else as the entry's last parameter (a later value wins)."""
    index = next((i for i in range(len(node.params) - 1, -1, -1)
                  if isinstance(node.params[i], Param) and node.params[i].name == name), None)  # type: ignore[union-attr]
    later_kept = index is not None and any(isinstance(p, Kept) for p in node.params[index + 1:])
    if index is not None and not later_kept:
        old = node.params[index]
        node.params[index] = Param(name, value, None, old.gap)
        return
    node.params = [p for p in node.params if not (isinstance(p, Param) and p.name == name)]
    node.params.append(Param(name, value))
