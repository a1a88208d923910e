"""JUnit XML for continuous integration: one test case per checked file.

A file with an error (or, when the caller counts them, a warning) is a failed
test case whose failure lists its diagnostics; a path that could not be read
is an errored test case; the other diagnostics of a file are its
``system-out``.  Text from documents (file names, messages) is escaped, and
characters XML 1.0 cannot hold are replaced.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence
    from typing import NamedTuple

from nodl.diagnostics import Diagnostic
from nodl.text_safety import visible

__all__ = ['JUnitCase', 'JUnitFailure', 'format_junit']

#: Characters XML 1.0 does not allow, even escaped.
_NOT_XML = re.compile('[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]')

if TYPE_CHECKING:
    class JUnitFailure(NamedTuple):
        """One ``<failure>`` of a test case: its type (may be empty), message and text."""

        type: str
        message: str
        text: str

    class JUnitCase(NamedTuple):
        """One checked unit: its name, its diagnostics, and whether it failed or was unreadable.

        By default the case is named in the suite's class, and a failed case has one
        failure listing its diagnostics (the others are its output).  A verb with its own
        layout gives ``classname``, ``failures`` (one ``<failure>`` each) and ``output``
        (the ``system-out`` lines) instead.
        """

        name: str
        diagnostics: Sequence[Diagnostic]
        failed: bool
        unreadable: bool = False
        classname: str | None = None
        failures: Sequence[JUnitFailure] | None = None
        output: Sequence[str] | None = None
else:
    from collections import namedtuple

    JUnitFailure = namedtuple('JUnitFailure', ['type', 'message', 'text'])
    JUnitFailure.__doc__ = 'One ``<failure>`` of a test case: its type (may be empty), message and text.'
    JUnitCase = namedtuple('JUnitCase', ['name', 'diagnostics', 'failed', 'unreadable', 'classname',
                                         'failures', 'output'],
                           defaults=[False, None, None, None])
    JUnitCase.__doc__ = ('One checked unit: its name, its diagnostics, and whether it failed or '
                         'was unreadable (classname, failures and output: a layout of its own).')


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
        classname = suite if case.classname is None else case.classname
        out.append(f'  <testcase classname={_attribute(classname)} name={_attribute(case.name)}>')
        lines = [str(d) for d in case.diagnostics]
        if case.failures is not None or case.output is not None:
            # JUnit's schema wants the failures first and at most one system-out
            for failure in case.failures or ():
                kind = f' type={_attribute(failure.type)}' if failure.type else ''
                out.append(f'    <failure{kind} message={_attribute(failure.message)}>'
                           f'{_text(failure.text)}</failure>')
            if case.output:
                out.append(f'    <system-out>{_text(chr(10).join(case.output))}</system-out>')
        elif case.unreadable:
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
