"""Finding NoDL files: explicit files of any extension, directories, stdin.

Directories are scanned the way colcon crawls a workspace:

* symbolic links to directories are followed (a repository linked into
  ``src/`` is a common layout), and each real directory is scanned once, so
  a link back to an ancestor cannot loop;
* a directory holding a ``COLCON_IGNORE`` or ``AMENT_IGNORE`` file is
  skipped, and so are hidden directories (``.git``) and, directly under a
  scanned directory, colcon's ``build``, ``install`` and ``log`` (their
  copies are not the sources);
* the files taken are those whose names end as a frontend says its files do
  (``SUFFIXES`` of :mod:`nodl.frontends`: ``*.nodl.yaml``, ``*.nodl.yml`` and
  ``*.nodl.json`` for the built-in YAML/JSON frontend, and a plug-in's own);
* only regular files (or links to them) are taken: a named pipe called
  ``x.nodl.yaml`` would block the scan, so it is skipped with a note;
* a directory that cannot be read is reported, never silently skipped.

A directory named on the command line is always scanned, marker or not.
"""

from __future__ import annotations

import os
import stat
from collections import namedtuple
from typing import TYPE_CHECKING

from nodl.frontends.frontend import frontend_suffixes

if TYPE_CHECKING:
    from collections.abc import Iterable, Iterator

__all__ = [
    'BUILD_OUTPUT_DIRS',
    'IGNORE_MARKERS',
    'NODL_SUFFIXES',
    'STDIN',
    'Target',
    'describe_os_error',
    'find_nodl_files',
    'iter_nodl_files',
    'special_file_kind',
    'tidy_path',
]

#: What a directory search looks for besides what frontend plug-ins add (the built-in
#: YAML/JSON frontend's ``SUFFIXES``).
NODL_SUFFIXES = ('.nodl.yaml', '.nodl.yml', '.nodl.json')
#: The path that means standard input.
STDIN = '-'
#: Files that make a directory scan skip the directory holding them (colcon's and ament's).
IGNORE_MARKERS = ('COLCON_IGNORE', 'AMENT_IGNORE')
#: colcon's output directories, skipped directly under a scanned directory (a workspace root).
BUILD_OUTPUT_DIRS = ('build', 'install', 'log')


class Target(namedtuple('Target', ['path', 'problem', 'special', 'skipped'],
                        defaults=[None, None, None])):
    """One thing to read: a file, standard input, or a problem finding it.

    ``special`` names what an explicitly given path is when it is not a
    regular file (``'named pipe'``, ``'character device'``): reading it may
    wait for another program.  ``skipped`` says why a file a directory scan
    found is left out (not an error: a named pipe there would block the scan).
    """

    __slots__ = ()


_SPECIAL_KINDS = ((stat.S_ISFIFO, 'named pipe'), (stat.S_ISCHR, 'character device'),
                  (stat.S_ISBLK, 'block device'), (stat.S_ISSOCK, 'socket'))


def tidy_path(path: str) -> str:
    """``path`` without ``.`` and ``..`` steps or doubled separators, as a user would write it.

    ``launch/../config/x.yaml`` becomes ``config/x.yaml``; a relative path stays relative.
    A ``..`` after a symbolic link to a folder leads where the link points, not where the
    text suggests, so a ``..`` is only taken out when the tidy path names the same file
    (or neither exists); otherwise the path is kept as it is.
    """
    if not path:
        return path
    tidy = os.path.normpath(path)
    if tidy == path or '..' not in path.split(os.sep):
        return tidy
    try:
        return tidy if os.path.samefile(path, tidy) else path
    except OSError:
        return path if os.path.lexists(path) or os.path.lexists(tidy) else tidy


def special_file_kind(mode: int) -> str | None:
    """What a non-regular, non-directory file is (``'named pipe'``...), or None for a regular file."""
    for test, kind in _SPECIAL_KINDS:
        if test(mode):
            return kind
    return None


def find_nodl_files(paths: Iterable[str]) -> list[Target]:
    """Every target of :func:`iter_nodl_files`, as a list."""
    return list(iter_nodl_files(paths))


def iter_nodl_files(paths: Iterable[str]) -> Iterator[Target]:
    """Expand paths, lazily: files are taken whatever their extension,
    directories are searched recursively for ``*.nodl.yaml``, ``*.nodl.yml``
    and ``*.nodl.json`` and the files of frontend plug-ins (see the module
    documentation for what a scan skips), and ``-`` is standard input.  Paths
    that cannot be used become targets with a problem, so that every other
    path is still processed."""
    suffixes: tuple[str, ...] | None = None
    for raw in paths:
        if raw == STDIN:
            yield Target(STDIN)
            continue
        try:
            st = os.stat(raw)
        except OSError as exc:
            yield Target(raw, _no_such(raw, exc))
            continue
        if stat.S_ISDIR(st.st_mode):
            if suffixes is None:
                suffixes = NODL_SUFFIXES + tuple(s for s in frontend_suffixes() if s not in NODL_SUFFIXES)
            found = False
            for target in _scan(raw, st, suffixes):
                found = found or (target.problem is None and target.skipped is None)
                yield target
            if not found:
                yield Target(raw, f'no NoDL files ({", ".join("*" + s for s in suffixes)}) '
                                  'found in this directory')
            continue
        kind = special_file_kind(st.st_mode)
        if kind == 'socket':
            yield Target(raw, 'is a socket, not a file')
        else:
            yield Target(raw, special=kind)


def _no_such(path: str, exc: OSError) -> str:
    if os.path.islink(path):
        return 'a symbolic link to a file or directory that does not exist'
    if isinstance(exc, FileNotFoundError):
        return 'no such file or directory'
    return describe_os_error(exc)


#: An OSError without its system's words (raised by Python itself, not by a system call) ->
#: what it means.
_OS_ERROR_WORDS: dict[type[OSError], str] = {FileNotFoundError: 'no such file or directory',
                   IsADirectoryError: 'is a directory, not a file',
                   NotADirectoryError: 'a part of the path is not a directory',
                   PermissionError: 'permission denied', FileExistsError: 'the file exists'}


def describe_os_error(exc: OSError) -> str:
    """What went wrong, in words a user reads (``No such file or directory``): the system's
    message without the ``[Errno N]`` and the path that ``str(exc)`` adds."""
    if exc.strerror:
        return exc.strerror
    if exc.errno is None and exc.args and all(isinstance(a, str) for a in exc.args):
        return str(exc)  # a message of the toolkit's own (no errno: no "[Errno N]" in it)
    words = next((text for kind, text in _OS_ERROR_WORDS.items() if isinstance(exc, kind)), None)
    if words:
        return words
    import errno

    if isinstance(exc.errno, int) and exc.errno in errno.errorcode:
        return os.strerror(exc.errno)
    return 'an input/output error'



def _scan(root: str, root_stat: os.stat_result, suffixes: tuple[str, ...]) -> Iterator[Target]:
    """Depth-first, sorted, each real directory once (by device and inode)."""
    visited = {(root_stat.st_dev, root_stat.st_ino)}
    pending = [(root, True)]
    while pending:
        directory, is_root = pending.pop()
        try:
            with os.scandir(directory) as it:
                entries = sorted(it, key=lambda e: e.name)
        except OSError as exc:
            yield Target(directory, f'cannot read this directory: {describe_os_error(exc)}')
            continue
        names = {e.name for e in entries}
        if not is_root and any(marker in names for marker in IGNORE_MARKERS):
            continue
        files: list[Target] = []
        subdirs: list[str] = []
        for entry in entries:
            name = entry.name
            try:
                is_dir = entry.is_dir()  # follows symbolic links
            except OSError:
                is_dir = False
            if is_dir:
                if name.startswith('.') or (is_root and name in BUILD_OUTPUT_DIRS):
                    continue
                try:
                    st = entry.stat()
                except OSError as exc:
                    files.append(Target(entry.path, f'cannot read this directory: {describe_os_error(exc)}'))
                    continue
                key = (st.st_dev, st.st_ino)
                if key in visited:  # a link back to an ancestor, or a second way in
                    continue
                visited.add(key)
                subdirs.append(entry.path)
                continue
            if not name.endswith(suffixes):
                continue
            try:
                st = entry.stat()
            except OSError as exc:
                files.append(Target(entry.path, _no_such(entry.path, exc)))
                continue
            if stat.S_ISREG(st.st_mode):
                files.append(Target(entry.path))
            else:
                kind = special_file_kind(st.st_mode)
                files.append(Target(entry.path, skipped=f'is a {kind}, not a regular file (name '
                                                        'it on its own to read it)'))
        yield from files
        pending.extend((d, False) for d in reversed(subdirs))
