"""Binding callbacks to declared entities: by mapping, or by decorating methods."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Mapping, TypeVar

from nodl_schema.runtime.errors import RuntimeDefinitionError

__all__ = ['callback', 'ActionCallbacks', 'CALLBACK_ATTRIBUTE', 'collect_callbacks', 'missing_callbacks']

#: The attribute :func:`callback` sets on a method: ``(declared name, role)``.
CALLBACK_ATTRIBUTE = '__nodl_callback__'

F = TypeVar('F', bound=Callable[..., Any])


@dataclass(frozen=True)
class ActionCallbacks:
    """The callbacks of an action server: ``execute(goal_handle) -> Result`` is required;
    ``goal(goal_request) -> GoalResponse`` and ``cancel(goal_handle) -> CancelResponse``
    default to rclpy's (accept every goal, reject every cancellation)."""

    execute: Callable[..., Any]
    goal: Callable[..., Any] | None = None
    cancel: Callable[..., Any] | None = None


def callback(name: str, role: str = 'callback') -> Callable[[F], F]:
    """Mark a method of a :class:`~nodl_schema.runtime.NodlNode` subclass as the callback of
    the entity declared as ``name``.  For an action server, ``role`` is ``execute``
    (the default for one), ``goal`` or ``cancel``."""
    if role not in ('callback', 'execute', 'goal', 'cancel'):
        raise ValueError(f"role {role!r} is not one of callback, execute, goal, cancel")

    def mark(function: F) -> F:
        setattr(function, CALLBACK_ATTRIBUTE, (name, role))
        return function
    return mark


def collect_callbacks(owner: Any, mapping: Mapping[str, Any] | None,
                      action_servers: set[str]) -> dict[str, Any]:
    """Declared name -> callable (or :class:`ActionCallbacks`) from ``mapping`` and decorated methods."""
    found: dict[str, Any] = dict(mapping or {})
    parts: dict[str, dict[str, Callable[..., Any]]] = {}
    for attribute in dir(type(owner)):
        function = getattr(type(owner), attribute, None)
        mark = getattr(function, CALLBACK_ATTRIBUTE, None)
        if mark is None:
            continue
        name, role = mark
        bound = getattr(owner, attribute)
        if name in action_servers:
            parts.setdefault(name, {})['execute' if role == 'callback' else role] = bound
        else:
            if name in found:
                raise RuntimeDefinitionError(f'two callbacks for {name!r}: one in callbacks=, one decorated')
            found[name] = bound
    for name, roles in parts.items():
        if name in found:
            raise RuntimeDefinitionError(f'two callbacks for {name!r}: one in callbacks=, one decorated')
        if 'execute' not in roles:
            raise RuntimeDefinitionError(f"action server {name!r} has goal/cancel callbacks but no "
                                         "execute callback (decorate one with @callback(name, 'execute'))")
        found[name] = ActionCallbacks(roles['execute'], roles.get('goal'), roles.get('cancel'))
    for name, value in list(found.items()):
        if name in action_servers and callable(value) and not isinstance(value, ActionCallbacks):
            found[name] = ActionCallbacks(value)
    return found


def missing_callbacks(needed: Mapping[str, str], bound: Mapping[str, Any]) -> list[str]:
    """One line per entity (declared name -> kind words) that needs a callback and has none."""
    return [f'{kind} {name!r} has no callback: pass callbacks={{{name!r}: ...}} or decorate a '
            f'method with @callback({name!r})' for name, kind in needed.items() if name not in bound]
