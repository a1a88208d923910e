"""JUnit XML for continuous integration: one test case per checked file.

A file with an error (or, when the caller counts them, a warning) is a failed
test case whose failure lists its diagnostics; a path that could not be read
is an errored test case; the other diagnostics of a file are its
``system-out``.  Text from documents (file names, messages) is escaped, and
characters XML 1.0 cannot hold are replaced.
"""

from __future__ import annotations

import re

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Iterable, NamedTuple, Sequence

from nodl.diagnostics import Diagnostic
from nodl.text_safety import visible

__all__ = ['JUnitCase', 'format_junit']

#: Characters XML 1.0 does not allow, even escaped.
_NOT_XML = re.compile('[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]')

if TYPE_CHECKING:
    class JUnitCase(NamedTuple):
        """One checked file: its name, its diagnostics, and whether it failed or was unreadable."""

        name: str
        diagnostics: Sequence[Diagnostic]
        failed: bool
        unreadable: bool = False
else:
    from collections import namedtuple

    JUnitCase = namedtuple('JUnitCase', ['name', 'diagnostics', 'failed', 'unreadable'],
                           defaults=[False])
    JUnitCase.__doc__ = ('One checked file: its name, its diagnostics, and whether it failed or '
                         'was unreadable.')


def _text(text: str) -> str:
    from xml.sax.saxutils import escape

    return escape(_NOT_XML.sub('\ufffd', visible(text)))


def _attribute(text: str) -> str:
    from xml.sax.saxutils import quoteattr

    return quoteattr(_NOT_XML.sub('\ufffd', visible(text)))


def format_junit(cases: Iterable[JUnitCase], suite: str) -> str:
    """A JUnit XML test suite named ``suite`` with one test case per :class:`JUnitCase`."""
    items = list(cases)
    failures = sum(1 for c in items if c.failed and not c.unreadable)
    errors = sum(1 for c in items if c.unreadable)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<testsuite name={_attribute(suite)} tests="{len(items)}" failures="{failures}" '
           f'errors="{errors}">']
    for case in items:
        out.append(f'  <testcase classname={_attribute(suite)} name={_attribute(case.name)}>')
        lines = [str(d) for d in case.diagnostics]
        if case.unreadable:
            message = case.diagnostics[0].message if case.diagnostics else 'cannot be read'
            out.append(f'    <error message={_attribute(message)}>{_text(chr(10).join(lines))}</error>')
        elif case.failed:
            out.append(f'    <failure message={_attribute(f"{len(lines)} diagnostic(s)")}>'
                       f'{_text(chr(10).join(lines))}</failure>')
        elif lines:
            out.append(f'    <system-out>{_text(chr(10).join(lines))}</system-out>')
        out.append('  </testcase>')
    out.append('</testsuite>')
    return '\n'.join(out) + '\n'
