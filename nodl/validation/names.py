"""ROS 2 names in definitions: topics, services and actions, and parameter names.

A topic, service or action name follows rcl's rules, which live in one place,
:func:`nodl.naming.declared_name_error` (tested against real rclpy).  This module
words rcl's reason for a definition's author, naming the character, token or
substitution at fault and what to write instead.  Parameter names follow the
NoDL rule: words of letters, digits, ``_`` and ``/`` separated by ``.``.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.naming.resolution import declared_name_error
from nodl.validation.characters import check_text
from nodl.vocabulary import NAME_SUBSTITUTIONS
from nodl.wording import described, show, subject

__all__ = ['SUBSTITUTIONS', 'ros_name_problem', 'parameter_name_problem',
           'check_ros_name', 'check_parameter_name']

#: Substitutions rcl expands in names (the vocabulary's table).
SUBSTITUTIONS = NAME_SUBSTITUTIONS

_ALLOWED = re.compile(r'[A-Za-z0-9_/~{}]')
_SUBSTITUTION = re.compile(r'\{([^{}]*)\}')
_IDENTIFIER = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')
_PARAMETER_NAME = re.compile(r'[A-Za-z_][A-Za-z0-9_/]*(\.[A-Za-z_][A-Za-z0-9_/]*)*')

_TILDE = "'~' may only start a name, followed by '/' (write '~/name')"


def ros_name_problem(name: str) -> str | None:
    """Which rule ``name`` breaks, or ``None`` if rcl accepts it as a topic/service/action name.

    The rules are rcl's (:func:`nodl.naming.declared_name_error`); the wording says
    what is at fault and what to write.
    """
    reason = declared_name_error(name)
    return None if reason is None else _worded(name, reason)


def _worded(name: str, reason: str) -> str:
    """rcl's ``reason`` for refusing ``name``, as a definition's author reads it."""
    if not name:
        return 'a name must not be empty'
    if name == '/':
        return "'/' alone is not a topic or service name"
    if 'characters other than alphanumerics' in reason and 'substitution' not in reason:
        char = next(c for c in name if not _ALLOWED.fullmatch(c))
        return (f"contains {char!r}, which is not allowed in a ROS name; use letters, digits, "
                "'_' and '/' ('~' only as a '~/' prefix, '{}' around a substitution)")
    if 'tilde' in reason:
        return _TILDE
    if 'unbalanced' in reason:
        depth = 0
        for char in name:
            depth += (char == '{') - (char == '}')
            if depth < 0:
                return "has a '}' without a matching '{'"
        return "has a '{' without a matching '}'"
    if reason.startswith('substitution name'):
        if name.count('{') > name.count('}') or _nested(name):
            return "substitutions cannot be nested ('{' inside '{...}')"
        return _substitution_wording(name)
    if reason.startswith('unknown substitution'):
        return _substitution_wording(name)
    if 'repeated' in reason:
        if '//' in name:
            return "contains a repeated '/'"
        return ("gives a repeated '/' once expanded: '{ns}' and '{namespace}' expand to an "
                "absolute namespace (/ns), so only the start of a name may hold them; write "
                "'{ns}/x', not '/{ns}/x' or 'a/{ns}/x'")
    if 'end with' in reason:
        return "must not end with '/'"
    if 'start with a number' in reason or 'starts with a number' in reason:
        body = name[2:] if name.startswith('~/') else name
        token = next(t for t in body.split('/') if t[:1].isdigit())
        return f"token '{token}' starts with a digit; name tokens must start with a letter or '_'"
    return reason


def _nested(name: str) -> bool:
    """Whether a ``{`` opens inside a substitution."""
    depth = 0
    for char in name:
        depth += (char == '{') - (char == '}')
        if depth > 1:
            return True
    return False


def _substitution_wording(name: str) -> str:
    """The first substitution of ``name`` that is not a known word, worded."""
    for match in _SUBSTITUTION.finditer(name):
        inner = match.group(1)
        if not _IDENTIFIER.fullmatch(inner):
            return f'substitution {match.group(0)!r} must hold a name (letters, digits, _)'
        if inner not in SUBSTITUTIONS:
            known = ', '.join('{' + s + '}' for s in SUBSTITUTIONS)
            return f'unknown substitution {match.group(0)!r}; ROS expands {known}'
    return "substitutions cannot be nested ('{' inside '{...}')"


def parameter_name_problem(name: str) -> str | None:
    """Which rule a parameter name breaks, or ``None``."""
    if not name:
        return 'a parameter name must not be empty'
    if _PARAMETER_NAME.fullmatch(name) is None:
        return ("parameter names are words of letters, digits, '_' and '/' separated by '.', "
                "each word starting with a letter or '_'")
    return None


def check_ros_name(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """Format check ``nodl-ros-name``."""
    if not isinstance(value, str):
        out.append(Diagnostic(Severity.ERROR, f'{subject(path)} must be a string, not '
                              f'{described(value)}', path, code='NODL103'))
        return
    if check_text(value, 'ROS name', path, out):
        return
    problem = ros_name_problem(value)
    if problem:
        out.append(Diagnostic(Severity.ERROR, f'invalid ROS name {show(value)}: {problem}', path,
                              code='NODL201'))


def check_parameter_name(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """Format check ``nodl-parameter-name`` (applied to mapping keys)."""
    if isinstance(value, str) and not check_text(value, 'parameter name', path, out, 'key'):
        problem = parameter_name_problem(value)
        if problem:
            out.append(Diagnostic(Severity.ERROR, f'invalid parameter name {show(value)}: {problem}',
                                  path, anchor='key', code='NODL202'))
