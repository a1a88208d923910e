"""Matching launched nodes to their registered definitions (through the ament index).

An executable is matched by ``nodl_nodes/<package>__<executable>`` (legacy
XML files included, as ``nodl show`` finds them).  A composable node is
matched by its plugin: the registration of the plugin's package that records
that plugin class (``ament_nodl_register_node(KEY FILE f PLUGIN pkg::Class)``),
otherwise the key that is the class name in snake case
(``rover_sensors::CameraDriver`` -> ``rover_sensors`` ``camera_driver``).

Each definition is found and resolved once per analysis, however many nodes
launch it.  Definitions folders in force (:mod:`nodl.registry.overlay`)
are looked in before the index; :attr:`Match.origin` says which served.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from nodl.composition.resolved import ResolvedNode
from nodl.composition.resolvers import ResolutionError
from nodl.diagnostics import Diagnostic
from nodl.launch.model import LaunchedNode
from nodl.registry import Registration, node_info, registrations
from nodl.targets.resolve import Provenance, no_header, resolve_registered

# Imported here, not in the functions: an import statement costs a few microseconds each
# time it runs, for every launched node.  The index functions are called through their
# modules, so that timing wrappers put on the modules' functions see these calls too.

__all__ = ['DefinitionMatcher', 'Match']


@dataclass
class Match:
    """The definition a launched node runs, and what its registration records."""

    package: str
    #: The registration key (the executable, or the plugin's key).
    key: str
    #: The registration's file (None: nothing registered).
    file: str | None
    #: The resolved node (None: not registered, or it does not resolve).
    resolved: ResolvedNode | None
    #: The name the executable gives its node (from the registration), if recorded.
    node_name: str | None = None
    #: How the definition was found (``executable``, ``plugin``, ``class name``).
    how: str = 'executable'
    #: Why resolving failed (errors of the definition), if it did.
    problems: list[Diagnostic] = field(default_factory=list)
    #: Where the definition was found: ``index``, ``overlay DIR`` (a definitions folder)
    #: or ``file`` (given by path).
    origin: str = 'index'
    #: Where the definition came from, with what wrote its file (read once: see
    #: :meth:`provenance`).
    _provenance: Provenance | None = field(default=None, repr=False, compare=False)

    def provenance(self) -> Provenance:
        """Where the definition came from (``none`` without one), and whether ``nodl extract``
        or ``nodl describe`` wrote its file: read from the file once per definition, however
        many launched nodes run it."""
        found = self._provenance
        if found is None:
            found = self._provenance = Provenance.of(self.origin, self.file)
        return found


class DefinitionMatcher:
    """Finds and resolves definitions for launch entries, each once."""

    def __init__(self, client_library: str | None = None,
                 prefixes: list[str] | None = None) -> None:
        self.client_library = client_library
        self.prefixes = prefixes if prefixes is not None else registrations.search_path()
        self._cache: dict[tuple[str, str, str], Match] = {}

    def read_ahead(self, entries: Iterable[LaunchedNode]) -> None:
        """Read and check the index-registered definitions the executables of ``entries`` run,
        before any is composed (:func:`nodl.registry.registrations.checked_registration`;
        within :func:`~nodl.registry.registrations.one_run`, :meth:`match` then composes
        what was read here: each document is still read once).  What cannot be read is left
        for :meth:`match` to say."""
        seen: set[tuple[str, str]] = set()
        for entry in entries:
            if entry.plugin is not None:
                continue
            wanted = (entry.package or '', entry.executable or '')
            if wanted in seen:
                continue
            seen.add(wanted)
            registration = registrations.find_node(wanted[0], wanted[1], self.prefixes)
            if registration is None or registration.origin != 'index' or registration.kind != 'node':
                continue
            try:
                registrations.checked_registration(registration, self.prefixes)
            except ResolutionError:
                continue

    def match(self, entry: LaunchedNode) -> Match:
        """The match of one launched node (cached per package and key)."""
        package = entry.package or ''
        how = 'executable'
        if entry.plugin is not None:
            info = node_info.find_plugin(package, entry.plugin, self.prefixes)
            key, how = (info.key, 'plugin') if info is not None \
                else (node_info.plugin_key(entry.plugin), 'class name')
        else:
            key = entry.executable or ''
        cache_key = (package, key, how)
        found = self._cache.get(cache_key)
        if found is None:
            found = self._find(package, key, how)
            self._cache[cache_key] = found
        return found

    def _find(self, package: str, key: str, how: str) -> Match:
        registration = registrations.find_node(package, key, self.prefixes)
        if registration is None:
            return Match(package, key, None, None, how=how)
        node_name = node_info.read_node_info(package, key, self.prefixes).node_name
        resolved, diagnostics, source = resolve_registered(
            package, key, client_library=self.client_library, prefixes=self.prefixes)
        problems = [d for d in diagnostics if d.severity.value == 'error']
        file = source or registration.file
        return Match(package, key, file, resolved, node_name, how, problems, registration.origin,
                     self._provenance(registration, file))

    def _provenance(self, registration: Registration, file: str) -> Provenance | None:
        """The provenance of an index registration whose document (read once, and kept by
        the run's snapshot of the index) cannot start with a ``nodl extract`` or ``nodl
        describe`` header; None (read from the file on first use) otherwise."""
        if registration.origin != 'index' or registration.kind != 'node':
            return None
        try:
            document = registrations.read_registration(registration, self.prefixes)
        except ResolutionError:
            return None
        if document.file != file or not no_header(document.text):
            return None
        return Provenance(registration.origin, None, None)
