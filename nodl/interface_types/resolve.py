"""Where interface types are defined: the ament index, and packages' source folders.

An installed package lists its interface files in the index resource
``rosidl_interfaces/<package>`` (one path per line, relative to
``<prefix>/share/<package>``: ``msg/String.idl``, ``msg/String.msg``...).  The
first prefix of ``AMENT_PREFIX_PATH`` that lists a package wins, as in
ament_index_python.  A package's source folder (``--package DIR``) is read
from its ``msg/``, ``srv/`` and ``action/`` folders, and shadows an installed
package of the same name: its own types resolve before it is installed.

Nothing here imports a ROS package.  One :class:`InterfaceIndex` is a
snapshot: every folder is listed once per index, so one run checking a
hundred definitions reads the index once (see :func:`interface_index`).
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any, NamedTuple

from nodl.ament_index import in_snapshot, prefix_paths, remembered
from nodl.interface_types.manifest import read_manifest
from nodl.wording import close_matches

__all__ = ['TypeName', 'InterfacePackage', 'InterfaceIndex', 'Resolution', 'interface_index',
           'NAMESPACES', 'INTERFACE_SUFFIXES', 'parse_type_name']

#: The interface namespaces, each with the file suffix of its ROS 2 interface files.
NAMESPACES: dict[str, str] = {'msg': '.msg', 'srv': '.srv', 'action': '.action'}
#: The suffixes of the files that define an interface (``.idl`` is preferred when both exist).
INTERFACE_SUFFIXES = ('.idl', '.msg', '.srv', '.action')
_WORDS = {'msg': 'a message', 'srv': 'a service', 'action': 'an action'}


class TypeName(NamedTuple):
    """A full interface type name: ``std_msgs/msg/String``."""

    package: str
    namespace: str
    name: str

    def __str__(self) -> str:
        """``package/namespace/Name``."""
        return f'{self.package}/{self.namespace}/{self.name}'


def parse_type_name(text: str) -> TypeName:
    """``'std_msgs/msg/String'`` -> :class:`TypeName`; ValueError unless it has three parts."""
    parts = text.split('/')
    if len(parts) != 3 or not all(parts) or parts[1] not in NAMESPACES:
        raise ValueError(f"'{text}' is not a full interface type name (package/msg|srv|action/Type)")
    return TypeName(parts[0], parts[1], parts[2])


class InterfacePackage:
    """One package's interface types and the folder their files are relative to."""

    def __init__(self, name: str, share: str, files: Iterable[str], origin: str) -> None:
        #: The package name.
        self.name = name
        #: ``<prefix>/share/<name>`` for an installed package; the package folder for a source one.
        self.share = share
        #: ``installed`` (found in the ament index) or ``source`` (a package folder).
        self.origin = origin
        #: ``(namespace, Name)`` -> the defining files, relative to :attr:`share`, ``.idl`` first.
        self.types: dict[tuple[str, str], list[str]] = {}
        for relative in files:
            folder, _, base = relative.strip().partition('/')
            stem, suffix = os.path.splitext(base)
            if folder in NAMESPACES and suffix in INTERFACE_SUFFIXES and stem and '/' not in base:
                if suffix != '.idl' and suffix != NAMESPACES[folder]:
                    continue  # a .srv file in msg/ is not a message
                self.types.setdefault((folder, stem), []).append(relative.strip())
        for found in self.types.values():
            found.sort(key=lambda f: INTERFACE_SUFFIXES.index(os.path.splitext(f)[1]))

    def names(self, namespace: str | None = None) -> list[str]:
        """The full names of its types (of one namespace, if given), sorted."""
        return sorted(f'{self.name}/{ns}/{name}' for ns, name in self.types
                      if namespace is None or ns == namespace)

    def file(self, namespace: str, name: str) -> str | None:
        """The absolute path of the file that best defines a type (``.idl`` first), or None."""
        found = self.types.get((namespace, name))
        return os.path.join(self.share, found[0]) if found else None

    def __repr__(self) -> str:
        return f'<InterfacePackage {self.name} ({self.origin}) {len(self.types)} types>'


class Resolution(NamedTuple):
    """What a type name written in a definition resolves to.

    ``status`` is one of:

    * ``ok``: the full name is defined;
    * ``short``: ``pkg/Type`` written, resolved to :attr:`type` (the namespace added);
    * ``unknown_package``: no package of that name is installed (nor given as source);
    * ``no_interfaces``: the package is installed but defines no interface types;
    * ``unknown_type``: the package defines no such type (:attr:`suggestions` are close names);
    * ``wrong_kind``: the type exists in another namespace (:attr:`type` is that one).
    """

    status: str
    type: TypeName | None
    suggestions: tuple[str, ...] = ()
    package: InterfacePackage | None = None

    @property
    def found(self) -> bool:
        """True when the name (possibly short) names a defined type of the wanted kind."""
        return self.status in ('ok', 'short')


class InterfaceIndex:
    """The interface types of one environment: the ament prefixes and source package folders.

    ``prefixes`` default to ``AMENT_PREFIX_PATH``; ``sources`` are package folders
    (with a ``package.xml``) whose own types shadow installed ones.  Packages are
    read on first use and kept: an index is a snapshot.
    """

    def __init__(self, prefixes: list[str] | None = None, sources: Iterable[str] = ()) -> None:
        self.prefixes = list(prefixes) if prefixes is not None else prefix_paths()
        self._packages: dict[str, InterfacePackage | None] = {}
        self._listing: dict[str, frozenset[str]] = {}
        self._all: dict[str, str] | None = None
        #: What has been read and built from this index's files (parsed IDL, trees, hashes).
        self.cache: dict[Any, Any] = {}
        for folder in sources:
            self.add_source(folder)

    # -- packages ---------------------------------------------------------------------------

    def _listed(self, prefix: str, resource_type: str) -> frozenset[str]:
        key = os.path.join(prefix, 'share', 'ament_index', 'resource_index', resource_type)
        found = self._listing.get(key)
        if found is None:
            try:
                with os.scandir(key) as entries:
                    found = frozenset(e.name for e in entries
                                      if not e.name.startswith('.') and e.is_file())
            except OSError:
                found = frozenset()
            self._listing[key] = found
        return found

    def add_source(self, folder: str, name: str | None = None) -> InterfacePackage:
        """Read a package folder's ``msg/``, ``srv/`` and ``action/`` files; it shadows an
        installed package of the same name.  ``name`` defaults to ``package.xml``'s
        ``<name>`` (else the folder's name)."""
        if name is None:
            manifest = read_manifest(folder)
            name = manifest.name or os.path.basename(os.path.abspath(folder))
        files: list[str] = []
        for namespace in NAMESPACES:
            try:
                with os.scandir(os.path.join(folder, namespace)) as entries:
                    files += [f'{namespace}/{e.name}' for e in entries if e.is_file()]
            except OSError:
                continue
        package = InterfacePackage(name, os.path.abspath(folder), files, 'source')
        self._packages[name] = package
        self._all = None
        return package

    def package(self, name: str) -> InterfacePackage | None:
        """The package's interface types (source first, then the first prefix listing it)."""
        if name in self._packages:
            return self._packages[name]
        found: InterfacePackage | None = None
        if '/' not in name and name not in ('', '.', '..'):
            for prefix in self.prefixes:
                if name in self._listed(prefix, 'rosidl_interfaces'):
                    path = os.path.join(prefix, 'share', 'ament_index', 'resource_index',
                                        'rosidl_interfaces', name)
                    try:
                        with open(path, encoding='utf-8') as handle:
                            lines = handle.read().splitlines()
                    except (OSError, UnicodeDecodeError):
                        lines = []
                    found = InterfacePackage(name, os.path.join(prefix, 'share', name), lines,
                                             'installed')
                    break
        self._packages[name] = found
        return found

    def installed(self, name: str) -> bool:
        """True if the ament index lists ``name`` as a package (interfaces or not)."""
        if self._packages.get(name) is not None:
            return True
        return any(name in self._listed(prefix, 'packages') for prefix in self.prefixes)

    def interface_packages(self) -> list[str]:
        """Every package that defines interface types, sorted."""
        if self._all is None:
            found: dict[str, str] = {}
            for prefix in self.prefixes:
                for name in self._listed(prefix, 'rosidl_interfaces'):
                    found.setdefault(name, prefix)
            for name, package in self._packages.items():
                if package is not None and package.origin == 'source':
                    found[name] = package.share
            self._all = found
        return sorted(self._all)

    def prefix_of(self, package: str) -> str | None:
        """The prefix (or source folder) a package's interfaces come from, or None."""
        found = self.package(package)
        if found is None:
            return None
        return found.share if found.origin == 'source' else os.path.dirname(os.path.dirname(found.share))

    # -- names ------------------------------------------------------------------------------

    def file(self, name: TypeName | str) -> str | None:
        """The absolute path of the file that defines a full type name, or None."""
        if isinstance(name, str):
            name = parse_type_name(name)
        package = self.package(name.package)
        return package.file(name.namespace, name.name) if package is not None else None

    def resolve(self, text: str, namespace: str) -> Resolution:
        """Resolve ``text`` (``pkg/ns/T`` or the short ``pkg/T``) where ``namespace`` types
        belong (``msg`` for topics, ``srv`` for services, ``action`` for actions).

        A name that is not an interface type name at all (see
        :func:`nodl.validation.types.type_problem`) resolves to ``unknown_type``.
        """
        parts = text.split('/')
        if len(parts) not in (2, 3) or not all(parts):
            return Resolution('unknown_type', None)
        package_name, name = parts[0], parts[-1]
        written = parts[1] if len(parts) == 3 else None
        package = self.package(package_name)
        if package is None:
            status = 'no_interfaces' if self.installed(package_name) else 'unknown_package'
            suggestions = () if status == 'no_interfaces' else tuple(
                close_matches(package_name, self.interface_packages(), most=3, cutoff=0.8))
            return Resolution(status, None, suggestions)
        wanted = TypeName(package_name, namespace, name)
        if written in (None, namespace) and (namespace, name) in package.types:
            return Resolution('ok' if written else 'short', wanted, (), package)
        for other in NAMESPACES:
            if other != namespace and (other, name) in package.types:
                return Resolution('wrong_kind', TypeName(package_name, other, name), (), package)
        candidates = [n for ns, n in package.types if ns == namespace]
        close = close_matches(name, candidates, most=3)
        return Resolution('unknown_type', None,
                          tuple(f'{package_name}/{namespace}/{c}' for c in close), package)

    def describe_kind(self, namespace: str) -> str:
        """``a message`` / ``a service`` / ``an action``."""
        return _WORDS[namespace]


def interface_index(sources: Iterable[str] = (), prefixes: list[str] | None = None) -> InterfaceIndex:
    """The index of the current ``AMENT_PREFIX_PATH`` (and source folders), one per run.

    Inside :func:`nodl.ament_index.snapshot` the same index (and its type
    cache) is returned for the same prefixes and sources; outside one, a new one.
    """
    chosen = list(prefixes) if prefixes is not None else prefix_paths()
    folders = tuple(os.path.abspath(s) for s in sources)
    if not in_snapshot():
        return InterfaceIndex(chosen, folders)
    return remembered(('interface_index', tuple(chosen), folders),
                      lambda: InterfaceIndex(chosen, folders))
