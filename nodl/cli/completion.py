"""Shell completion (argcomplete), loaded only when a shell asks for completions.

Enable it once per shell with ``eval "$(register-python-argcomplete nodl)"``
(argcomplete is in the toolkit's ``completion`` extra).  Verbs, options and
file paths complete; ``FILE | PACKAGE EXECUTABLE`` arguments also offer the
packages and executables registered in the ament index.
"""

from __future__ import annotations

import os
import shlex
import sys
from collections.abc import Callable
from typing import Any

from nodl.registry.registrations import list_registrations

__all__ = ['complete_definition', 'autocomplete']


def complete_definition(prefix: str = '', parsed_args: Any = None, **_: Any) -> list[str]:
    """Completions for ``FILE | PACKAGE EXECUTABLE``: paths and registered packages, or,
    after a package, its registered executables."""
    given = [t for t in (getattr(parsed_args, 'target', None) or getattr(parsed_args, 'definition', None)
                         or [])]
    try:
        registered = list_registrations()
    except Exception:  # noqa: BLE001 - completion must never fail the shell
        registered = []
    if given:  # the executable of a package
        return sorted({r.name for r in registered
                       if r.package == given[0] and r.kind == 'node' and r.name.startswith(prefix)})
    packages = sorted({r.package for r in registered if r.package.startswith(prefix)})
    from argcomplete.completers import FilesCompleter

    files: list[str] = list(FilesCompleter()(prefix))
    return packages + files


def autocomplete(build_parser: Callable[[list[str] | None], Any]) -> None:
    """If a shell asks for completions (``_ARGCOMPLETE`` is set), answer and exit."""
    import argcomplete

    line = os.environ.get('COMP_LINE', '')
    point = int(os.environ.get('COMP_POINT', len(line)))
    try:
        words = shlex.split(line[:point])[1:]
    except ValueError:
        words = []
    # Only the verb being completed needs loading (none named yet: all of them).
    parser = build_parser(words[:-1] if words and not line[:point].endswith(' ') else words)
    argcomplete.autocomplete(parser)
    sys.exit(0)  # not reached when argcomplete answered
