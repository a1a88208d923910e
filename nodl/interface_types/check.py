"""The interface types a NoDL document names, checked against what is installed.

Each ``type:`` of an endpoint section must name an installed (or, with a
package's source folder, a source) message, service or action type of the
section's kind.  With the package's manifest, each interface package must be
a run-time dependency of it.  Diagnostics are placed at the ``type:`` value.

Names are resolved (the index is read once per run), and the file of each type
a definition names is read, with the files of the types it nests, once per run:
a malformed one is one diagnostic at its line (NODL258), related to every
``type:`` that names it.  An installed type is read from its ``.msg``, ``.srv``
or ``.action`` file with rosidl_adapter's parser (fast: the ``.idl`` beside it
is generated from it); only a type installed as ``.idl`` alone, and the
package's own source types, are parsed as IDL.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from nodl.interface_types.manifest import read_manifest
from nodl.interface_types.tree import (
    InterfaceFileError,
    _adapter_spec,
    _read_text,
    load_type,
)
from nodl.validation.types import type_problem

if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from nodl.interface_types.manifest import Manifest
    from nodl.interface_types.resolve import InterfaceIndex
    from nodl.loading import CheckedSource

from nodl.diagnostics import Diagnostic, DocPath, Severity, format_path
from nodl.vocabulary import SECTIONS

__all__ = ['check_types', 'type_entries', 'manifest_for']

_USERS = {'msg': 'topics carry messages', 'srv': 'services need a service type',
          'action': 'actions need an action type'}


def type_entries(report: CheckedSource) -> Iterator[tuple[DocPath, str, str]]:
    """``(path of the type: value, type text, wanted namespace)`` of every endpoint in a
    node or interface document (a node's ``main``)."""
    data = report.data
    kind = getattr(report.kind, 'value', report.kind)
    prefix: DocPath = ()
    if kind == 'node' and isinstance(data, dict):
        data, prefix = data.get('main'), ('main',)
    if not isinstance(data, dict):
        return
    for section in SECTIONS:
        entries = data.get(section.key)
        if not isinstance(entries, list):
            continue
        for number, entry in enumerate(entries):
            if isinstance(entry, dict) and isinstance(entry.get('type'), str):
                yield prefix + (section.key, number, 'type'), entry['type'], section.namespace


def manifest_for(file: str, package_dir: str | None = None) -> Manifest | None:
    """The manifest a definition is checked against: ``package_dir``'s, or for a registered
    definition (a file under ``<prefix>/share/<package>/`` of an ament prefix) its package's."""
    if package_dir is not None:
        return read_manifest(package_dir)
    folder = os.path.dirname(os.path.abspath(file))
    while True:
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        if os.path.basename(parent) == 'share' and os.path.isfile(
                os.path.join(parent, 'ament_index', 'resource_index', 'packages',
                             os.path.basename(folder))):
            return read_manifest(folder) if os.path.isfile(os.path.join(folder, 'package.xml')) else None
        folder = parent


def check_types(report: CheckedSource, index: InterfaceIndex, manifest: Manifest | None = None, *,
                build: bool = False) -> list[Diagnostic]:
    """Check every endpoint type of ``report`` against ``index``; placed diagnostics.

    ``manifest``: the package the definition belongs to; each interface package (but
    its own) must be a run-time dependency of it.  ``build``: checked while the package
    builds (``ament_nodl``), where a dependency that is declared but not installed is a
    warning (build farms install no exec-only dependency for a build).
    """
    out: list[Diagnostic] = []
    own = manifest.name if manifest is not None and manifest.problem is None else None
    if manifest is not None and manifest.problem is not None:
        out.append(Diagnostic(Severity.ERROR, f'package.xml {manifest.problem}; interface '
                              'dependencies cannot be checked', file=manifest.file, code='NODL259'))
    unreadable: dict[str, tuple[str, Any]] = {}  # interface file -> (type, InterfaceFileError)
    named: dict[str, list[tuple[str, int, int, str]]] = {}
    for path, text, namespace in type_entries(report):
        found = list(_check_one(index, text, namespace, path, manifest, own, build))
        for d in found:
            if isinstance(d, tuple):  # (type, InterfaceFileError): one diagnostic per file
                problem = d[1]
                unreadable.setdefault(problem.file, d)
                where = report.place(Diagnostic(Severity.ERROR, '', path))
                named.setdefault(problem.file, []).append(
                    (where.file, where.line, where.column, f"'{text}' named here, as "
                     f'{format_path(path)}'))
            else:
                out.append(report.place(d))
    for file, (type_name, problem) in unreadable.items():
        first = named[file][0]
        more = len(named[file]) - 1
        by = f'{first[0]}:{first[1]}:{first[2]}' + (f' and {more} more' if more else '')
        out.append(Diagnostic(Severity.ERROR, f"'{type_name}' cannot be read: {problem.message} "
                              f'(named by {by}); fix the file, or reinstall its package', (),
                              file, problem.line, problem.column, code='NODL258',
                              related=named[file]))
    return out


def _check_one(index: InterfaceIndex, text: str, namespace: str, path: DocPath,
               manifest: Manifest | None, own: str | None, build: bool
               ) -> Iterator[Diagnostic | tuple[str, Any]]:
    problem = type_problem(text, namespace)
    if problem is not None and problem[0] is Severity.ERROR:
        return  # not a type name (reported by validation, NODL203/NODL204)
    resolution = index.resolve(text, namespace)
    package = text.split('/')[0]
    declared = manifest is not None and own is not None and package in manifest.depends
    if resolution.status == 'unknown_package':
        if build and declared:
            yield Diagnostic(Severity.WARNING, f"package '{package}' of '{text}' is declared in "
                             'package.xml but not installed, so the type is not checked at build '
                             'time; it must be installed where the node runs', path, code='NODL257')
            return
        hint = ''
        if resolution.suggestions:
            hint = f"; did you mean '{resolution.suggestions[0]}'?"
        yield Diagnostic(Severity.ERROR, f"package '{package}' of '{text}' is not installed: no "
                         'prefix of AMENT_PREFIX_PATH lists its interfaces; install it or source '
                         f'the workspace that builds it{hint}', path, code='NODL250')
        return
    if resolution.status == 'no_interfaces':
        yield Diagnostic(Severity.ERROR, f"package '{package}' is installed but defines no "
                         f"interface types, so '{text}' does not exist", path, code='NODL254')
        return
    if resolution.status == 'unknown_type':
        name = text.split('/')[-1]
        hint = (f"; did you mean '{resolution.suggestions[0]}'?" if resolution.suggestions
                else f"; its {index.describe_kind(namespace).split()[-1]} types: "
                     f"{', '.join(n.split('/')[-1] for n in _names(resolution.package, namespace)) or 'none'}")
        yield Diagnostic(Severity.ERROR, f"'{text}': package '{package}' defines no "
                         f"{index.describe_kind(namespace).split()[-1]} '{name}'{hint}", path,
                         code='NODL251')
        return
    if resolution.status == 'wrong_kind':
        assert resolution.type is not None
        yield Diagnostic(Severity.ERROR, f"'{text}' is not {index.describe_kind(namespace)} type: "
                         f"'{resolution.type}' is {index.describe_kind(resolution.type.namespace)}, "
                         f'and {_USERS[namespace]}', path, code='NODL252')
        return
    assert resolution.type is not None
    if resolution.status == 'short':
        yield Diagnostic(Severity.WARNING, f"'{text}' resolves to '{resolution.type}'; write the "
                         'full name', path, code='NODL253')
    problem = interface_problem(index, str(resolution.type))
    if problem is not None:
        yield str(resolution.type), problem
    if manifest is None or own is None or package == own:
        return
    if manifest.run_time(package):
        return
    if manifest.build_only(package):
        yield Diagnostic(Severity.WARNING, f"package '{package}' of '{text}' is only a build "
                         f'dependency in {manifest.file}:{manifest.line_of(package)}: the node '
                         f'needs it at run time; use <depend>{package}</depend>', path,
                         code='NODL256',
                         related=[(manifest.file, manifest.line_of(package), 1,
                                   'declared as a build dependency only')])
        return
    yield Diagnostic(Severity.ERROR, f"package '{package}' of '{text}' is not a dependency of "
                     f"'{own}': add <depend>{package}</depend> to {manifest.file}", path,
                     code='NODL255', related=[(manifest.file, 1, 1, f"the manifest of '{own}'")])


def _names(package: Any, namespace: str) -> list[str]:
    return package.names(namespace)[:8] if package is not None else []


def interface_problem(index: InterfaceIndex, name: str) -> Any:
    """The :class:`~nodl.interface_types.tree.InterfaceFileError` of the file that
    defines ``name`` or a type it nests (the first found), else None; once per index.

    A source package's type is parsed as IDL (as its build will); an installed one from its
    ``.msg``/``.srv``/``.action`` file by rosidl_adapter's parser (the ``.idl`` installed
    beside it is generated from it), or as IDL when none is installed.
    """
    key = ('problem', name)
    if key in index.cache:
        return index.cache[key]
    index.cache[key] = None  # a type nesting itself is checked once
    index.cache[key] = problem = _problem(index, name)
    return problem


def _problem(index: InterfaceIndex, name: str) -> Any:
    package, namespace, base = name.split('/')
    owner = index.package(package)
    files = owner.types.get((namespace, base), []) if owner is not None else []
    if owner is None or not files:
        return None
    plain = [f for f in files if not f.endswith('.idl')]
    if owner.origin == 'source' or not plain:
        try:
            load_type(index, name)
        except InterfaceFileError as exc:
            return exc
        except LookupError:
            return None
        return None
    path = os.path.join(owner.share, plain[0])
    try:
        nested = _nested(path, package, namespace, base)
    except InterfaceFileError as exc:
        return exc
    for field, line, (other_package, other) in nested:
        inner = f'{other_package}/msg/{other}'
        found = index.package(other_package)
        if found is None or ('msg', other) not in found.types:
            where = 'its package is not installed' if found is None else 'no such message there'
            return InterfaceFileError(f"field '{field}' is of type '{inner}', which cannot be "
                                      f'found ({where})', path, line)
        problem = interface_problem(index, inner)
        if problem is not None:
            return problem
    return None


def _nested(path: str, package: str, namespace: str, base: str
            ) -> list[tuple[str, int, tuple[str, str]]]:
    """``(field, line, (package, Type))`` of each field of a ``.msg``/``.srv``/``.action``
    file whose type is a message; InterfaceFileError if the file is malformed."""
    text = _read_text(path)
    spec = _adapter_spec(text, path, package, namespace, base)  # as the typed tree reads it
    parts = {'msg': ('',), 'srv': ('request', 'response'),
             'action': ('goal', 'result', 'feedback')}[namespace]
    lines = text.splitlines()
    out: list[tuple[str, int, tuple[str, str]]] = []
    for part in parts:
        message: Any = getattr(spec, part) if part else spec
        for field in message.fields:
            if field.type.is_primitive_type():
                continue
            line = next((n for n, t in enumerate(lines, 1)
                         if t.split('#')[0].split()[1:2] == [field.name]), 0)
            out.append((field.name, line, (str(field.type.pkg_name), str(field.type.type))))
    return out
