"""``nodl doc --check``: are the pages on disk what the definitions give?

Each file the run would write is compared with the one on disk (its text
without the content marker): a file that differs is stale (NODL275), a file
that is missing is too (NODL276), and a page nodl wrote earlier that the run
no longer makes (a node removed from its package) is left over (NODL277).
Nothing is written.  Stale documentation then fails CI, as a test.
"""

from __future__ import annotations

import os

from nodl.diagnostics import Diagnostic, Severity
from nodl.doc import EXTENSIONS
from nodl.files import describe_os_error
from nodl.writing import marker_state, unmark

__all__ = ['check_files']

_HOW = 'run nodl doc again without --check to update it'


def check_files(files: dict[str, str], folder: str, format: str) -> list[Diagnostic]:
    """What differs between ``files`` (relative path -> text, from
    :func:`nodl.doc.writer.render_files`) and the folder ``folder``."""
    problems: list[Diagnostic] = []
    for name, text in files.items():
        path = os.path.join(folder, *name.split('/'))
        try:
            with open(path, 'rb') as stream:
                existing = stream.read().decode('utf-8', 'surrogateescape')
        except FileNotFoundError:
            problems.append(Diagnostic(Severity.ERROR, f'the page is missing; {_HOW}', file=path,
                                       code='NODL276'))
            continue
        except OSError as exc:
            problems.append(Diagnostic(Severity.ERROR, f'the page cannot be read: '
                                       f'{describe_os_error(exc)}', file=path, code='NODL276'))
            continue
        if unmark(existing) != unmark(text):
            line = _first_difference(unmark(existing), unmark(text))
            problems.append(Diagnostic(Severity.ERROR, 'the page differs from what the definitions '
                                       f'give (from line {line} on, without the marker); {_HOW}',
                                       file=path, code='NODL275'))
    wanted = {os.path.normpath(os.path.join(folder, *name.split('/'))) for name in files}
    endings = (EXTENSIONS[format], '.svg')
    for top, folders, names in os.walk(folder):
        folders.sort()
        for file_name in sorted(names):
            path = os.path.normpath(os.path.join(top, file_name))
            if not file_name.endswith(endings) or path in wanted:
                continue
            try:
                with open(path, encoding='utf-8') as stream:
                    text = stream.read()
            except (OSError, UnicodeDecodeError):
                continue
            if marker_state(text) != 'absent':
                problems.append(Diagnostic(Severity.ERROR, 'nodl wrote this page, but the '
                                           'definitions no longer give it; remove it', file=path,
                                           code='NODL277'))
    return problems


def _first_difference(old: str, new: str) -> int:
    for number, (a, b) in enumerate(zip(old.splitlines(), new.splitlines(), strict=False), 1):
        if a != b:
            return number
    return min(len(old.splitlines()), len(new.splitlines())) + 1
