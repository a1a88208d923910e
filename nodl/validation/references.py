"""Mixin references: ``nodl://<package>/<name>`` or a path relative to the node file.

Only the syntax is checked here; whether a reference resolves is the job of
composition, where the resolvers (one per URI scheme, plugins) live.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.wording import described, show

__all__ = ['NODL_SCHEME', 'parse_nodl_uri', 'reference_problem', 'check_reference']

NODL_SCHEME = 'nodl'
_SCHEME = re.compile(r'([A-Za-z][A-Za-z0-9+.-]*)://(.*)', re.S)
_PACKAGE = re.compile(r'[a-z][a-z0-9_]*')
_RESOURCE = re.compile(r'[A-Za-z0-9_][A-Za-z0-9_.-]*')


def parse_nodl_uri(text: str) -> tuple[str, str] | None:
    """``nodl://pkg/name`` -> ``('pkg', 'name')``; None if malformed."""
    match = _SCHEME.fullmatch(text)
    if not match or match.group(1).lower() != NODL_SCHEME:
        return None
    package, _, name = match.group(2).partition('/')
    if not _PACKAGE.fullmatch(package) or not _RESOURCE.fullmatch(name):
        return None
    return package, name


def reference_problem(text: str) -> str | None:
    """What is wrong with the syntax of a reference, or None."""
    if not text.strip():
        return 'a mixin reference must not be empty'
    match = _SCHEME.fullmatch(text)
    if match:
        if match.group(1).lower() == NODL_SCHEME and parse_nodl_uri(text) is None:
            return (f'{show(text)} is not a valid nodl:// reference; expected '
                    'nodl://<package>/<name>, for example nodl://my_pkg/diagnostics')
        return None
    if text.startswith('/'):
        return (f'{show(text)} is an absolute path; a mixin path is relative to the node file '
                '(or use nodl://<package>/<name>)')
    return None


def check_reference(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """Format check ``nodl-reference``."""
    if not isinstance(value, str):
        out.append(Diagnostic(Severity.ERROR, f'a mixin must be a reference or an interface '
                              f'definition, not {described(value)}', path, code='NODL103'))
        return
    problem = reference_problem(value)
    if problem:
        out.append(Diagnostic(Severity.ERROR, problem, path, code='NODL217'))
