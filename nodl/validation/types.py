"""Interface type names: ``pkg/msg/Type``, ``pkg/srv/Type``, ``pkg/action/Type``.

The middle namespace must fit the section: topics carry messages, services
service types, actions action types.  The short form ``pkg/Type`` is
accepted (it is common in older files) with a warning naming the full form.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.wording import described, show, subject

__all__ = ['NAMESPACE_WORDS', 'split_type', 'type_problem', 'check_msg_type',
           'check_srv_type', 'check_action_type']

NAMESPACE_WORDS = {'msg': 'a message type', 'srv': 'a service type', 'action': 'an action type'}
_USERS = {'msg': 'topics carry messages', 'srv': 'services need a service type',
          'action': 'actions need an action type'}
_PACKAGE = re.compile(r'[a-z][a-z0-9_]*')
_TYPE_NAME = re.compile(r'[A-Z][A-Za-z0-9]*')


def split_type(text: str) -> tuple[str, str | None, str] | None:
    """``('std_msgs', 'msg', 'String')``; the namespace is None in the short form."""
    parts = text.split('/')
    if len(parts) == 3:
        return parts[0], parts[1], parts[2]
    if len(parts) == 2:
        return parts[0], None, parts[1]
    return None


def type_problem(text: str, namespace: str) -> tuple[Severity, str, str] | None:
    """What is wrong with ``text`` used where ``namespace`` types belong: severity, message, code."""
    example = {'msg': 'std_msgs/msg/String', 'srv': 'std_srvs/srv/Trigger',
               'action': 'test_msgs/action/Fibonacci'}[namespace]
    parts = split_type(text)
    if parts is None or not all(parts[i] for i in (0, 2)) or parts[1] == '':
        return Severity.ERROR, (f'{show(text)} is not an interface type name; '
                                f'expected package/{namespace}/Type (for example {example})'), 'NODL203'
    package, middle, name = parts
    if not _PACKAGE.fullmatch(package) or '__' in package or package.endswith('_'):
        return Severity.ERROR, (f'package name {show(package)} in {show(text)} is invalid: package '
                                "names are lowercase letters, digits and single '_', starting with a letter"), 'NODL203'
    if middle is not None and middle != namespace:
        if middle in NAMESPACE_WORDS:
            return Severity.ERROR, (f'{show(text)} is {NAMESPACE_WORDS[middle]}, but {_USERS[namespace]} '
                                    f'(package/{namespace}/Type)'), 'NODL204'
        return Severity.ERROR, (f'unknown interface namespace {show(middle)} in {show(text)}; '
                                f'expected {show(namespace)}'), 'NODL203'
    if not _TYPE_NAME.fullmatch(name):
        return Severity.ERROR, (f'type name {show(name)} in {show(text)} must be CamelCase: an uppercase '
                                'letter followed by letters and digits'), 'NODL203'
    if middle is None:
        return Severity.WARNING, (f'{show(text)} omits the interface namespace; write '
                                  f"'{package}/{namespace}/{name}'"), 'NODL205'
    return None


def _make(namespace: str) -> Any:
    def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
        if not isinstance(value, str):
            out.append(Diagnostic(Severity.ERROR, f'{subject(path)} must be a string, not '
                                  f'{described(value)}', path, code='NODL103'))
            return
        problem = type_problem(value, namespace)
        if problem is not None:
            out.append(Diagnostic(problem[0], problem[1], path, code=problem[2]))
    return check


#: Format check ``nodl-msg-type``.
check_msg_type = _make('msg')
#: Format check ``nodl-srv-type``.
check_srv_type = _make('srv')
#: Format check ``nodl-action-type``.
check_action_type = _make('action')
