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

Definitions folders (overlays, :mod:`nodl.registry.overlay`) in force come
first: a package's executable defined there is found there, whatever the index
holds, and its :attr:`Registration.origin` says which folder served it.
"""

from __future__ import annotations

import os
from contextlib import AbstractContextManager
from pathlib import Path

# The names compose_registered needs are imported here rather than on every call (an
# import statement costs a few microseconds each time it runs).  Composing and checking
# are called through their modules, so that timing wrappers see the calls.
from nodl import ament_index, composition, loading
from nodl.composition.resolvers import ResolutionError, Resolved
from nodl.diagnostics import Diagnostic, Severity
from nodl.files import describe_os_error, tidy_path
from nodl.frontends.source import read_regular
from nodl.registry import Registration, overlay
from nodl.registry.legacy import compose_legacy, legacy_registrations
from nodl.validation.kinds import Kind
from nodl.vocabulary import (
    INTERFACE_RESOURCE,
    NODE_RESOURCE,
    REFERENCE_RESOURCE,
    RESOURCE_SEPARATOR,
    resource_name,
)

__all__ = ['Registration', 'search_path', 'one_run', 'list_registrations', 'find_node',
           'read_registration', 'read_registered', 'interface_entry', 'find_interface',
           'compose_registered', 'checked_registration', 'describe_missing']

_KINDS = {NODE_RESOURCE: 'node', INTERFACE_RESOURCE: 'interface', REFERENCE_RESOURCE: 'node'}
#: Where a node definition may be registered, in the order they are looked up.
_NODE_RESOURCES = (NODE_RESOURCE, REFERENCE_RESOURCE)


def search_path(prefixes: list[str] | None = None) -> list[str]:
    """The prefixes a look-up searches: ``prefixes`` as given, else ``AMENT_PREFIX_PATH``'s."""
    return prefixes if prefixes is not None else ament_index.prefix_paths()


def one_run() -> AbstractContextManager[None]:
    """A block within which every look-up sees the index as it was when first read (one
    listing per resource folder, each entry and registered document read once): for one
    run over many nodes, such as an analysis of a launched system.  Nested blocks share
    the outer one (:func:`nodl.ament_index.snapshot`)."""
    return ament_index.snapshot()


def read_registered(resource: ament_index.Resource, package: str) -> Resolved:
    """The document a registration entry points at (or holds); read once per entry within
    :func:`one_run`.

    The entry's content is the path of the installed file relative to
    ``share/<package>`` (what ``ament_nodl_register_*`` and the Python helper write), an
    absolute path (the build-time staging index), or the document itself (the reference's
    ``nodl`` resource).  :class:`ResolutionError` for a path whose file is gone.
    """
    return ament_index.remembered(('registered', resource, package),
                                  lambda: _read_registered(resource, package))


def _read_registered(resource: ament_index.Resource, package: str) -> Resolved:
    content = resource.content.strip()
    # A path is one line; a document held in the entry may be one line too (flow YAML
    # or minified JSON: '{...}', or 'key: value').
    if content and '\n' not in content and not content.startswith('{') and ': ' not in content:
        candidate = tidy_path(content if os.path.isabs(content) else
                              os.path.join(resource.prefix, 'share', package, content))
        data = read_regular(candidate)
        if data is not None:
            return Resolved(data, candidate)
        raise ResolutionError(f'the index entry {resource.path} points at {candidate}, '
                              'which does not exist (is the package fully installed?)', [candidate])
    return Resolved(resource.content, resource.path)


def _v2(resource_type: str, prefixes: list[str], package: str | None) -> list[Registration]:
    found = []
    for name in ament_index.get_resources(resource_type, prefixes):
        pkg, sep, key = name.partition(RESOURCE_SEPARATOR)
        if not sep or (package is not None and pkg != package):
            continue
        resource = ament_index.get_resource(resource_type, name, prefixes)
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
    prefixes = prefixes if prefixes is not None else ament_index.prefix_paths()
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
        v2_nodes = {(r.package, r.name) for r in found if r.kind == 'node'}
        found += [r for r in legacy_registrations(package, prefixes)
                  if (r.package, r.name) not in v2_nodes]
    return found


def find_node(package: str, executable: str,
              prefixes: list[str] | None = None) -> Registration | None:
    """The node definition registered for ``package``'s ``executable`` (v2 first, then legacy);
    looked up once within an :func:`nodl.ament_index.snapshot`."""
    definitions = overlay.active()
    if definitions:
        served = definitions.find_node(package, executable)
        if served is not None:
            return Registration(package, executable, 'node', served[0], served[1].label)
    prefixes = prefixes if prefixes is not None else ament_index.prefix_paths()
    return ament_index.remembered(('find_node', package, executable, tuple(prefixes)),
                            lambda: _find_node(package, executable, prefixes))


def _node_resource(package: str, executable: str, prefixes: list[str] | None
                   ) -> tuple[str, ament_index.Resource] | None:
    """The resource type and entry a node definition is registered as (own type first)."""
    key = resource_name(package, executable)
    for resource_type in _NODE_RESOURCES:
        resource = ament_index.get_resource(resource_type, key, prefixes)
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
    resource: ament_index.Resource | None
    if registration.kind == 'node':
        found = _node_resource(registration.package, registration.name, prefixes)
        resource_type, resource = found if found is not None else (NODE_RESOURCE, None)
    else:
        resource_type = INTERFACE_RESOURCE
        resource = ament_index.get_resource(resource_type, resource_name(registration.package,
                                                                   registration.name), prefixes)
    if resource is None:
        raise ResolutionError(f'{registration.package}/{registration.name} is not registered')
    return read_registered(resource, registration.package), resource_type == REFERENCE_RESOURCE


def interface_entry(package: str, name: str, resource_type: str = INTERFACE_RESOURCE,
                    prefixes: list[str] | None = None) -> ament_index.Resource | None:
    """The index entry registering ``package``'s interface definition ``name`` as
    ``resource_type`` (``nodl_interfaces``, or the reference's ``nodl``), or None."""
    return ament_index.get_resource(resource_type, resource_name(package, name), prefixes)


def find_interface(package: str, name: str, prefixes: list[str] | None = None) -> Resolved:
    """The interface definition ``nodl://<package>/<name>``: a definitions folder's in force
    first, then ``nodl_interfaces``, then the reference's ``nodl`` resource, in ``prefixes``
    (default: ``AMENT_PREFIX_PATH``).

    :class:`ResolutionError` saying what was searched and what the package registers.
    """
    definitions = overlay.active()
    served = definitions.find_interface(package, name) if definitions else None
    if served is not None:
        data = read_regular(served[0])
        if data is None:
            raise ResolutionError(f'{served[0]} cannot be read', [served[0]])
        return Resolved(data, served[0])
    where = 'prefixes searched' if prefixes is not None else 'AMENT_PREFIX_PATH'
    prefixes = search_path(prefixes)
    key = resource_name(package, name)
    resource = (ament_index.get_resource(INTERFACE_RESOURCE, key, prefixes)
                or ament_index.get_resource(REFERENCE_RESOURCE, key, prefixes))
    if resource is not None:
        return read_registered(resource, package)
    searched = [ament_index.resource_file(p, t, key)
                for t in (INTERFACE_RESOURCE, REFERENCE_RESOURCE) for p in prefixes]
    if not prefixes:
        if where != 'AMENT_PREFIX_PATH':
            raise ResolutionError('no ament prefix was given to search, so no package can be found')
        raise ResolutionError('AMENT_PREFIX_PATH is empty, so no package can be found; '
                              'source the workspace (install/setup.bash) first')
    start = resource_name(package, '')
    available = sorted({n[len(start):] for t in (INTERFACE_RESOURCE, REFERENCE_RESOURCE)
                        for n in ament_index.get_resources(t, prefixes) if n.startswith(start)})
    if available:
        raise ResolutionError(f"package '{package}' registers no interface definition "
                              f"'{name}' (it registers: {', '.join(available)})", searched)
    if ament_index.package_share_directory(package, prefixes) is None:
        raise ResolutionError(f"package '{package}' is not in the ament index "
                              f"({where}: {os.pathsep.join(prefixes)})", searched)
    raise ResolutionError(f"package '{package}' registers no interface definitions", searched)


def describe_missing(package: str, executable: str, prefixes: list[str] | None = None) -> str:
    """Why ``find_node`` found nothing, for an error message."""
    prefixes = prefixes if prefixes is not None else ament_index.prefix_paths()
    definitions = overlay.active()
    folders = ('; the definitions folders (' + ', '.join(f.root for f in definitions.folders)
               + f') have none of {package} {executable} either') if definitions else ''
    if not prefixes:
        return ('AMENT_PREFIX_PATH is empty; source the workspace (install/setup.bash) first'
                + folders)
    registered = list_registrations(package, prefixes)
    names = sorted(r.name for r in registered if 'node' in r.kind)
    if not registered and ament_index.package_share_directory(package, prefixes) is None:
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
        try:
            report = loading.check_source(Path(registration.file), kind=Kind.NODE,
                                          file=registration.file)
        except OSError as exc:
            return None, [Diagnostic(Severity.ERROR, f'cannot read the definition: '
                                     f'{describe_os_error(exc)}', (), registration.file,
                                     code='NODL246')], registration.file
        composed, diagnostics = composition.compose_report(report, client_library=client_library,
                                                           prefixes=prefixes)
        return composed, diagnostics, registration.file
    if registration.kind == 'legacy node':
        composed, diagnostics = compose_legacy(registration, client_library)
        return composed, diagnostics, registration.file
    try:
        report = checked_registration(registration, prefixes)
    except ResolutionError as exc:  # an entry whose file is gone (a partly removed install)
        return None, [Diagnostic(Severity.ERROR, exc.message, (), where, code='NODL015')], where
    composed, diagnostics = composition.compose_report(report, client_library=client_library,
                                                       prefixes=prefixes)
    return composed, diagnostics, report.file


def checked_registration(registration: Registration, prefixes: list[str] | None = None
                         ) -> loading.CheckedSource:
    """The document of an index-registered v2 node definition read, parsed and validated
    (:func:`nodl.loading.check_source`); once per registration within :func:`one_run`.

    An analysis asks this for all its definitions before it composes any: reading a
    thousand documents one after another, rather than each between the composing and
    instantiating of others, was measured about 20 ms faster (issue 16).
    :class:`ResolutionError` for an entry whose file is gone.
    """
    key = ('checked', registration, tuple(prefixes) if prefixes is not None else None)
    return ament_index.remembered(key, lambda: _check_registration(registration, prefixes))


def _check_registration(registration: Registration, prefixes: list[str] | None
                        ) -> loading.CheckedSource:
    resolved, installed = _read_registration(registration, prefixes)
    return loading.check_source(resolved.text, kind=Kind.NODE, file=resolved.file,
                                installed=installed)
