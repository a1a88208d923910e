"""Binding callbacks to declared entities: by mapping, or by decorating methods."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, TypeVar

from nodl.runtime.errors import RuntimeDefinitionError
from nodl.system import EntityKind

__all__ = ['callback', 'ActionCallbacks', 'CALLBACK_ATTRIBUTE', 'collect_callbacks', 'missing_callbacks']

#: The attribute :func:`callback` sets on a method: ``(declared name, role, kind or None)``.
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


#: A callback key: the declared name (when only one entity needing a callback has it) or
#: ``(kind, name)`` with the kind as :class:`~nodl.system.EntityKind` or its word
#: (``'subscription'``, ``'service_server'``, ``'action_server'``).
CallbackKey = Any


def callback(name: str, role: str = 'callback', kind: Any = None) -> Callable[[F], F]:
    """Mark a method of a :class:`~nodl.runtime.NodlNode` subclass as the callback of
    the entity declared as ``name``.  For an action server, ``role`` is ``execute``
    (the default for one), ``goal`` or ``cancel``.  ``kind`` (``'subscription'``,
    ``'service_server'``, ``'action_server'``) is needed only when entities of two kinds
    share the name."""
    if role not in ('callback', 'execute', 'goal', 'cancel'):
        raise ValueError(f"role {role!r} is not one of callback, execute, goal, cancel")

    def mark(function: F) -> F:
        setattr(function, CALLBACK_ATTRIBUTE, (name, role, kind))
        return function
    return mark


def _key(key: CallbackKey, needed: Mapping[tuple[Any, str], str]) -> tuple[Any, str]:
    """The ``(kind, name)`` of ``needed`` that ``key`` (a name or ``(kind, name)``) means."""
    if isinstance(key, tuple) and len(key) == 2:
        kind, name = key
        try:
            kind = EntityKind(kind)
        except ValueError:
            raise RuntimeDefinitionError(f'a callback is given for {key!r}: {kind!r} is not an entity kind '
                                         '(subscription, service_server, action_server)') from None
        if (kind, name) not in needed:
            raise RuntimeDefinitionError(f'a callback is given for {key!r}, which the definition does not '
                                         'declare as a subscription, service server or action server')
        return kind, name
    matches = [k for k in needed if k[1] == key]
    if not matches:
        raise RuntimeDefinitionError(f'a callback is given for {key!r}, which the definition declares '
                                     'as no subscription, service server or action server')
    if len(matches) > 1:
        kinds = ', '.join(repr((k.value, key)) for k, _ in sorted(matches))
        raise RuntimeDefinitionError(f'a callback is given for {key!r}, which names more than one entity: '
                                     f'key it by kind and name ({kinds})')
    return matches[0]


def collect_callbacks(owner: Any, mapping: Mapping[CallbackKey, Any] | None,
                      needed: Mapping[tuple[Any, str], str]) -> dict[tuple[Any, str], Any]:
    """``(kind, name)`` -> callable (or :class:`ActionCallbacks`) from ``mapping`` and decorated methods.

    ``needed`` maps the ``(EntityKind, declared name)`` of every entity that needs a callback to
    its kind's words.  A key may be the declared name alone when no other such entity has it.
    """
    found: dict[tuple[Any, str], Any] = {}
    problems: list[str] = []
    for key, value in (mapping or {}).items():
        try:
            resolved = _key(key, needed)
        except RuntimeDefinitionError as exc:
            problems.append(str(exc))
            continue
        if resolved in found:
            problems.append(f'two callbacks for {resolved[1]!r} in callbacks=')
        found[resolved] = value
    given = set(found)
    parts: dict[tuple[Any, str], dict[str, Callable[..., Any]]] = {}
    for attribute in dir(type(owner)):
        function = getattr(type(owner), attribute, None)
        mark = getattr(function, CALLBACK_ATTRIBUTE, None)
        if mark is None:
            continue
        name, role, kind = mark
        try:
            resolved = _key(name if kind is None else (kind, name), needed)
        except RuntimeDefinitionError as exc:
            problems.append(f'{attribute}: {exc}')
            continue
        bound = getattr(owner, attribute)
        if resolved in given:
            problems.append(f'two callbacks for {name!r}: one in callbacks=, one decorated')
        elif resolved[0] is EntityKind.ACTION_SERVER:
            parts.setdefault(resolved, {})['execute' if role == 'callback' else role] = bound
        elif resolved in found:
            problems.append(f'two decorated callbacks for {name!r}')
        else:
            found[resolved] = bound
    for resolved, roles in parts.items():
        if 'execute' not in roles:
            problems.append(f"action server {resolved[1]!r} has goal/cancel callbacks but no execute "
                            "callback (decorate one with @callback(name, 'execute'))")
            continue
        found[resolved] = ActionCallbacks(roles['execute'], roles.get('goal'), roles.get('cancel'))
    for resolved, value in list(found.items()):
        if resolved[0] is EntityKind.ACTION_SERVER and callable(value) and not isinstance(value, ActionCallbacks):
            found[resolved] = ActionCallbacks(value)
    if problems:
        raise RuntimeDefinitionError('\n'.join(problems))
    return found


def missing_callbacks(needed: Mapping[tuple[Any, str], str], bound: Mapping[tuple[Any, str], Any]) -> list[str]:
    """One line per entity (``(kind, name)`` -> kind words) that needs a callback and has none."""
    names = [n for _, n in needed]
    out = []
    for (kind, name), words in needed.items():
        if (kind, name) in bound:
            continue
        key = repr(name) if names.count(name) == 1 else repr((kind.value, name))
        hint = f'@callback({name!r})' if names.count(name) == 1 else \
            f'@callback({name!r}, kind={kind.value!r})'
        out.append(f'{words} {name!r} has no callback: pass callbacks={{{key}: ...}} or decorate a '
                   f'method with {hint}')
    return out
