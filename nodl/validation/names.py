"""ROS 2 names: topics, services and actions, and parameter names.

Topic/service/action names follow the rules of the ROS 2 "Topic and
Service name mapping" design, as rcl applies them to names before
expansion:

* not empty; only letters, digits, ``_`` and ``/``, plus ``~`` and ``{}``;
* ``~`` only as the first character, alone or followed by ``/`` (``~/scan``);
* no token (the text between slashes) starts with a digit;
* no repeated ``/`` and no trailing ``/``;
* ``{...}`` substitutions balanced, not nested, naming ``node``, ``ns`` or
  ``namespace``.
"""

from __future__ import annotations

import re

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.validation.characters import check_text
from nodl.validation.messages import described, show, subject
from nodl.vocabulary import NAME_SUBSTITUTIONS

__all__ = ['SUBSTITUTIONS', 'ros_name_problem', 'parameter_name_problem',
           'check_ros_name', 'check_parameter_name']

#: Substitutions rcl expands in names (the vocabulary's table).
SUBSTITUTIONS = NAME_SUBSTITUTIONS

_ALLOWED = re.compile(r'[A-Za-z0-9_/~{}]*')
_SUBSTITUTION = re.compile(r'\{([^{}]*)\}')
_IDENTIFIER = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')
_PARAMETER_NAME = re.compile(r'[A-Za-z_][A-Za-z0-9_/]*(\.[A-Za-z_][A-Za-z0-9_/]*)*')


def ros_name_problem(name: str) -> str | None:
    """Which rule ``name`` breaks, or ``None`` if it is a valid ROS 2 name."""
    if not name:
        return 'a name must not be empty'
    bad = _ALLOWED.fullmatch(name) is None
    if bad:
        char = next(c for c in name if not _ALLOWED.fullmatch(c))
        return (f"contains {char!r}, which is not allowed in a ROS name; use letters, digits, "
                "'_' and '/' ('~' only as a '~/' prefix, '{}' around a substitution)")
    if '~' in name[1:] or (name.startswith('~') and name != '~' and not name.startswith('~/')):
        return "'~' may only start a name, followed by '/' (write '~/name')"
    if '//' in name:
        return "contains a repeated '/'"
    if len(name) > 1 and name.endswith('/'):
        return "must not end with '/'"
    if name == '/':
        return "'/' alone is not a topic or service name"
    depth = 0
    for char in name:
        if char == '{':
            depth += 1
            if depth > 1:
                return "substitutions cannot be nested ('{' inside '{...}')"
        elif char == '}':
            depth -= 1
            if depth < 0:
                return "has a '}' without a matching '{'"
    if depth:
        return "has a '{' without a matching '}'"
    for match in _SUBSTITUTION.finditer(name):
        inner = match.group(1)
        if not _IDENTIFIER.fullmatch(inner):
            return f'substitution {match.group(0)!r} must hold a name (letters, digits, _)'
        if inner not in SUBSTITUTIONS:
            known = ', '.join('{' + s + '}' for s in SUBSTITUTIONS)
            return f'unknown substitution {match.group(0)!r}; ROS expands {known}'
    body = name[2:] if name.startswith('~/') else name.lstrip('~')
    for token in body.split('/'):
        if token[:1].isdigit():
            return f"token '{token}' starts with a digit; name tokens must start with a letter or '_'"
    return None


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
