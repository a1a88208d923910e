"""The verb extension point shared by ``nodl`` and ``ros2 nodl``.

A verb is a class registered in the ``nodl.verbs`` entry point group,
normally a subclass of :class:`VerbExtension`.  The first line of its
docstring is its help text.  It must not import heavy modules at import
time: the library is imported inside :meth:`VerbExtension.main`.
"""

from __future__ import annotations

import argparse
from collections.abc import Iterable

from nodl.diagnostics import Diagnostic
from nodl.plugins import EXTENSION_POINTS, ExtensionPoint

__all__ = ['VerbExtension', 'Verb', 'EXIT_OK', 'EXIT_FAILURE', 'EXIT_USAGE', 'EXIT_INTERNAL', 'EXIT_INTERRUPTED',
           'EXIT_BROKEN_PIPE', 'EXIT_STATUSES', 'NOT_FOUND_CODES', 'failure_status', 'help_text',
           'exit_status_epilog']

EXIT_OK = 0
#: The checked thing is invalid / does not conform.
EXIT_FAILURE = 1
#: Bad usage, or input that could not be read.
EXIT_USAGE = 2
#: A bug in the toolkit (or a plugin).
EXIT_INTERNAL = 3
#: Interrupted with Ctrl-C (128 + SIGINT); what was printed before is kept.
EXIT_INTERRUPTED = 130
#: Standard output was closed early, e.g. piped into ``head`` (128 + SIGPIPE, as other tools).
EXIT_BROKEN_PIPE = 141

#: What each exit status means, the same for every verb; status 1 is described by the
#: verb's ``failure`` attribute (None: the verb never returns it).
EXIT_STATUSES = (
    (EXIT_OK, 'success'),
    (EXIT_FAILURE, ''),
    (EXIT_USAGE, 'usage error, or a path, node or output that cannot be read or written '
                 '(one line says which)'),
    (EXIT_INTERNAL, 'internal error: a bug in the toolkit or a plugin, please report it'),
    (EXIT_INTERRUPTED, 'interrupted (Ctrl-C); what was already printed is kept'),
    (EXIT_BROKEN_PIPE, 'standard output was closed early (e.g. piped into head); nothing more '
                       'is printed'),
)

#: Diagnostic codes that mean "what was asked for cannot be found or read" (a package or
#: executable not in the ament index, a registered file that is gone): exit status 2, as
#: for a missing file, in every verb; any other error is the verb's finding (status 1).
NOT_FOUND_CODES = frozenset({'NODL015', 'NODL306'})


def failure_status(diagnostics: Iterable[Diagnostic]) -> int:
    """The exit status of a verb that could not produce its result because of ``diagnostics``."""
    return EXIT_USAGE if any(d.code in NOT_FOUND_CODES for d in diagnostics) else EXIT_FAILURE


class VerbExtension(ExtensionPoint):
    """Base class of verbs (the ``nodl.verbs`` extension point).

    Subclassing it is optional (the protocol is what counts), but it gives a
    verb its extension point version and priority.
    """

    #: Version 1.0: ``add_arguments(parser)``, ``main(args) -> int``, ``failure``.
    EXTENSION_POINT_VERSION = EXTENSION_POINTS['nodl.verbs'].version

    #: What exit status 1 means for this verb (None: it never exits 1); shown in ``--help``.
    failure: str | None = 'the check found a problem'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        """Declare the verb's arguments."""

    def main(self, args: argparse.Namespace) -> int:
        """Run the verb; return the exit code."""
        raise NotImplementedError


#: The name verbs were written with before extension points had versions.
Verb = VerbExtension


def help_text(verb: object) -> str:
    """The first line of a verb's docstring."""
    doc = (type(verb).__doc__ or '').strip()
    return doc.splitlines()[0] if doc else ''


def exit_status_epilog(verb: object) -> str:
    """The ``exit status`` section of a verb's ``--help`` (see :data:`EXIT_STATUSES`)."""
    failure = getattr(verb, 'failure', Verb.failure)
    lines = ['exit status:']
    for status, meaning in EXIT_STATUSES:
        if status == EXIT_FAILURE:
            if not failure:
                continue
            meaning = failure
        lines.append(f'  {status:<4} {meaning}')
    return '\n'.join(lines)
