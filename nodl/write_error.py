"""The error of a file the toolkit did not write: :class:`WriteError`.

Its own module, apart from :mod:`nodl.writing`, because the command line catches it for
every verb (one coded line, exit status 2) and must not load what writing files needs
(``tempfile``, ``hashlib``) to run a verb that writes nothing, such as ``nodl validate``.
"""

from __future__ import annotations

from nodl.diagnostics import Diagnostic

__all__ = ['WriteError']


class WriteError(Exception):
    """A file was not written (or not replaced); :attr:`diagnostic` says which and why.

    The message is the diagnostic's one line: ``FILE: error: message [CODE]``.
    """

    def __init__(self, diagnostic: Diagnostic) -> None:
        super().__init__(str(diagnostic))
        #: The coded diagnostic (NODL030-NODL034, NODL708), at the file concerned.
        self.diagnostic = diagnostic
