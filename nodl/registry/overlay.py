"""Definition folders (overlays): definitions for packages you do not own.

A definitions folder is laid out by package::

    DIR/<package>/<executable>.nodl.yaml           a node definition
    DIR/<package>/interfaces/<name>.nodl.yaml      nodl://<package>/<name>
    DIR/<package>/nodes.yaml                       what a registration records (optional):
                                                   {<executable or key>: {plugin: pkg::Class,
                                                                          node_name: name}}

(``.nodl.yml`` and ``.nodl.json`` are read too.)  The layout is checked when a
folder is read (:func:`read_folder`): a file in the wrong place, a folder that
is not a package name, a ``nodes.yaml`` that is not a table of registrations,
or a plugin of another package than its folder's is one located diagnostic
each (codes NODL240 to 247); files starting with ``.`` and ``README``/``LICENSE``
files are left alone.

:class:`Definitions` is the ordered list of folders of one run (the first
that has a definition wins).  :func:`using` makes it the one every look-up of
the run consults before the ament index (:mod:`nodl.registry.registrations`,
:mod:`nodl.registry.node_info`, ``nodl://`` references); :func:`active`
is what is in force.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from contextvars import ContextVar
from typing import NamedTuple

import yaml

from nodl.diagnostics import Diagnostic, Severity
from nodl.files import describe_os_error
from nodl.frontends import yaml_events
from nodl.frontends.source import decode, read_limited
from nodl.frontends.yaml_events import _COLUMN_BITS, _COLUMN_MASK

__all__ = ['DEFINITION_SUFFIXES', 'NODES_FILE', 'INTERFACES_FOLDER', 'OverlayEntry',
           'DefinitionFolder', 'Definitions', 'read_folder', 'read_folders', 'using', 'active']

#: The endings of a definition's file name in a definitions folder.
DEFINITION_SUFFIXES = ('.nodl.yaml', '.nodl.yml', '.nodl.json')
#: The file of a package folder that records what registrations would (plugin, node name).
NODES_FILE = 'nodes.yaml'
#: The sub-folder of a package folder that holds its interface definitions.
INTERFACES_FOLDER = 'interfaces'
#: A package name (REP 144: lower case letters, digits and '_', starting with a letter).
_PACKAGE = re.compile(r'[a-z][a-z0-9_]*')
_NAME = re.compile(r'[A-Za-z0-9_][A-Za-z0-9_.-]*')
_PLUGIN = re.compile(r'[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)+')
_NODE_NAME = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')
#: Files a definitions folder may hold anywhere without being definitions.
_LEFT_ALONE = re.compile(r'(README|LICEN[CS]E|COPYING)([._-].*)?', re.I)
_LAYOUT = ('DIR/<package>/<executable>.nodl.yaml, DIR/<package>/interfaces/<name>.nodl.yaml '
           'or DIR/<package>/nodes.yaml')


class OverlayEntry(NamedTuple):
    """One definition of a definitions folder."""

    package: str
    #: The executable (or registration key) of a node, the name of an interface.
    name: str
    #: ``node`` or ``interface``.
    kind: str
    file: str


class _Info(NamedTuple):
    plugin: str | None
    node_name: str | None


def _stem(file_name: str) -> str | None:
    for suffix in DEFINITION_SUFFIXES:
        if file_name.endswith(suffix):
            return file_name[:-len(suffix)]
    return None


class DefinitionFolder:
    """One definitions folder, read and its layout checked (see the module docstring)."""

    def __init__(self, root: str, given_by: str = '--definitions') -> None:
        #: The folder as given.
        self.root = root
        #: Where it was given: ``--definitions``, ``NODL_PATH`` or a configuration file.
        self.given_by = given_by
        #: ``(package, executable) -> file``.
        self.nodes: dict[tuple[str, str], str] = {}
        #: ``(package, name) -> file`` (``nodl://<package>/<name>``).
        self.interfaces: dict[tuple[str, str], str] = {}
        #: ``(package, key) -> (plugin, node_name)`` from the packages' ``nodes.yaml``.
        self.info: dict[tuple[str, str], _Info] = {}
        #: What is wrong with the layout (errors) and what looks amiss (warnings).
        self.diagnostics: list[Diagnostic] = []

    @property
    def label(self) -> str:
        """``overlay DIR``: where a definition of this folder comes from, for outputs."""
        return f'overlay {self.root}'

    def entries(self) -> list[OverlayEntry]:
        """Every definition of the folder, sorted."""
        found = [OverlayEntry(p, n, 'node', f) for (p, n), f in self.nodes.items()]
        found += [OverlayEntry(p, n, 'interface', f) for (p, n), f in self.interfaces.items()]
        return sorted(found)

    def _error(self, file: str, message: str, code: str, line: int = 0, column: int = 0,
               severity: Severity = Severity.ERROR) -> None:
        self.diagnostics.append(Diagnostic(severity, message, (), file, line, column, code=code))

    def __repr__(self) -> str:
        return (f'DefinitionFolder({self.root!r}, {len(self.nodes)} nodes, '
                f'{len(self.interfaces)} interfaces, {len(self.diagnostics)} diagnostics)')


def _list(folder: str) -> list[os.DirEntry[str]]:
    with os.scandir(folder) as entries:
        return sorted((e for e in entries if not e.name.startswith('.')), key=lambda e: e.name)


def _misplaced(found: DefinitionFolder, path: str, why: str) -> None:
    found._error(path, f'{why}; a definitions folder holds only {_LAYOUT} (move or remove it)',
                 'NODL240')


def read_folder(root: str, given_by: str = '--definitions') -> DefinitionFolder:
    """Read the definitions folder ``root`` and check its layout (never raises: a folder
    that cannot be read is a NODL246 diagnostic)."""
    found = DefinitionFolder(root, given_by)
    if not os.path.isdir(root):
        why = 'no such folder' if not os.path.exists(root) else 'not a folder'
        found._error(root, f'the definitions folder given by {given_by} cannot be used: {why}',
                     'NODL246')
        return found
    try:
        packages = _list(root)
    except OSError as exc:
        found._error(root, f'cannot read the definitions folder: {describe_os_error(exc)}', 'NODL246')
        return found
    for entry in packages:
        path = os.path.join(root, entry.name)
        if _LEFT_ALONE.fullmatch(entry.name) and not entry.is_dir():
            continue
        if not entry.is_dir():
            what = 'a definition' if _stem(entry.name) is not None else 'a file'
            _misplaced(found, path, f'{what} at the top of the definitions folder, outside any '
                       'package folder (put it in DIR/<package>/)')
            continue
        if not _PACKAGE.fullmatch(entry.name):
            found._error(path, f"'{entry.name}' is not a package name (lower case letters, digits "
                         "and '_', starting with a letter), so this folder serves no package; name "
                         'it after the package whose definitions it holds', 'NODL243')
            continue
        _read_package(found, entry.name, path)
    return found


def _read_package(found: DefinitionFolder, package: str, folder: str) -> None:
    try:
        entries = _list(folder)
    except OSError as exc:
        found._error(folder, f'cannot read the package folder: {describe_os_error(exc)}', 'NODL246')
        return
    stems: dict[str, str] = {}
    nodes_file = None
    for entry in entries:
        path = os.path.join(folder, entry.name)
        if _LEFT_ALONE.fullmatch(entry.name) and not entry.is_dir():
            continue
        if entry.is_dir():
            if entry.name == INTERFACES_FOLDER:
                _read_interfaces(found, package, path)
            else:
                _misplaced(found, path, f"a folder '{entry.name}' in the package folder (only "
                           f"'{INTERFACES_FOLDER}/' may be there)")
            continue
        if entry.name == NODES_FILE:  # read after the definitions, which its keys must name
            nodes_file = path
            continue
        stem = _stem(entry.name)
        if stem is None or not _NAME.fullmatch(stem):
            _misplaced(found, path, 'not a definition (<executable>.nodl.yaml)')
            continue
        if stem in stems:
            found._error(path, f"a second definition of '{package} {stem}' (the other is "
                         f'{stems[stem]}); keep one', 'NODL247')
            continue
        stems[stem] = path
        found.nodes[package, stem] = path
    if nodes_file is not None:
        _read_nodes_file(found, package, nodes_file)


def _read_interfaces(found: DefinitionFolder, package: str, folder: str) -> None:
    try:
        entries = _list(folder)
    except OSError as exc:
        found._error(folder, f'cannot read the interfaces folder: {describe_os_error(exc)}',
                     'NODL246')
        return
    for entry in entries:
        path = os.path.join(folder, entry.name)
        if _LEFT_ALONE.fullmatch(entry.name) and not entry.is_dir():
            continue
        stem = _stem(entry.name) if not entry.is_dir() else None
        if stem is None or not _NAME.fullmatch(stem):
            _misplaced(found, path, 'not an interface definition (interfaces/<name>.nodl.yaml) '
                       'in the interfaces folder')
            continue
        if (package, stem) in found.interfaces:
            found._error(path, f"a second definition of 'nodl://{package}/{stem}' (the other is "
                         f'{found.interfaces[package, stem]}); keep one', 'NODL247')
            continue
        found.interfaces[package, stem] = path


def _read_nodes_file(found: DefinitionFolder, package: str, path: str) -> None:
    """``nodes.yaml``: ``{key: {plugin: pkg::Class, node_name: name}}``, each value checked
    at its line and column."""
    try:
        text, problem = decode(read_limited(path), path)
    except OSError as exc:
        found._error(path, f'cannot read the file: {describe_os_error(exc)}', 'NODL246')
        return
    if text is None:
        assert problem is not None
        found.diagnostics.append(problem)
        return
    spans: dict[object, object] = {}
    try:
        data, _ = yaml_events.read(text, spans)
    except yaml_events.Stop as stop:
        line, column = _mark(stop.mark)
        found._error(path, f'{stop.message}', 'NODL244', line, column)
        return
    except yaml.YAMLError as exc:
        line, column = _mark(getattr(exc, 'problem_mark', None))
        why = getattr(exc, 'problem', None) or 'not YAML'
        found._error(path, f'not valid YAML: {why}', 'NODL244', line, column)
        return

    def at(*keys: object, anchor: str = 'value') -> tuple[int, int]:
        return yaml_events.span_position(spans, keys, anchor) or (1, 1)  # type: ignore[arg-type]

    if data is None:
        return
    if not isinstance(data, dict):
        found._error(path, f'{NODES_FILE} must be a mapping {{<executable or key>: {{plugin: '
                     '<pkg::Class>, node_name: <name>}}}}', 'NODL244', *at())
        return
    for key, value in data.items():
        if not isinstance(key, str) or not _NAME.fullmatch(key):
            found._error(path, f'{key!r} is not an executable or registration key', 'NODL244',
                         *at(key, anchor='key'))
            continue
        if not isinstance(value, dict):
            found._error(path, f"'{key}' must map to {{plugin: <pkg::Class>, node_name: <name>}}",
                         'NODL244', *at(key))
            continue
        plugin = node_name = None
        for name, item in value.items():
            where = at(key, name)
            if name == 'plugin':
                if not isinstance(item, str) or not _PLUGIN.fullmatch(item):
                    found._error(path, f"'{key}'.plugin: {item!r} is not a plugin class name "
                                 '(expected <package>::<Class>)', 'NODL244', *where)
                    continue
                owner = item.split('::', 1)[0]
                if owner != package:
                    found._error(path, f"'{key}'.plugin '{item}' is a class of package '{owner}', "
                                 f"but this is the folder of package '{package}': put it in "
                                 f"{owner}/{NODES_FILE} (with its definition), or correct the "
                                 'class', 'NODL242', *where)
                    continue
                plugin = item
            elif name == 'node_name':
                if not isinstance(item, str) or not _NODE_NAME.fullmatch(item):
                    found._error(path, f"'{key}'.node_name: {item!r} is not a node name (letters, "
                                 "digits and '_', not starting with a digit)", 'NODL244', *where)
                    continue
                node_name = item
            else:
                found._error(path, f"'{key}': unknown key '{name}'; expected plugin or node_name",
                             'NODL244', *at(key, name, anchor='key'))
        found.info[package, key] = _Info(plugin, node_name)
    for (pkg, key) in list(found.info):
        if pkg == package and (pkg, key) not in found.nodes:
            line, column = at(key, anchor='key')
            found._error(path, f"'{key}' has no definition in this folder: add "
                         f'{package}/{key}.nodl.yaml, or remove the entry', 'NODL245', line, column,
                         Severity.WARNING)


def _mark(mark: object) -> tuple[int, int]:
    if mark is None:
        return 0, 0
    if isinstance(mark, int):  # yaml_events' packed positions
        return (mark >> _COLUMN_BITS) + 1, (mark & _COLUMN_MASK) + 1
    return getattr(mark, 'line', -1) + 1, getattr(mark, 'column', -1) + 1


class Definitions:
    """The definitions folders of one run, in order of precedence (the first that has a
    definition wins, before the ament index)."""

    def __init__(self, folders: Sequence[DefinitionFolder] = ()) -> None:
        #: The folders, first wins.
        self.folders: tuple[DefinitionFolder, ...] = tuple(folders)

    def __bool__(self) -> bool:
        return bool(self.folders)

    @property
    def diagnostics(self) -> list[Diagnostic]:
        """What is wrong with the folders' layouts."""
        return [d for folder in self.folders for d in folder.diagnostics]

    def find_node(self, package: str, key: str) -> tuple[str, DefinitionFolder] | None:
        """``(file, folder)`` of the first node definition of ``package``'s ``key``, or None."""
        for folder in self.folders:
            file = folder.nodes.get((package, key))
            if file is not None:
                return file, folder
        return None

    def find_interface(self, package: str, name: str) -> tuple[str, DefinitionFolder] | None:
        """``(file, folder)`` of the first interface definition ``nodl://package/name``."""
        for folder in self.folders:
            file = folder.interfaces.get((package, name))
            if file is not None:
                return file, folder
        return None

    def node_info(self, package: str, key: str) -> tuple[str | None, str | None] | None:
        """``(plugin, node_name)`` the first folder that records ``package``'s ``key`` gives."""
        for folder in self.folders:
            info = folder.info.get((package, key))
            if info is not None:
                return info.plugin, info.node_name
        return None

    def find_plugin(self, package: str, plugin: str) -> str | None:
        """The key ``package``'s ``nodes.yaml`` records ``plugin`` for (first folder wins)."""
        for folder in self.folders:
            for (pkg, key), info in folder.info.items():
                if pkg == package and info.plugin == plugin:
                    return key
        return None

    def packages(self) -> set[str]:
        """Every package some folder has a definition of."""
        return {p for folder in self.folders for p, _ in (*folder.nodes, *folder.interfaces)}

    def entries(self, package: str | None = None) -> list[tuple[OverlayEntry, DefinitionFolder]]:
        """Every definition that serves (a definition of a later folder that an earlier one
        shadows is left out), of ``package`` only if given."""
        seen: set[tuple[str, str, str]] = set()
        out: list[tuple[OverlayEntry, DefinitionFolder]] = []
        for folder in self.folders:
            for entry in folder.entries():
                key = (entry.package, entry.name, entry.kind)
                if key in seen or (package is not None and entry.package != package):
                    continue
                seen.add(key)
                out.append((entry, folder))
        return out


def read_folders(roots: Sequence[tuple[str, str]]) -> Definitions:
    """:class:`Definitions` of ``(folder, given_by)`` pairs, in order (a folder given twice is
    read once, at its first place)."""
    seen: set[str] = set()
    folders: list[DefinitionFolder] = []
    for root, given_by in roots:
        key = os.path.realpath(root)
        if key in seen:
            continue
        seen.add(key)
        folders.append(read_folder(root, given_by))
    return Definitions(folders)


_ACTIVE: ContextVar[Definitions | None] = ContextVar('nodl_definitions', default=None)


@contextmanager
def using(definitions: Definitions | None) -> Iterator[None]:
    """Within the block, every look-up of a registered definition (node, interface,
    registration record) consults ``definitions`` before the ament index.  None or an empty
    :class:`Definitions` leaves what is in force unchanged."""
    if not definitions:
        yield
        return
    token = _ACTIVE.set(definitions)
    try:
        yield
    finally:
        _ACTIVE.reset(token)


def active() -> Definitions | None:
    """The definitions folders in force (see :func:`using`), or None."""
    return _ACTIVE.get()
