"""A small reader of the ament resource index.

The index is a folder tree under each prefix of ``AMENT_PREFIX_PATH``:
``<prefix>/share/ament_index/resource_index/<type>/<name>``, whose content is
free text chosen by the resource type.  The first prefix that has a resource
wins, as with ``ament_index_python``.  Reading it needs no ROS package.

This reader knows nothing of NoDL: which resources are NoDL registrations, and what
they hold, is the registry's (:mod:`nodl.registry`).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any, NamedTuple, TypeVar

__all__ = ['Resource', 'prefix_paths', 'get_resource', 'get_resources', 'package_prefix',
           'package_share_directory', 'resource_file', 'snapshot', 'in_snapshot', 'remembered']

_INDEX = os.path.join('share', 'ament_index', 'resource_index')
_T = TypeVar('_T')


class _Snapshot:
    """What one run has read of the index: each resource folder listed once, each entry read
    once, and facts derived from the index (see :func:`remembered`)."""

    def __init__(self) -> None:
        self.listings: dict[str, frozenset[str]] = {}
        # Keyed by (prefix, resource type), not by the folder's path: a look-up per node
        # then joins no path (os.path.join costs more than the rest of the look-up).
        self.folders: dict[tuple[str, str], frozenset[str]] = {}
        self.entries: dict[tuple[str, str, str], Resource] = {}
        self.facts: dict[Any, Any] = {}

    def files(self, folder: str) -> frozenset[str]:
        """The names of the files (symbolic links followed) in ``folder`` (empty if none)."""
        found = self.listings.get(folder)
        if found is None:
            try:
                with os.scandir(folder) as entries:
                    found = frozenset(e.name for e in entries if e.is_file())
            except OSError:
                found = frozenset()
            self.listings[folder] = found
        return found

    def listed(self, prefix: str, resource_type: str) -> frozenset[str]:
        """The names in ``prefix``'s folder of ``resource_type``."""
        found = self.folders.get((prefix, resource_type))
        if found is None:
            found = self.folders[prefix, resource_type] = self.files(
                os.path.join(prefix, _INDEX, resource_type))
        return found

    def entry(self, prefix: str, resource_type: str, name: str) -> Resource:
        """The listed entry ``name`` of ``prefix``'s folder of ``resource_type``, read once."""
        key = (prefix, resource_type, name)
        found = self.entries.get(key)
        if found is None:
            path = resource_file(prefix, resource_type, name)
            found = self.entries[key] = Resource(_read_text(path), prefix, path)
        return found

    def package_prefix(self, package: str, prefixes: list[str]) -> str | None:
        """The first of ``prefixes`` whose index lists ``package``."""
        for prefix in prefixes:
            if package in self.listed(prefix, 'packages'):
                return prefix
        return None


def _read_text(path: str) -> str:
    """A regular file's text as ``open(path, encoding='utf-8').read()`` gives it (newlines
    made ``\\n``), read through the file descriptor: an index entry is a few bytes, and the
    three layers of a text file object cost more than reading them."""
    fd = os.open(path, os.O_RDONLY)
    try:
        chunks = []
        while True:
            chunk = os.read(fd, 65536)
            if not chunk:
                break
            chunks.append(chunk)
            if len(chunk) < 65536:  # a regular file (entries are listed as files) is at its end
                break
    finally:
        os.close(fd)
    text = b''.join(chunks).decode('utf-8')
    return text.replace('\r\n', '\n').replace('\r', '\n') if '\r' in text else text


_SNAPSHOT: ContextVar[_Snapshot | None] = ContextVar('nodl_ament_snapshot', default=None)


@contextmanager
def snapshot() -> Iterator[None]:
    """Within the block the index is read as it was when first looked at: one listing per
    resource folder, each entry read once, and :func:`remembered` facts kept.

    For one run over many nodes (an analysis of a launched system): looking a thousand
    nodes up would otherwise cost several file system calls each.  Nested blocks share
    the outer snapshot.
    """
    if _SNAPSHOT.get() is not None:
        yield
        return
    token = _SNAPSHOT.set(_Snapshot())
    try:
        yield
    finally:
        _SNAPSHOT.reset(token)


def in_snapshot() -> bool:
    """True inside a :func:`snapshot` block."""
    return _SNAPSHOT.get() is not None


def remembered(key: Any, compute: Callable[[], _T]) -> _T:
    """``compute()``, computed once per ``key`` inside a :func:`snapshot` (each time outside
    one): for facts derived from installed files, such as a package's build type."""
    current = _SNAPSHOT.get()
    if current is None:
        return compute()
    if key in current.facts:
        found: _T = current.facts[key]
        return found
    value = current.facts[key] = compute()
    return value


class Resource(NamedTuple):
    """One resource: its content and the prefix it was found in."""

    content: str
    prefix: str
    path: str


def prefix_paths(environ: dict[str, str] | None = None) -> list[str]:
    """The prefixes of ``AMENT_PREFIX_PATH``, in order, without duplicates."""
    value = (environ if environ is not None else os.environ).get('AMENT_PREFIX_PATH', '')
    seen: list[str] = []
    for part in value.split(os.pathsep):
        if part and part not in seen:
            seen.append(part)
    return seen


def resource_file(prefix: str, resource_type: str, name: str) -> str:
    """Where a resource lives (or would live) under ``prefix``."""
    return os.path.join(prefix, _INDEX, resource_type, name)


def get_resource(resource_type: str, name: str,
                 prefixes: list[str] | None = None) -> Resource | None:
    """The first resource ``resource_type/name`` found, or None."""
    current = _SNAPSHOT.get()
    if prefixes is None:
        prefixes = prefix_paths()
    if current is not None and os.sep not in name and name not in ('', '.', '..'):
        # One run's look-ups: the folder's listing says whether the entry exists, so a
        # missing one costs no file system call.
        for prefix in prefixes:
            if name in current.listed(prefix, resource_type):
                return current.entry(prefix, resource_type, name)
        return None
    # Outside a run (or a name that is not an entry of the folder itself, looked up as a
    # path): the disk as it is now.
    for prefix in prefixes:
        path = resource_file(prefix, resource_type, name)
        if os.path.isfile(path):
            return Resource(_read_text(path), prefix, path)
    return None


def get_resources(resource_type: str, prefixes: list[str] | None = None) -> dict[str, str]:
    """Every resource name of ``resource_type`` -> the prefix it is found in (first wins)."""
    found: dict[str, str] = {}
    current = _SNAPSHOT.get()
    for prefix in prefixes if prefixes is not None else prefix_paths():
        folder = os.path.join(prefix, _INDEX, resource_type)
        if current is not None:
            for name in sorted(current.files(folder)):
                if not name.startswith('.'):
                    found.setdefault(name, prefix)
            continue
        try:
            names = sorted(os.listdir(folder))
        except OSError:
            continue
        for name in names:
            if not name.startswith('.') and os.path.isfile(os.path.join(folder, name)):
                found.setdefault(name, prefix)
    return found


def package_prefix(package: str, prefixes: list[str] | None = None) -> str | None:
    """The prefix a package is found in (the first of ``prefixes`` whose index lists it), or None."""
    current = _SNAPSHOT.get()
    if current is not None and os.sep not in package and package not in ('', '.', '..'):
        # Only whether the marker exists matters (its content is not read).
        return current.package_prefix(package, prefixes if prefixes is not None else prefix_paths())
    resource = get_resource('packages', package, prefixes)
    return resource.prefix if resource else None


def package_share_directory(package: str, prefixes: list[str] | None = None) -> str | None:
    """``<prefix>/share/<package>`` of a package in the index, or None."""
    prefix = package_prefix(package, prefixes)
    return os.path.join(prefix, 'share', package) if prefix is not None else None
