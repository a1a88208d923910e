"""Finding NoDL files: explicit files of any extension, directories, stdin."""

from __future__ import annotations

import os
from collections import namedtuple

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Iterable

__all__ = ['NODL_SUFFIXES', 'STDIN', 'Target', 'find_nodl_files']

#: What a directory search looks for.
NODL_SUFFIXES = ('.nodl.yaml', '.nodl.yml', '.nodl.json')
#: The path that means standard input.
STDIN = '-'


class Target(namedtuple('Target', ['path', 'problem'], defaults=[None])):
    """One thing to read: a file, standard input, or a problem finding it."""

    __slots__ = ()


def find_nodl_files(paths: Iterable[str]) -> list[Target]:
    """Expand paths: files are taken whatever their extension, directories are
    searched recursively for ``*.nodl.yaml``, ``*.nodl.yml`` and ``*.nodl.json``,
    and ``-`` is standard input.  Paths that cannot be used become targets with
    a problem, so that every other path is still processed."""
    targets: list[Target] = []
    for raw in paths:
        if raw == STDIN:
            targets.append(Target(STDIN))
            continue
        if os.path.isdir(raw):
            found = sorted(
                os.path.join(root, name)
                for root, dirs, names in os.walk(raw)
                for name in names if name.endswith(NODL_SUFFIXES))
            if not found:
                targets.append(Target(raw, f'no NoDL files ({", ".join("*" + s for s in NODL_SUFFIXES)}) '
                                           'found in this directory'))
            targets.extend(Target(f) for f in found)
        elif os.path.exists(raw):
            targets.append(Target(raw))
        else:
            targets.append(Target(raw, 'no such file or directory'))
    return targets
