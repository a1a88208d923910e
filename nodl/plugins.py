"""Extension points: discovery, versions, priorities, a blocklist and fault-tolerant loading.

Every extension point of the toolkit is an entry point group, listed once in
:data:`EXTENSION_POINTS` with the version of its interface and its base
class.  The built-in implementations are registered in ``pyproject.toml``
exactly as a third-party package registers its own.

An extension is a class (usually a subclass of the group's base class, itself
a subclass of :class:`ExtensionPoint`) with

* ``EXTENSION_POINT_VERSION``: the ``MAJOR.MINOR`` version of the interface it
  was written for.  It loads if the major version is the toolkit's and the
  minor version is not newer; otherwise it is reported and skipped;
* ``PRIORITY``: extensions of a group are ordered by descending priority
  (then by name).

A plugin that cannot be imported, declares an incompatible version or fails
to instantiate is reported and skipped: it never stops the tool.  The library
never prints: a loader hands each :class:`PluginError` to its ``on_error``
callback or, without one, keeps it for :func:`take_plugin_errors`, which the
``nodl`` command calls to write each as one warning line on standard error.
``NODL_EXTENSION_BLOCKLIST`` names extensions to leave out, separated by
commas (or the path separator): ``nodl.verbs.describe`` leaves out one
extension, ``nodl.resolvers`` a whole group.

Discovery finds what :mod:`importlib.metadata` finds (the first distribution
of a name on ``sys.path`` wins; a test keeps the two in agreement) and caches
it for the process.  For directories on ``sys.path`` it reads the
``entry_points.txt`` metadata files directly: ``importlib.metadata`` builds a
distribution object for every installed package and costs about 100 ms in an
environment holding the ROS 2 wheels, which ``nodl`` start-up cannot afford.
Other entries (zip files) are asked through :mod:`importlib.metadata` itself.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import re
import sys
from collections import namedtuple
from collections.abc import Callable, Iterable
from typing import Any

__all__ = [
    'BLOCKLIST_VARIABLE',
    'ExtensionPoint',
    'ExtensionPointSpec',
    'EXTENSION_POINTS',
    'PluginError',
    'EntryPointSpec',
    'satisfies_version',
    'is_blocked',
    'iter_entry_points',
    'load_plugins',
    'instantiate_extensions',
    'take_plugin_errors',
]

#: The environment variable listing extensions (``group.name``) or groups to leave out.
BLOCKLIST_VARIABLE = 'NODL_EXTENSION_BLOCKLIST'


class ExtensionPointSpec(namedtuple('ExtensionPointSpec', ['group', 'version', 'base', 'purpose'])):
    """One extension point: its entry point group, interface version, base class, purpose.

    ``base`` is ``module:Class`` (imported only when asked for), or None for a
    group reserved for extensions to come (its base is :class:`ExtensionPoint`).
    """

    __slots__ = ()

    def base_class(self) -> type:
        """The group's base class."""
        if self.base is None:
            return ExtensionPoint
        cls: type = EntryPointSpec('base', self.base, self.group).load()
        return cls


#: Every extension point of the toolkit, by entry point group.
EXTENSION_POINTS: dict[str, ExtensionPointSpec] = {p.group: p for p in (
    ExtensionPointSpec('nodl.verbs', '1.0', 'nodl.cli.verb:VerbExtension',
                       'verbs of `nodl` and `ros2 nodl`'),
    ExtensionPointSpec('nodl.resolvers', '1.0',
                       'nodl.composition.resolvers:ResolverExtension',
                       'mixin reference resolvers, one per URI scheme (the entry point name)'),
    ExtensionPointSpec('nodl.frontends', '1.0', 'nodl.frontends.frontend:FrontendExtension',
                       'readers of a text as a NoDL document, asked by priority'),
    ExtensionPointSpec('nodl.checks', '1.0', 'nodl.system.checks:CheckExtension',
                       'checks of `nodl analyse` over a launched system'),
    ExtensionPointSpec('nodl.generators', '1.0', 'nodl.generate:GeneratorExtension',
                       'code generators, one per language (the entry point name)'),
    ExtensionPointSpec('nodl.reporters', '1.0', 'nodl.reporting.reporters:ReporterExtension',
                       "output formats of every verb's report (`--format NAME`)"),
)}


class ExtensionPoint:
    """Base class of every extension.

    Subclasses of a group's base class inherit the version the toolkit
    provides; a plugin written for a given version states it by setting
    ``EXTENSION_POINT_VERSION`` itself.  ``EXTENSION_GROUP`` and
    ``EXTENSION_NAME`` are set on each instance when it is loaded.
    """

    #: The ``MAJOR.MINOR`` version of the extension point interface implemented.
    EXTENSION_POINT_VERSION: str = '1.0'
    #: Extensions of a group are ordered by descending priority.
    PRIORITY: int = 100
    #: The entry point group the extension was loaded from.
    EXTENSION_GROUP: str | None = None
    #: The entry point name it was registered under.
    EXTENSION_NAME: str | None = None


def _version(text: object) -> tuple[int, int] | None:
    match = re.fullmatch(r'([0-9]+)\.([0-9]+)(?:\.[0-9]+)?', str(text))
    return (int(match.group(1)), int(match.group(2))) if match else None


def satisfies_version(version: str, caret_range: str) -> bool:
    """True if ``version`` is in ``caret_range`` (``^1.2``: at least 1.2, below 2.0).

    Extensions may call it with the toolkit's version of their extension point,
    raising an exception if it is not satisfied (they are then reported and skipped).
    """
    if not caret_range.startswith('^'):
        raise ValueError(f'{caret_range!r} is not a caret range (^MAJOR.MINOR)')
    have, want = _version(version), _version(caret_range[1:])
    if have is None or want is None:
        raise ValueError(f'cannot compare version {version!r} with {caret_range!r}')
    return have[0] == want[0] and have[1] >= want[1]


def _incompatibility(group: str, obj: object) -> str | None:
    """Why an extension's declared version does not fit the group's, or None."""
    spec = EXTENSION_POINTS.get(group)
    declared = getattr(obj, 'EXTENSION_POINT_VERSION', None)
    if spec is None or declared is None:
        return None  # a group the toolkit does not define, or a plugin that states no version
    wanted = _version(declared)
    if wanted is None:
        return f"EXTENSION_POINT_VERSION {declared!r} is not 'MAJOR.MINOR'"
    if not satisfies_version(spec.version, f'^{wanted[0]}.{wanted[1]}'):
        return (f'it implements version {declared} of the {group} extension point; this toolkit '
                f'provides {spec.version} (the major versions must be equal and the toolkit\'s '
                'minor version at least the plugin\'s)')
    return None


class EntryPointSpec(namedtuple('EntryPointSpec', ['name', 'value', 'group', 'distribution'], defaults=[''])):
    """One entry point as declared by a distribution."""

    __slots__ = ()

    def load(self) -> Any:
        """Import the module and return the named attribute."""
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


# --------------------------------------------------------------------------
# Discovery

_NORMALIZE = re.compile(r'[-_.]+')
_META_SUFFIXES = ('.dist-info', '.egg-info')


class _Scan:
    """What was found on ``sys.path``: each distribution's ``entry_points.txt``, in path order.

    A group's entry points are parsed when it is first asked for, from the texts that name
    it: a command loads a group or two, and the ROS 2 wheels bring about ninety such files
    that declare none of the toolkit's groups.
    """

    def __init__(self, paths: tuple[str, ...]) -> None:
        self.paths = paths
        #: (distribution, text of its entry_points.txt), the first distribution of a name only.
        self.texts: list[tuple[str, str]] = []
        self._groups: dict[str, list[EntryPointSpec]] = {}

    def group(self, group: str) -> list[EntryPointSpec]:
        """The entry points of ``group``, in the order of the distributions."""
        found = self._groups.get(group)
        if found is None:
            found = []
            for distribution, text in self.texts:
                if group in text:
                    found += _parse_entry_points(text, distribution).get(group, ())
            self._groups[group] = found
        return found


#: The process-wide cache: what was found on ``sys.path`` as it was then.
_cache: _Scan | None = None


def _dist_name(meta_dir: str) -> str:
    stem = meta_dir.rsplit('.', 1)[0]
    # "name-version" (dist-info) or "name-version-pyX" / "name" (egg-info)
    name = stem.split('-', 1)[0]
    return _NORMALIZE.sub('-', name).lower()


def _parse_entry_points(text: str, distribution: str) -> dict[str, list[EntryPointSpec]]:
    into: dict[str, list[EntryPointSpec]] = {}
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
    return into


def _scan_archive(entry: str, seen: set[str], into: list[tuple[str, str]]) -> None:
    """Distributions inside a zip file on ``sys.path``, through importlib.metadata."""
    # (imported here, the one import not at the top: importlib.metadata costs the command line
    # ~10 ms of start-up, and zip files holding distributions are rare on sys.path)
    import importlib.metadata

    for dist in importlib.metadata.distributions(path=[entry]):
        name = _NORMALIZE.sub('-', dist.metadata['Name'] or '').lower()
        if not name or name in seen:
            continue
        seen.add(name)
        into.append((name, dist.read_text('entry_points.txt') or ''))


def _scan(paths: Iterable[str]) -> _Scan:
    scan = _Scan(tuple(paths))
    seen: set[str] = set()
    for entry in scan.paths:
        try:
            names = sorted(os.listdir(entry or '.'))
        except OSError:
            if os.path.isfile(entry):
                with contextlib.suppress(Exception):  # an unreadable archive holds no plugins
                    _scan_archive(entry, seen, scan.texts)
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
            scan.texts.append((dist, text))
    return scan


def _blocklist() -> set[str]:
    text = os.environ.get(BLOCKLIST_VARIABLE, '')
    return {item.strip() for item in re.split(f'[,{re.escape(os.pathsep)}]', text) if item.strip()}


def is_blocked(group: str, name: str) -> bool:
    """True if :data:`BLOCKLIST_VARIABLE` leaves out extension ``name`` of ``group`` (or the group)."""
    blocked = _blocklist()
    return group in blocked or f'{group}.{name}' in blocked


def iter_entry_points(group: str, *, include_blocked: bool = False) -> list[EntryPointSpec]:
    """Return the entry points of ``group`` from every installed distribution.

    Within a group a name is unique: the first distribution on ``sys.path``
    that declares it wins.  Blocked extensions are left out unless
    ``include_blocked``.
    """
    global _cache
    if _cache is None or _cache.paths != tuple(sys.path):
        _cache = _scan(sys.path)
    result: dict[str, EntryPointSpec] = {}
    for spec in _cache.group(group):
        result.setdefault(spec.name, spec)
    if include_blocked:
        return list(result.values())
    blocked = _blocklist()
    if group in blocked:
        return []
    return [spec for name, spec in result.items() if f'{group}.{name}' not in blocked]


# --------------------------------------------------------------------------
# Loading

#: Plugin errors reported without an ``on_error`` callback, until :func:`take_plugin_errors`.
_pending: list[PluginError] = []
#: (group, name, error) of every error kept so far: each broken plugin is kept once per process.
_kept: set[tuple[str, str, str]] = set()


def _report(error: PluginError, on_error: Callable[[PluginError], None] | None) -> None:
    if on_error is not None:
        on_error(error)
        return
    key = (error.group, error.name, str(error.error))
    if key not in _kept:
        _kept.add(key)
        _pending.append(error)


def take_plugin_errors() -> list[PluginError]:
    """The plugin errors reported since the last call by loaders given no ``on_error`` callback.

    Each broken plugin appears once per process, however often its group is
    loaded (every composition loads the resolvers).  The library never prints
    them; a program shows them (``nodl`` writes ``str(error)``, one warning
    line, on standard error when the verb ends).
    """
    taken = list(_pending)
    del _pending[:]
    return taken


def _priority(item: tuple[str, Any]) -> tuple[int, str]:
    priority = getattr(item[1], 'PRIORITY', ExtensionPoint.PRIORITY)
    return (-priority if isinstance(priority, int) else -ExtensionPoint.PRIORITY, item[0])


def load_plugins(
    group: str,
    *,
    names: Iterable[str] | None = None,
    on_error: Callable[[PluginError], None] | None = None,
) -> dict[str, Any]:
    """Load the entry points of ``group`` (optionally only ``names``), ordered by priority.

    A plugin that fails to import or declares an incompatible
    ``EXTENSION_POINT_VERSION`` is reported through ``on_error`` (default:
    kept for :func:`take_plugin_errors`) and skipped; it never stops the tool.
    """
    wanted = None if names is None else set(names)
    loaded: dict[str, Any] = {}
    for spec in iter_entry_points(group):
        if wanted is not None and spec.name not in wanted:
            continue
        try:
            obj = spec.load()
            problem = _incompatibility(group, obj)
        except Exception as exc:  # noqa: BLE001 - any plugin failure is reported, not raised
            problem = f'{type(exc).__name__}: {exc}'
        if problem is not None:
            _report(PluginError(group, spec.name, spec.value, spec.distribution, problem), on_error)
            continue
        loaded[spec.name] = obj
    return dict(sorted(loaded.items(), key=_priority))


def instantiate_extensions(
    group: str,
    *,
    names: Iterable[str] | None = None,
    on_error: Callable[[PluginError], None] | None = None,
) -> dict[str, Any]:
    """Load and instantiate the extensions of ``group``, ordered by priority.

    Each instance gets ``EXTENSION_GROUP`` and ``EXTENSION_NAME``.  One whose
    class cannot be loaded or instantiated is reported and skipped.
    """
    specs = {spec.name: spec for spec in iter_entry_points(group)}
    instances: dict[str, Any] = {}
    for name, factory in load_plugins(group, names=names, on_error=on_error).items():
        try:
            instance = factory()
        except Exception as exc:  # noqa: BLE001 - a broken plugin must not break the tool
            spec = specs[name]
            _report(PluginError(group, name, spec.value, spec.distribution,
                                f'{type(exc).__name__}: {exc}'), on_error)
            continue
        try:
            instance.EXTENSION_GROUP = group
            instance.EXTENSION_NAME = name
        except AttributeError:
            pass  # an instance with slots keeps its class attributes
        instances[name] = instance
    return instances
