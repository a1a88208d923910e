"""Entry-point plugins: discovery and fault-tolerant loading.

Every extension point of the toolkit (verbs, reference resolvers, and later
generators, analysis checks and output formats) is an entry point group.
The built-in implementations are registered in ``pyproject.toml`` exactly as
a third-party package would register its own.

Discovery reads the standard ``entry_points.txt`` metadata files directly.
``importlib.metadata.entry_points()`` builds a distribution object for every
installed package before filtering, which costs about 100 ms in a virtual
environment holding the ROS 2 wheels; reading the same files costs a few
milliseconds and keeps ``nodl`` start-up fast.  The first distribution found
on ``sys.path`` wins, as with ``importlib.metadata``.
"""

from __future__ import annotations

import os
import re
import sys
from collections import namedtuple

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any, Callable, Iterable

__all__ = [
    'PluginError',
    'EntryPointSpec',
    'iter_entry_points',
    'load_plugins',
]

_NORMALIZE = re.compile(r'[-_.]+')
_META_SUFFIXES = ('.dist-info', '.egg-info')


class EntryPointSpec(namedtuple('EntryPointSpec', ['name', 'value', 'group', 'distribution'], defaults=[''])):
    """One entry point as declared by a distribution."""

    __slots__ = ()

    def load(self) -> Any:
        """Import the module and return the named attribute."""
        import importlib

        module_name, _, attr = self.value.partition(':')
        obj: Any = importlib.import_module(module_name.strip())
        for part in attr.strip().split('.') if attr.strip() else ():
            obj = getattr(obj, part)
        return obj


class PluginError(namedtuple('PluginError', ['group', 'name', 'value', 'distribution', 'error'])):
    """A plugin that could not be loaded; reported, never fatal."""

    __slots__ = ()

    def __str__(self) -> str:
        where = f' (from {self.distribution})' if self.distribution else ''
        return (
            f"warning: skipped plugin '{self.name}' of group '{self.group}'{where}: "
            f'{self.error}'
        )


class _Scan:
    def __init__(self, paths: tuple[str, ...]) -> None:
        self.paths = paths
        self.groups: dict[str, list[EntryPointSpec]] = {}


_cache: _Scan | None = None


def _dist_name(meta_dir: str) -> str:
    stem = meta_dir.rsplit('.', 1)[0]
    # "name-version" (dist-info) or "name-version-pyX" / "name" (egg-info)
    name = stem.split('-', 1)[0]
    return _NORMALIZE.sub('-', name).lower()


def _parse_entry_points(text: str, distribution: str, into: dict[str, list[EntryPointSpec]]) -> None:
    group = None
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line[0] in '#;':
            continue
        if line[0] == '[' and line[-1] == ']':
            group = line[1:-1].strip()
            continue
        if group is None or '=' not in line:
            continue
        name, _, value = line.partition('=')
        into.setdefault(group, []).append(
            EntryPointSpec(name.strip(), value.strip(), group, distribution)
        )


def _scan(paths: Iterable[str]) -> _Scan:
    scan = _Scan(tuple(paths))
    seen: set[str] = set()
    for entry in scan.paths:
        try:
            names = sorted(os.listdir(entry or '.'))
        except OSError:
            continue
        for name in names:
            if not name.endswith(_META_SUFFIXES):
                continue
            dist = _dist_name(name)
            if dist in seen:
                continue
            seen.add(dist)
            try:
                with open(os.path.join(entry or '.', name, 'entry_points.txt'), encoding='utf-8') as f:
                    text = f.read()
            except OSError:
                continue
            _parse_entry_points(text, dist, scan.groups)
    return scan


def iter_entry_points(group: str) -> list[EntryPointSpec]:
    """Return the entry points of ``group`` from every installed distribution.

    Within a group a name is unique: the first distribution on ``sys.path``
    that declares it wins.
    """
    global _cache
    if _cache is None or _cache.paths != tuple(sys.path):
        _cache = _scan(sys.path)
    result: dict[str, EntryPointSpec] = {}
    for spec in _cache.groups.get(group, ()):
        result.setdefault(spec.name, spec)
    return list(result.values())


def load_plugins(
    group: str,
    *,
    names: Iterable[str] | None = None,
    on_error: Callable[[PluginError], None] | None = None,
) -> dict[str, Any]:
    """Load the entry points of ``group`` (optionally only ``names``).

    A plugin that fails to import is reported through ``on_error`` (default:
    a warning line on stderr) and skipped; it never stops the tool.
    """
    wanted = None if names is None else set(names)
    loaded: dict[str, Any] = {}
    for spec in iter_entry_points(group):
        if wanted is not None and spec.name not in wanted:
            continue
        try:
            loaded[spec.name] = spec.load()
        except Exception as exc:  # noqa: BLE001 - any plugin failure is reported, not raised
            error = PluginError(group, spec.name, spec.value, spec.distribution,
                                f'{type(exc).__name__}: {exc}')
            if on_error is None:
                print(error, file=sys.stderr)
            else:
                on_error(error)
    return loaded
