"""Launch conditions (``if``/``unless``, ``LaunchConfigurationEquals``): whether an action runs.

A condition's text is performed and read as ``launch`` reads it: ``true``/``1`` or
``false``/``0`` in any case; anything else is an error (NODL514).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from nodl.launch.errors import LaunchProblem
from nodl.launch.substitutions import Substitution, normalize, perform

if TYPE_CHECKING:
    from nodl.launch.context import LaunchContext

__all__ = ['Condition', 'IfCondition', 'UnlessCondition', 'LaunchConfigurationEquals',
           'LaunchConfigurationNotEquals']


class Condition:
    """Decides whether an action runs."""

    def evaluate(self, context: LaunchContext) -> bool:
        """True if the action runs."""
        raise NotImplementedError


def _condition_value(context: LaunchContext, expression: list[Substitution]) -> bool:
    text = perform(context, expression).strip().lower()
    if text in ('true', '1'):
        return True
    if text in ('false', '0'):
        return False
    raise LaunchProblem('NODL514', f"condition expression '{text}' is neither true nor false; "
                                   "expected 'true', 'false', '1' or '0' (any case)")


class IfCondition(Condition):
    """``if="..."``: runs when the expression is true."""

    def __init__(self, predicate_expression: Any) -> None:
        self.expression = normalize(predicate_expression)

    def evaluate(self, context: LaunchContext) -> bool:
        return _condition_value(context, self.expression)


class UnlessCondition(IfCondition):
    """``unless="..."``: runs when the expression is false."""

    def evaluate(self, context: LaunchContext) -> bool:
        return not _condition_value(context, self.expression)


class LaunchConfigurationEquals(Condition):
    """Runs when a launch configuration equals a value (None: the configuration is unset)."""

    def __init__(self, launch_configuration_name: str, expected_value: Any) -> None:
        self.name = launch_configuration_name
        self.expected = None if expected_value is None else normalize(expected_value)

    def evaluate(self, context: LaunchContext) -> bool:
        value = context.configurations.get(self.name)
        expected = None if self.expected is None else perform(context, self.expected)
        return (value if isinstance(value, str) else None) == expected


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    """The opposite of :class:`LaunchConfigurationEquals`."""

    def evaluate(self, context: LaunchContext) -> bool:
        return not super().evaluate(context)
