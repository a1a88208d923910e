"""The core launch actions (``launch``'s): what the frontends build and the walk executes.

Each class reproduces what its ``launch`` namesake does at launch time, without starting
anything: arguments, configurations (``let``), groups and their scopes, includes, the
environment.  The ROS actions (``launch_ros``'s: nodes, namespaces, remaps, parameters)
are in :mod:`nodl.launch.ros_actions`; conditions in :mod:`nodl.launch.conditions`.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from nodl.launch.conditions import Condition
from nodl.launch.errors import LaunchProblem, SubstitutionTooLarge, too_large_message
from nodl.launch.model import LaunchArgument, SourceLocation
from nodl.launch.substitutions import Deferred, Oversized, check_joined_size, normalize, perform, perform_bounded

if TYPE_CHECKING:
    from nodl.launch.context import LaunchContext

__all__ = ['Action', 'LaunchDescription', 'DeclareLaunchArgument', 'SetLaunchConfiguration',
           'UnsetLaunchConfiguration', 'GroupAction', 'IncludeLaunchDescription',
           'SetEnvironmentVariable', 'UnsetEnvironmentVariable', 'AppendEnvironmentVariable',
           'ExecuteProcess', 'Unevaluated', 'Ignored']


class Action:
    """A launch entity: a condition, a location, and what it does when executed."""

    location: SourceLocation = SourceLocation('', 0, 0)
    condition: Condition | None = None

    def execute(self, context: LaunchContext) -> list[Action] | None:
        """Do what launch would do; return the entities to visit next."""
        return None


class LaunchDescription(Action):
    """A list of entities (a launch file's content)."""

    def __init__(self, initial_entities: Any = None, *, deprecated_reason: str | None = None) -> None:
        self.entities: list[Any] = list(initial_entities or [])

    def add_action(self, action: Any) -> None:
        """Append an action."""
        self.entities.append(action)

    add_entity = add_action

    def execute(self, context: LaunchContext) -> list[Action] | None:
        return list(self.entities)


class DeclareLaunchArgument(Action):
    """``arg``: a value given by the includer, or the default; checked against ``choices``."""

    def __init__(self, name: str, *, default_value: Any = None, description: str = '',
                 choices: Any = None, **_: Any) -> None:
        self.name = name
        self.default_value = None if default_value is None else normalize(default_value)
        self.description = description
        self.choices = None if choices is None else [str(c) for c in choices]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        value = context.configurations.get(self.name)
        argument = LaunchArgument(self.name, self.location, None, self.description,
                                  tuple(self.choices) if self.choices is not None else None)
        if not isinstance(value, (str, Deferred, Oversized)):
            if self.default_value is None:
                context.declare(argument)
                raise LaunchProblem('NODL506', f"required launch argument '{self.name}' was not "
                                               f'provided; pass {self.name}:=VALUE')
            value = perform_bounded(context, self.default_value, f"the default of launch argument "
                                    f"'{self.name}'", self.location)
            context.configurations[self.name] = value
            if isinstance(value, Oversized):
                context.declare(argument)
                raise value.problem.again()
        if isinstance(value, Oversized):  # given by an include, already reported there
            context.declare(argument)
            return None
        if self.default_value is not None:
            try:
                argument.default = perform(context, self.default_value)
            except LaunchProblem:
                argument.default = None
        argument.value = value if isinstance(value, str) else None
        context.declare(argument)
        if self.choices is not None and isinstance(value, str) and value not in self.choices:
            from nodl.wording import did_you_mean

            raise LaunchProblem('NODL505', f"argument '{self.name}' has value '{value}', which is "
                                           f'not one of its choices: {", ".join(self.choices)}'
                                           f'{did_you_mean(value, self.choices)}')
        return None


class SetLaunchConfiguration(Action):
    """``let``: set a launch configuration in the current scope."""

    def __init__(self, name: Any, value: Any, **_: Any) -> None:
        self.name, self.value = normalize(name), normalize(value)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        name = perform(context, self.name)
        value = context.configurations[name] = perform_bounded(
            context, self.value, f"the value of launch configuration '{name}'", self.location)
        if isinstance(value, Oversized):
            raise value.problem.again()
        if isinstance(value, Deferred):
            value.location = self.location  # where it is set: each use names the let
        return None


class UnsetLaunchConfiguration(Action):
    """Remove a launch configuration."""

    def __init__(self, name: Any, **_: Any) -> None:
        self.name = normalize(name)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.configurations.pop(perform(context, self.name), None)
        return None


class _Push(Action):
    def __init__(self, forwarding: bool, keep: list[tuple[Any, Any]]) -> None:
        self.forwarding, self.keep = forwarding, keep

    def execute(self, context: LaunchContext) -> list[Action] | None:
        values: list[tuple[str, Any]] = []
        for k, v in self.keep:
            name = perform(context, k)
            values.append((name, perform_bounded(context, v, f"the value of launch configuration '{name}'",
                                                 self.location)))
        context.push_configurations()
        context.push_environment()
        if not self.forwarding:
            context.reset_configurations({})
        for name, value in values:
            context.configurations[name] = value
        for _, value in values:
            if isinstance(value, Oversized):
                raise value.problem.again()
        return None


class _Pop(Action):
    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.pop_environment()
        context.pop_configurations()
        return None


class GroupAction(Action):
    """``group``: its actions, scoped (by default) or not, forwarding configurations or not."""

    def __init__(self, actions: Any, *, scoped: bool = True, forwarding: bool = True,
                 launch_configurations: Any = None, **_: Any) -> None:
        self.actions = list(actions)
        self.scoped, self.forwarding = scoped, forwarding
        self.keep = [(normalize(k), normalize(v)) for k, v in dict(launch_configurations or {}).items()]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        if not self.scoped:
            sets: list[Action] = [SetLaunchConfiguration(k, v) for k, v in self.keep]
            return sets + self.actions
        return [_Push(self.forwarding, self.keep), *self.actions, _Pop()]


class IncludeLaunchDescription(Action):
    """``include``: another launch file, its arguments set in the *current* scope (not scoped).

    The walk (:func:`nodl.launch.evaluate.include`) reads the file when it visits the
    entity: reading it takes every frontend, and the frontends build these actions."""

    def __init__(self, launch_description_source: Any, *, launch_arguments: Any = None, **_: Any) -> None:
        location = getattr(launch_description_source, 'location', launch_description_source)
        self.path = normalize(location)
        self.launch_arguments = [(normalize(k), normalize(v)) for k, v in
                                 (launch_arguments.items() if isinstance(launch_arguments, dict)
                                  else launch_arguments or [])]


class SetEnvironmentVariable(Action):
    """``set_env``."""

    def __init__(self, name: Any, value: Any, **_: Any) -> None:
        self.name, self.value = normalize(name), normalize(value)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        name = perform(context, self.name)
        context.environment[name] = perform(context, self.value)
        context.oversized_environment.pop(name, None)
        return None


class UnsetEnvironmentVariable(Action):
    """``unset_env``."""

    def __init__(self, name: Any, **_: Any) -> None:
        self.name = normalize(name)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        name = perform(context, self.name)
        context.environment.pop(name, None)
        context.oversized_environment.pop(name, None)
        return None


class AppendEnvironmentVariable(Action):
    """``append_env``."""

    def __init__(self, name: Any, value: Any, *, prepend: bool = False, separator: str = os.pathsep,
                 **_: Any) -> None:
        self.name, self.value = normalize(name), normalize(value)
        self.prepend, self.separator = prepend, separator

    def execute(self, context: LaunchContext) -> list[Action] | None:
        name, value = perform(context, self.name), perform(context, self.value)
        old = context.environment.get(name)
        if old:
            try:
                check_joined_size([old, value], self.separator)  # appending to itself doubles it
            except SubstitutionTooLarge:
                problem = context.oversized_environment[name] = SubstitutionTooLarge(
                    too_large_message(f"environment variable '{name}' after this append_env")
                    + '; what uses it is not analysed', *self.location)
                raise problem.again() from None
            value = f'{value}{self.separator}{old}' if self.prepend else f'{old}{self.separator}{value}'
        context.environment[name] = value
        return None


class ExecuteProcess(Action):
    """``executable`` (``ExecuteProcess``): a plain process, not looked into.  Said at its line
    (a warning when the command starts ROS nodes: ``ros2 ...``, ``--ros-args``, an executable
    of a package; else a note), so nodes it may start are not silently missing."""

    def __init__(self, *, cmd: Any = (), **_: Any) -> None:
        parts = cmd if isinstance(cmd, (list, tuple)) else [cmd]
        self.cmd = [normalize(part) for part in parts]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        import re

        from nodl.diagnostics import Diagnostic, Severity
        from nodl.launch.substitutions import ExecutableInPackage

        try:
            text = ' '.join(perform(context, part) for part in self.cmd)
        except LaunchProblem:
            text = ' '.join(''.join(s.describe() for s in part) for part in self.cmd)
        ros = any(isinstance(s, ExecutableInPackage) for part in self.cmd for s in part) or bool(
            re.search(r'(^|[\s/])ros2\s|--ros-args', text))
        shown = text if len(text) <= 80 else text[:77] + '...'
        what = ('the ROS nodes it starts are missing from the analysis' if ros else
                'if it starts ROS nodes, they are missing from the analysis')
        context.report(Diagnostic(Severity.WARNING if ros else Severity.INFO,
                                  f"'{shown}' runs as a plain process, which the analyser does not "
                                  f'look into; {what} (launch them with <node>/Node to analyse them)',
                                  (), *self.location, code='NODL512'))
        return None


class Ignored(Action):
    """An action that starts no node and changes nothing analysed (``log``, ``executable``...)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self.actions = [a for a in kwargs.get('actions', []) if isinstance(a, Action)]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        return list(self.actions)


class Unevaluated(Action):
    """Something only a running launch can evaluate (``OpaqueFunction``, an unknown action)."""

    def __init__(self, what: str) -> None:
        self.what = what

    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.warn('NODL512', f'{self.what} cannot be evaluated without running the launch; '
                                'nodes it would start are missing from the analysis', self.location)
        return None
