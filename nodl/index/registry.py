"""Registered NoDL definitions: what packages install in the ament index.

* ``nodl_nodes/<package>__<executable>``: a node definition for an executable;
* ``nodl_interfaces/<package>__<name>``: an interface definition, used as
  ``nodl://<package>/<name>``;
* ``nodl/<package>__<name>``: what the reference implementation's current
  ``ament_nodl_register(NAME FILE f [PACKAGE p])`` installs, the entry holding
  the document itself: a node definition of executable ``name`` (read in the
  include dialect, a flat document as a node of that interface alone), and
  also what ``nodl://<package>/<name>`` finds when no interface definition of
  that name is registered;
* legacy packages: the ``nodl_desc/<package>`` marker (spec 001) and a
  ``package.xml`` that exports ``<interface path="..."/>`` (spec 000).

Definitions folders (overlays, :mod:`nodl.targets.overlay`) in force come
first: a package's executable defined there is found there, whatever the index
holds, and its :attr:`Registration.origin` says which folder served it.
"""

from __future__ import annotations

import os
from typing import NamedTuple

# Importing the ament resolver imports the composition package, and with it loading: the
# names compose_registered needs are there already, so they are imported here rather than
# on every call (an import statement costs a few microseconds each time it runs).  Composing
# and checking are called through their modules, so that timing wrappers see the calls.
from nodl import composition, loading
from nodl.composition.ament_resolver import (
    INTERFACE_RESOURCE, NODE_RESOURCE, read_registered, resource_name)
from nodl.vocabulary import REFERENCE_RESOURCE
from nodl.composition.resolvers import ResolutionError, Resolved
from nodl.diagnostics import Diagnostic, Severity
from nodl.index import ament
from nodl.targets import overlay
from nodl.validation.kinds import Kind
from nodl.vocabulary import RESOURCE_SEPARATOR

__all__ = ['Registration', 'list_registrations', 'find_node', 'read_registration',
           'compose_registered', 'describe_missing']

_KINDS = {NODE_RESOURCE: 'node', INTERFACE_RESOURCE: 'interface', REFERENCE_RESOURCE: 'node'}
#: Where a node definition may be registered, in the order they are looked up.
_NODE_RESOURCES = (NODE_RESOURCE, REFERENCE_RESOURCE)


class Registration(NamedTuple):
    """One registered definition."""

    package: str
    #: The executable (node definitions) or the name (interface definitions).
    name: str
    #: ``node``, ``interface`` or ``legacy node``.
    kind: str
    #: The file the definition is read from (for index entries holding the
    #: document itself, the index entry).
    file: str
    #: Where it was found: ``index``, or ``overlay DIR`` (a definitions folder).
    origin: str = 'index'


def _v2(resource_type: str, prefixes: list[str], package: str | None) -> list[Registration]:
    found = []
    for name in ament.get_resources(resource_type, prefixes):
        pkg, sep, key = name.partition(RESOURCE_SEPARATOR)
        if not sep or (package is not None and pkg != package):
            continue
        resource = ament.get_resource(resource_type, name, prefixes)
        assert resource is not None
        try:
            file = read_registered(resource, pkg).file
        except ResolutionError:
            file = resource.path
        found.append(Registration(pkg, key, _KINDS[resource_type], file))
    return found


def list_registrations(package: str | None = None, prefixes: list[str] | None = None,
                       kind: str | None = None) -> list[Registration]:
    """Every registered definition (of ``package`` only, if given), sorted.

    ``kind`` keeps one kind: ``node`` (v2 and legacy node definitions) or ``interface``.
    """
    prefixes = prefixes if prefixes is not None else ament.prefix_paths()
    found: list[Registration] = []
    definitions = overlay.active()
    served: set[tuple[str, str, str]] = set()
    if definitions:
        for entry, folder in definitions.entries(package):
            if kind in (None, entry.kind):
                found.append(Registration(entry.package, entry.name, entry.kind, entry.file,
                                          folder.label))
                served.add((entry.package, entry.name, entry.kind))
    found += [r for r in _index_registrations(package, prefixes, kind)
              if (r.package, r.name, 'interface' if r.kind == 'interface' else 'node') not in served]
    return sorted(found)


def _index_registrations(package: str | None, prefixes: list[str], kind: str | None
                         ) -> list[Registration]:
    found: list[Registration] = []
    if kind in (None, 'node'):
        found += _v2(NODE_RESOURCE, prefixes, package)
        # The reference's registrations: a node's own registration wins over one of the same name.
        own = {(r.package, r.name) for r in found}
        found += [r for r in _v2(REFERENCE_RESOURCE, prefixes, package)
                  if (r.package, r.name) not in own]
    if kind in (None, 'interface'):
        found += _v2(INTERFACE_RESOURCE, prefixes, package)
    if kind in (None, 'node'):
        from nodl.index.legacy import legacy_registrations

        v2_nodes = {(r.package, r.name) for r in found if r.kind == 'node'}
        found += [r for r in legacy_registrations(package, prefixes)
                  if (r.package, r.name) not in v2_nodes]
    return found


def find_node(package: str, executable: str,
              prefixes: list[str] | None = None) -> Registration | None:
    """The node definition registered for ``package``'s ``executable`` (v2 first, then legacy);
    looked up once within an :func:`nodl.index.ament.snapshot`."""
    definitions = overlay.active()
    if definitions:
        served = definitions.find_node(package, executable)
        if served is not None:
            return Registration(package, executable, 'node', served[0], served[1].label)
    prefixes = prefixes if prefixes is not None else ament.prefix_paths()
    return ament.remembered(('find_node', package, executable, tuple(prefixes)),
                            lambda: _find_node(package, executable, prefixes))


def _node_resource(package: str, executable: str, prefixes: list[str] | None
                   ) -> tuple[str, ament.Resource] | None:
    """The resource type and entry a node definition is registered as (own type first)."""
    key = resource_name(package, executable)
    for resource_type in _NODE_RESOURCES:
        resource = ament.get_resource(resource_type, key, prefixes)
        if resource is not None:
            return resource_type, resource
    return None


def _find_node(package: str, executable: str, prefixes: list[str]) -> Registration | None:
    found = _node_resource(package, executable, prefixes)
    if found is not None:
        resource = found[1]
        try:
            return Registration(package, executable, 'node', read_registered(resource, package).file)
        except ResolutionError:
            return Registration(package, executable, 'node', resource.path)
    from nodl.index.legacy import legacy_registrations

    for registration in legacy_registrations(package, prefixes):
        if registration.name == executable:
            return registration
    return None


def read_registration(registration: Registration, prefixes: list[str] | None = None) -> Resolved:
    """The text of a registered v2 definition."""
    return _read_registration(registration, prefixes)[0]


def _read_registration(registration: Registration, prefixes: list[str] | None
                       ) -> tuple[Resolved, bool]:
    """The text of a registered v2 definition, and whether the reference's macro installed it."""
    resource: ament.Resource | None
    if registration.kind == 'node':
        found = _node_resource(registration.package, registration.name, prefixes)
        resource_type, resource = found if found is not None else (NODE_RESOURCE, None)
    else:
        resource_type = INTERFACE_RESOURCE
        resource = ament.get_resource(resource_type, resource_name(registration.package,
                                                                   registration.name), prefixes)
    if resource is None:
        raise ResolutionError(f'{registration.package}/{registration.name} is not registered')
    return read_registered(resource, registration.package), resource_type == REFERENCE_RESOURCE


def describe_missing(package: str, executable: str, prefixes: list[str] | None = None) -> str:
    """Why ``find_node`` found nothing, for an error message."""
    prefixes = prefixes if prefixes is not None else ament.prefix_paths()
    definitions = overlay.active()
    folders = ('; the definitions folders (' + ', '.join(f.root for f in definitions.folders)
               + f') have none of {package} {executable} either') if definitions else ''
    if not prefixes:
        return ('AMENT_PREFIX_PATH is empty; source the workspace (install/setup.bash) first'
                + folders)
    registered = list_registrations(package, prefixes)
    names = sorted(r.name for r in registered if 'node' in r.kind)
    if not registered and ament.package_share_directory(package, prefixes) is None:
        return f"package '{package}' is not in the ament index{folders}"
    if names:
        return (f"package '{package}' registers no node definition for '{executable}' "
                f"(it has: {', '.join(names)}){folders}")
    return f"package '{package}' registers no node definitions{folders}"


def compose_registered(package: str, executable: str, prefixes: list[str] | None = None,  # type: ignore[no-untyped-def]
                       client_library: str = 'rclpy'):
    """Find and compose the node definition registered for ``package``'s ``executable``
    (with the base of ``client_library``), its ``nodl://`` mixins looked up in the same
    ``prefixes`` (default: ``AMENT_PREFIX_PATH``).

    Returns ``(composed or None, diagnostics, source)``; a legacy node is
    converted to v2 in memory first.  Never raises for a missing or broken
    registration: that is a diagnostic.
    """
    where = f'{package}/{executable}'
    registration = find_node(package, executable, prefixes)
    if registration is None:
        return None, [Diagnostic(Severity.ERROR, describe_missing(package, executable, prefixes),
                                 (), where, code='NODL306')], where
    if registration.origin != 'index':  # a definitions folder's file
        from pathlib import Path

        try:
            report = loading.check_source(Path(registration.file), kind=Kind.NODE,
                                          file=registration.file)
        except OSError as exc:
            from nodl.files import describe_os_error

            return None, [Diagnostic(Severity.ERROR, f'cannot read the definition: '
                                     f'{describe_os_error(exc)}', (), registration.file,
                                     code='NODL246')], registration.file
        composed, diagnostics = composition.compose_report(report, client_library=client_library,
                                                           prefixes=prefixes)
        return composed, diagnostics, registration.file
    if registration.kind == 'legacy node':
        from nodl.index.legacy import compose_legacy

        composed, diagnostics = compose_legacy(registration, client_library)
        return composed, diagnostics, registration.file
    try:
        resolved, installed = _read_registration(registration, prefixes)
    except ResolutionError as exc:  # an entry whose file is gone (a partly removed install)
        return None, [Diagnostic(Severity.ERROR, exc.message, (), where, code='NODL015')], where
    composed, diagnostics = composition.compose_report(
        loading.check_source(resolved.text, kind=Kind.NODE, file=resolved.file, installed=installed),
        client_library=client_library, prefixes=prefixes)
    return composed, diagnostics, resolved.file
