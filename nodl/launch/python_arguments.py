"""The arguments a Python launch file gives an action while modules it imports are missing.

A value made from a missing module is a placeholder (:mod:`nodl.launch.python_missing`);
:func:`action_arguments` makes the arguments of a stand-in action (launch's and
launch_ros's) into what the action reads as a run-time value: an argument's name and
description as their marker text, a placeholder condition evaluated at run time, a list given
whole as a placeholder as a node's run-time keyword (:data:`nodl.launch.ros_actions.RUN_TIME_KEYWORD`),
a placeholder composable node as one whose package and plugin are known only at run time.
"""

from __future__ import annotations

import types
from typing import Any

from nodl.launch import actions as A
from nodl.launch import conditions as C
from nodl.launch.python_missing import Placeholder, RunTimeText, entities, make_placeholder, run_time
from nodl.launch.ros_actions import (
    RUN_TIME_KEYWORD,
    ComposableNode,
    ComposableNodeContainer,
    LoadComposableNodes,
    Node,
)

__all__ = ['action_arguments']


def _plain(value: Any) -> Any:
    """A text for the launch model (an argument's name, description): a placeholder's marker."""
    if isinstance(value, (Placeholder, RunTimeText)):
        return str.__str__(str(value))
    return value


def _composable(description: Any) -> Any:
    if not isinstance(description, Placeholder):
        return description
    unknown = make_placeholder(description._nodl_what, description._nodl_module,
                    missing='; the composable node it describes is missing from the analysis')
    made = ComposableNode(package=unknown, plugin=unknown)
    made.location = description.location
    return made


def action_arguments(cls: type, args: tuple[Any, ...], kwargs: dict[str, Any]) -> tuple[tuple[Any, ...],
                                                                                        dict[str, Any]]:
    """The arguments of a stand-in action, with what came from a missing module made into
    what the action reads as a run-time value (call only when :func:`stubs_active`)."""
    if issubclass(cls, A.DeclareLaunchArgument):
        args = tuple(_plain(a) for a in args)
        kwargs = {k: _plain(v) if k in ('name', 'description') else v for k, v in kwargs.items()}
        choices = kwargs.get('choices')
        if choices is not None:
            kwargs['choices'] = None if isinstance(choices, Placeholder) else [_plain(c) for c in choices]
        if 'default_value' in kwargs:
            kwargs['default_value'] = run_time(kwargs['default_value'])
        return args, kwargs
    args, kwargs = run_time(args), run_time(kwargs)
    if isinstance(kwargs.get('condition'), Placeholder):
        kwargs['condition'] = C.IfCondition(kwargs['condition'])  # evaluated: a run-time value
    if args and issubclass(cls, (A.GroupAction,)):
        args = (entities(args[0]), *args[1:])
    if args and issubclass(cls, A.IncludeLaunchDescription) and isinstance(args[0], Placeholder):
        args = (types.SimpleNamespace(location=args[0]), *args[1:])
    source = kwargs.get('launch_description_source')
    if isinstance(source, Placeholder):
        kwargs['launch_description_source'] = types.SimpleNamespace(location=source)
    for key in ('actions', 'parameters'):
        if key in kwargs:
            kwargs[key] = entities(kwargs[key])
    # A list given whole as a placeholder would iterate as nothing: the node says instead
    # that it is known only at run time (ros_actions.RUN_TIME_KEYWORD).
    if issubclass(cls, (Node, ComposableNode)):
        whole = {key: kwargs.pop(key) for key in ('remappings', 'arguments', 'ros_arguments')
                 if isinstance(kwargs.get(key), Placeholder)}
        if whole:
            kwargs[RUN_TIME_KEYWORD] = whole
    if issubclass(cls, (ComposableNodeContainer, LoadComposableNodes)) and \
            kwargs.get('composable_node_descriptions') is not None:
        kwargs['composable_node_descriptions'] = [
            _composable(d) for d in entities(kwargs['composable_node_descriptions'])]
    return args, kwargs
