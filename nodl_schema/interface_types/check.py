"""The interface types a NoDL document names, checked against what is installed.

Each ``type:`` of an endpoint section must name an installed (or, with a
package's source folder, a source) message, service or action type of the
section's kind.  With the package's manifest, each interface package must be
a run-time dependency of it.  Diagnostics are placed at the ``type:`` value.

Only names are resolved here (the index is read once per run, no interface
file is parsed), except the package's own source types, which no build has
checked yet: those are parsed, and a malformed one is reported at its line.
"""

from __future__ import annotations

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any, Iterator

    from nodl_schema.interface_types.manifest import Manifest
    from nodl_schema.interface_types.resolve import InterfaceIndex
    from nodl_schema.loading import Report

from nodl_schema.diagnostics import Diagnostic, DocPath, Severity
from nodl_schema.vocabulary import SECTIONS

__all__ = ['check_types', 'type_entries', 'manifest_for']

_USERS = {'msg': 'topics carry messages', 'srv': 'services need a service type',
          'action': 'actions need an action type'}


def type_entries(report: Report) -> Iterator[tuple[DocPath, str, str]]:
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
    import os

    from nodl_schema.interface_types.manifest import read_manifest

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


def check_types(report: Report, index: InterfaceIndex, manifest: Manifest | None = None, *,
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
    for path, text, namespace in type_entries(report):
        found = list(_check_one(index, text, namespace, path, manifest, own, build))
        out += [report.place(d) for d in found]
    return out


def _check_one(index: InterfaceIndex, text: str, namespace: str, path: DocPath,
               manifest: Manifest | None, own: str | None, build: bool) -> Iterator[Diagnostic]:
    from nodl_schema.validation.types import type_problem

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
    if resolution.package is not None and resolution.package.origin == 'source':
        yield from _parse_source(index, str(resolution.type), path)
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


def _parse_source(index: InterfaceIndex, name: str, path: DocPath) -> Iterator[Diagnostic]:
    """A source package's type is parsed (no build has checked it): a malformed file is
    reported once, at its line, as related to the ``type:`` that names it."""
    from nodl_schema.interface_types.tree import InterfaceFileError, load_type

    try:
        load_type(index, name)
    except InterfaceFileError as exc:
        yield Diagnostic(Severity.ERROR, f"'{name}' cannot be read: {exc}; fix the file",
                         path, code='NODL258',
                         related=[(exc.file, exc.line, exc.column, exc.message)])
    except LookupError:
        return
