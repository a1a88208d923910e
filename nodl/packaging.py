"""Registering NoDL definitions from a Python (setuptools) package.

The index layout is the one ``ament_nodl_register_node`` and
``ament_nodl_register_interface`` produce for CMake packages:

* the definition files in ``share/<package>/nodl/``;
* ``share/ament_index/resource_index/nodl_nodes/<package>__<executable>`` and
  ``.../nodl_interfaces/<package>__<name>``, each holding the installed path
  relative to ``share/<package>`` (``nodl/<file>``).

In ``setup.py``::

    from nodl.packaging import nodl_data_files

    setup(
        ...,
        data_files=[
            ('share/ament_index/resource_index/packages', ['resource/my_pkg']),
            ('share/my_pkg', ['package.xml']),
            *nodl_data_files('my_pkg',
                             nodes={'talker': 'nodl/talker.nodl.yaml'},
                             interfaces={'chatter': 'nodl/chatter.nodl.yaml'}),
        ],
    )

The definitions are validated when the package is built (the kind enforced,
mixin references resolved, also ``nodl://<this package>/...``); an invalid
file stops the build with ``FILE:LINE:COL`` diagnostics (:class:`NodlBuildError`;
warnings of valid files go to the ``nodl.packaging`` logger).  The build then
needs this toolkit importable (``pip install --no-build-isolation``, or the
toolkit in ``[build-system] requires``).  Without that, use the plain recipe
in the package authors' guide (ros/nodl_toolkit/doc/guides/package-authors.md,
"Registering from a Python package"), which needs nothing at build time.
"""

from __future__ import annotations

import logging
import os
import posixpath
import re
import shutil
from collections.abc import Mapping, Sequence
from pathlib import Path

from nodl.checking import check_paths, failed
from nodl.composition.resolvers import scheme_of
from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.builtin import INCLUDE
from nodl.loading import check_source
from nodl.registry.node_info import NODE_INFO_RESOURCE, format_node_info
from nodl.reporting import format_text, without_info
from nodl.validation.kinds import Kind
from nodl.vocabulary import INTERFACE_RESOURCE, NODE_RESOURCE, resource_name
from nodl.writing import WriteError, write_file

__all__ = ['nodl_data_files', 'relative_mixins', 'package_dependencies', 'NodlBuildError',
           'NODE_RESOURCE', 'INTERFACE_RESOURCE']

_KEY = re.compile(r'[A-Za-z0-9_][A-Za-z0-9_.-]*')
_INDEX = 'share/ament_index/resource_index'


class NodlBuildError(SystemExit):
    """Raised by :func:`nodl_data_files` when the definitions cannot be registered.

    ``str(error)`` is every problem, one a line: a wrong argument, or the
    diagnostics of the invalid definitions (``FILE:LINE:COL: severity: message
    [CODE]``) followed by ``<package>: invalid NoDL definitions: FILE, ...``;
    :attr:`diagnostics` holds those diagnostics (empty for a wrong argument).

    It is a :class:`SystemExit` on purpose: ``setup.py`` runs the helper while
    the build describes the package, and an exception of this kind is
    setuptools' (and Python's) way to stop it with exactly these lines and
    status 1, where any other exception would print a traceback for what is a
    user's error.  Catch it to handle the failure yourself.
    """

    def __init__(self, message: str, diagnostics: Sequence[Diagnostic] = ()) -> None:
        super().__init__(message)
        #: The diagnostics of the definitions (errors and warnings), in file order.
        self.diagnostics: list[Diagnostic] = list(diagnostics)


def _write(path: str, text: str) -> None:
    """Write an ament index marker atomically (:func:`nodl.writing.write_file`); a
    failure is a :class:`NodlBuildError` naming the file."""
    try:
        write_file(path, text)
    except WriteError as exc:
        raise NodlBuildError(str(exc)) from None


def nodl_data_files(package: str, nodes: Mapping[str, str] | None = None,
                    interfaces: Mapping[str, str] | None = None, *,
                    validate: bool = True, staging_dir: str = os.path.join('build', 'nodl_index'),
                    plugins: Mapping[str, str] | None = None,
                    node_names: Mapping[str, str] | None = None,
                    ) -> list[tuple[str, list[str]]]:
    """``data_files`` entries that install and register NoDL definitions.

    :param package: the Python/ROS package name
    :param nodes: executable -> node definition file (relative to setup.py)
    :param interfaces: name -> interface definition file, used as ``nodl://<package>/<name>``
    :param validate: validate every file now and stop the build if one is invalid
    :param staging_dir: where the index marker files are written (relative to setup.py)
    :param plugins: executable -> the composable node class (``pkg::ClassName``) its
        definition describes (``nodl analyse`` matches ``ComposableNode(plugin=...)``)
    :param node_names: executable -> the name it gives its node when launched without one
    :raises NodlBuildError: a wrong argument, a file that is missing, or (``validate``) an
        invalid definition: the message lists every problem
    """
    nodes = dict(nodes or {})
    interfaces = dict(interfaces or {})
    problems: list[str] = []
    installed: dict[str, str] = {}
    for key, file in list(nodes.items()) + list(interfaces.items()):
        if not _KEY.fullmatch(key):
            problems.append(f"nodl_data_files: '{key}' is not a valid name (letters, digits, '_', '.', '-')")
        if not os.path.isfile(file):
            problems.append(f"nodl_data_files: {file}: no such file (registered as '{key}')")
        name = os.path.basename(file)
        if installed.setdefault(name, file) != file:
            problems.append(f'nodl_data_files: {installed[name]} and {file} would both be installed '
                            f'as share/{package}/nodl/{name}; rename one')
    if problems:
        raise NodlBuildError('\n'.join(problems))

    entries: dict[str, list[str]] = {}
    for resource_type, registry in ((NODE_RESOURCE, nodes), (INTERFACE_RESOURCE, interfaces)):
        folder = os.path.join(staging_dir, 'share', 'ament_index', 'resource_index', resource_type)
        os.makedirs(folder, exist_ok=True)
        for key, file in registry.items():
            marker = os.path.join(folder, resource_name(package, key))
            _write(marker, f'nodl/{os.path.basename(file)}')
            entries.setdefault(f'{_INDEX}/{resource_type}', []).append(marker)
    entries[f'share/{package}/nodl'] = sorted(set(installed.values()))
    _node_info(package, nodes, dict(plugins or {}), dict(node_names or {}), staging_dir, entries)
    # What the build validates is what gets installed: the node files' relative mixins,
    # at the same place relative to the installed node file.
    destinations = {f'share/{package}/nodl/{name}': file for name, file in installed.items()}
    for file in dict.fromkeys(nodes.values()):
        for reference in relative_mixins(file):
            source = os.path.normpath(os.path.join(os.path.dirname(file), reference))
            target = posixpath.normpath(f'share/{package}/nodl/{reference}')
            if not target.startswith(f'share/{package}/'):
                problems.append(f"nodl_data_files: {file}: mixin '{reference}' would be installed "
                                f'outside share/{package}; keep relative mixins in or below '
                                f'the folder above the node file, or register the mixin as an '
                                f'interface and use nodl://{package}/<name>')
                continue
            if not os.path.isfile(source):
                continue  # validation reports it with its position
            other = destinations.setdefault(target, source)
            if os.path.normpath(other) != source:
                problems.append(f'nodl_data_files: {other} and {source} would both be installed '
                                f'as {target}; rename one')
                continue
            if source not in entries.setdefault(posixpath.dirname(target), []):
                entries[posixpath.dirname(target)].append(source)
    if problems:
        raise NodlBuildError('\n'.join(problems))
    if validate:
        _validate(package, nodes, interfaces, staging_dir)
    return sorted(entries.items())


def _validate(package: str, nodes: Mapping[str, str], interfaces: Mapping[str, str],
              staging_dir: str) -> None:
    # A staging index lets nodl://<package>/<name> resolve before installation: its
    # markers point at the source files by absolute path.
    stage = os.path.abspath(os.path.join(staging_dir, 'stage'))
    # Rebuilt every time: an entry left over from an earlier build (an interface since
    # removed from setup.py) would let a reference to it pass here and fail once installed.
    shutil.rmtree(stage, ignore_errors=True)
    folder = os.path.join(stage, 'share', 'ament_index', 'resource_index', INTERFACE_RESOURCE)
    os.makedirs(folder, exist_ok=True)
    for key, file in interfaces.items():
        _write(os.path.join(folder, resource_name(package, key)), os.path.abspath(file))
    packages = os.path.join(stage, 'share', 'ament_index', 'resource_index', 'packages')
    os.makedirs(packages, exist_ok=True)
    _write(os.path.join(packages, package), '')

    previous = os.environ.get('AMENT_PREFIX_PATH')
    os.environ['AMENT_PREFIX_PATH'] = os.pathsep.join(p for p in (stage, previous) if p)
    try:
        failures = []
        shown: list[Diagnostic] = []
        for kind, registry in ((Kind.INTERFACE, interfaces), (Kind.NODE, nodes)):
            # one file may serve several keys: check (and report) it once
            for result in check_paths(list(dict.fromkeys(registry.values())), kind, resolve=True):
                shown += without_info(result.diagnostics)
                if result.problem:
                    shown.append(Diagnostic(Severity.ERROR, result.problem, file=result.path))
                if result.problem or failed(result, strict=False):
                    failures.append(result.path)
    finally:
        if previous is None:
            del os.environ['AMENT_PREFIX_PATH']
        else:
            os.environ['AMENT_PREFIX_PATH'] = previous
    if failures:
        raise NodlBuildError(f'{format_text(shown)}{package}: invalid NoDL definitions: '
                             f'{", ".join(failures)}', shown)
    if shown:  # warnings only: the build goes on, and whoever runs it decides what is shown
        logging.getLogger(__name__).warning('%s', format_text(shown).rstrip('\n'))


def relative_mixins(node_file: str | os.PathLike[str]) -> list[str]:
    """The mixins of a node definition that are files of its own package.

    Each is the reference as written, without ``file://``, normalised, with ``/``
    separators: a path relative to the node file's folder. An installed copy of
    the node file resolves them only if they are installed at the same place
    relative to it, which ``nodl_data_files`` and ``ament_nodl_register_node`` do.
    In the order written, each once. A file that cannot be read or parsed, or
    that has no mixins, has none (validation says what is wrong with it).
    A mixin in the include dialect includes others in turn (``local://``
    relative to itself): those are listed too, after it, relative to the
    node file's folder.
    """
    found: list[str] = []
    _relative_mixins(os.fspath(node_file), '', found, set())
    return found


def package_dependencies(node_file: str | os.PathLike[str]) -> tuple[list[str], list[Diagnostic]]:
    """``nodl deps``: the files of its own package a node definition needs
    (:func:`relative_mixins`), and what is wrong (coded diagnostics, errors):

    * the file is not a valid node definition (its errors, as ``nodl validate`` gives them):
      then no path is listed, since none can be trusted;
    * a mixin leads outside the package (above the folder holding the nearest
      ``package.xml``, or the node file's folder without one): NODL532, and it is not listed
      (an installed copy of the node file cannot reach it).

    I/O errors such as a missing file propagate as :class:`OSError`.
    """
    name = os.fspath(node_file)
    report = check_source(Path(name), kind=Kind.NODE)
    errors = report.errors
    if errors:
        return [], errors
    folder = os.path.dirname(os.path.abspath(name))
    root = folder
    while not os.path.isfile(os.path.join(root, 'package.xml')):
        parent = os.path.dirname(root)
        if parent == root:
            root = folder  # no package.xml above it: the node file's folder is all there is
            break
        root = parent
    inside = os.path.join(os.path.realpath(root), '')
    listed: list[str] = []
    problems: list[Diagnostic] = []
    for path in relative_mixins(name):
        target = os.path.realpath(os.path.join(folder, path))
        if (target + os.sep).startswith(inside):
            listed.append(path)
            continue
        problems.append(Diagnostic(
            Severity.ERROR, f"the mixin '{path}' leads outside the package ({root}): an "
            'installed copy of the node file cannot reach it; move it into the package, or '
            'register it in the package it belongs to and refer to it as nodl://PACKAGE/...',
            (), name, code='NODL532'))
    return listed, problems


def _relative_mixins(file: str, prefix: str, found: list[str], visited: set[str]) -> None:
    """Add the relative mixins of ``file`` (whose folder is ``prefix`` from the node's) to ``found``."""
    visited.add(os.path.realpath(file))
    try:
        report = check_source(Path(file))
    except OSError:
        return
    data = report.data
    mixins = data.get('mixins') if isinstance(data, dict) else None
    for mixin in mixins if isinstance(mixins, list) else ():
        if not isinstance(mixin, str) or scheme_of(mixin) != 'file':
            continue
        path = mixin[len('file://'):] if mixin.startswith('file://') else mixin
        if not path or os.path.isabs(path) or posixpath.isabs(path):
            continue
        normal = posixpath.normpath(posixpath.join(prefix, path.replace(os.sep, '/')))
        if normal not in found:
            found.append(normal)
        target = os.path.join(os.path.dirname(file), path)
        if os.path.realpath(target) not in visited and os.path.isfile(target):
            # Only the include dialect nests; a cycle is the validator's to report.
            try:
                nested = check_source(Path(target)).dialect == INCLUDE
            except OSError:
                nested = False
            if nested:
                _relative_mixins(target, posixpath.dirname(normal), found, visited)


def _node_info(package: str, nodes: Mapping[str, str], plugins: dict[str, str],
               node_names: dict[str, str], staging_dir: str,
               entries: dict[str, list[str]]) -> None:
    """Write the ``nodl_node_info`` markers (plugin, node name) and add them to ``entries``."""
    problems = [f"nodl_data_files: {what} names '{key}', which is not in nodes"
                for what, given in (('plugins', plugins), ('node_names', node_names))
                for key in given if key not in nodes]
    folder = os.path.join(staging_dir, 'share', 'ament_index', 'resource_index', NODE_INFO_RESOURCE)
    for key in sorted(set(plugins) | set(node_names)):
        try:
            content = format_node_info(plugins.get(key), node_names.get(key))
        except ValueError as exc:
            problems.append(f'nodl_data_files: {key}: {exc}')
            continue
        os.makedirs(folder, exist_ok=True)
        marker = os.path.join(folder, resource_name(package, key))
        _write(marker, content)
        entries.setdefault(f'{_INDEX}/{NODE_INFO_RESOURCE}', []).append(marker)
    if problems:
        raise NodlBuildError('\n'.join(problems))
