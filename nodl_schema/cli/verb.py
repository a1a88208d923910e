"""The verb protocol shared by ``nodl`` and ``ros2 nodl``.

A verb is a class registered in the ``nodl.verbs`` entry point group.  The
first line of its docstring is its help text.  It must not import heavy
modules at import time: the library is imported inside :meth:`Verb.main`.
"""

from __future__ import annotations

import argparse

__all__ = ['Verb', 'EXIT_OK', 'EXIT_FAILURE', 'EXIT_USAGE', 'EXIT_INTERNAL', 'help_text']

EXIT_OK = 0
#: The checked thing is invalid / does not conform.
EXIT_FAILURE = 1
#: Bad usage, or input that could not be read.
EXIT_USAGE = 2
#: A bug in the toolkit (or a plugin).
EXIT_INTERNAL = 3


class Verb:
    """Base class of verbs (subclassing it is optional; the protocol is what counts)."""

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        """Declare the verb's arguments."""

    def main(self, args: argparse.Namespace) -> int:
        """Run the verb; return the exit code."""
        raise NotImplementedError


def help_text(verb: object) -> str:
    """The first line of a verb's docstring."""
    doc = (type(verb).__doc__ or '').strip()
    return doc.splitlines()[0] if doc else ''
