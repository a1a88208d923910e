"""What the studio lets a request do: the token every request carries, the hosts it
answers, and the folders it may read and write.

* :func:`new_token`: a random URL-safe token (192 bits), printed once in the address;
  :func:`same_token` compares in constant time.
* :func:`allowed_host`: the ``Host`` header must name the loopback address the server is
  bound to (a page of another site that resolves its name to 127.0.0.1, "DNS
  rebinding", sends its own name and is refused).
* :class:`FolderGuard`: the folders given on the command line and the launch file's
  folder.  A path is inside when its real path (links resolved, ``..`` removed) is under
  the real path of one of them; a link that leads out is refused, as is a path that
  only looks inside (``root/../elsewhere``).
"""

from __future__ import annotations

import hmac
import os
import secrets
from collections.abc import Iterable

from nodl.diagnostics import Diagnostic, Severity

__all__ = ['TOKEN_HEADER', 'TOKEN_QUERY', 'FolderGuard', 'allowed_host', 'new_token', 'same_token']

#: The request header the page's script sends the token in.
TOKEN_HEADER = 'x-nodl-token'
#: The query parameter of the address printed (and of the page's own files).
TOKEN_QUERY = 'token'
#: The host names that mean the loopback address the server binds to.
_LOOPBACK_NAMES = ('127.0.0.1', 'localhost')


def new_token() -> str:
    """A new random token."""
    return secrets.token_urlsafe(24)


def same_token(given: str | None, token: str) -> bool:
    """True if ``given`` is ``token`` (compared in constant time)."""
    if not given:
        return False
    return hmac.compare_digest(given.encode('utf-8', 'replace'), token.encode('utf-8'))


def allowed_host(host: str | None, port: int) -> bool:
    """True if a request's ``Host`` header names the loopback server on ``port``."""
    if not host:
        return False
    name, sep, given_port = host.rpartition(':')
    if not sep:
        name, given_port = host, '80'
    return name.lower() in _LOOPBACK_NAMES and given_port == str(port)


class FolderGuard:
    """The folders the studio may read and write under."""

    def __init__(self, roots: Iterable[str | os.PathLike[str]]) -> None:
        real = [os.path.realpath(os.fspath(r)) for r in roots]
        #: Their real paths, each once.
        self.roots: list[str] = list(dict.fromkeys(real))

    def inside(self, path: str | os.PathLike[str]) -> bool:
        """True if ``path`` (links resolved, existing or not) is under one of the folders."""
        real = os.path.realpath(os.fspath(path))
        return any(real == root or real.startswith(root.rstrip(os.sep) + os.sep)
                   for root in self.roots)

    def check(self, path: str | os.PathLike[str], what: str = 'the file') -> Diagnostic | None:
        """None if ``path`` may be read or written; else why not (NODL990)."""
        if self.inside(path):
            return None
        folders = ', '.join(self.roots) or 'none'
        return Diagnostic(Severity.ERROR,
                          f'{what} is outside the folders nodl studio was started with '
                          f'({folders}): give its folder with --definitions, or start the studio '
                          'on a launch file there', (), os.fspath(path), 0, 0, code='NODL990')
