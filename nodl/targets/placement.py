"""Node definitions placed by name, for consumers that take definitions without a launch
file (``nodl policy DEFINITION...``, ``nodl analyse DEFINITION...``).

A definition is a file or ``PACKAGE EXECUTABLE`` (looked up in the definitions
folders in force, then the ament index); each is placed with a name (``/ns/node``;
by default the file's stem or the executable, at ``/``), the remapping rules given
(as rcl applies them: ``node:from:=to`` applies to one node only) and parameter values.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

from nodl.composition.instance import NodeInstance
from nodl.diagnostics import Diagnostic, Severity
from nodl.launch.file_kind import not_a_launch_file
from nodl.registry.overlay import Definitions
from nodl.targets.resolve import Provenance, resolve_target

__all__ = ['Definition', 'Placed', 'LAUNCH_SUFFIXES', 'is_launch_file', 'names_definitions', 'split_targets',
           'default_node_name', 'split_node_name', 'place_definitions', 'instances_from_definitions']

#: File name endings of launch files (XML, YAML, Python frontends).
LAUNCH_SUFFIXES = ('.launch.xml', '.launch.py', '.launch.yaml', '.launch.yml', '.launch')


class Definition(NamedTuple):
    """A node definition to place: ``file``, or ``package`` and ``executable``."""

    file: str | None = None
    package: str | None = None
    executable: str | None = None

    def __str__(self) -> str:
        return self.file if self.file is not None else f'{self.package} {self.executable}'


def is_launch_file(path: str) -> bool:
    """True for a file name launch files are written with."""
    return path.endswith(LAUNCH_SUFFIXES)


def _is_path(token: str) -> bool:
    return any(c in token for c in './\\') or os.path.exists(token)


def names_definitions(first: str) -> bool:
    """True when the first target of a command line names node definitions (a file holding
    one, or ``PACKAGE EXECUTABLE``) rather than a launch file; a file that cannot be read is
    taken for a launch file, whose reader says why."""
    if is_launch_file(first):
        return False
    if not _is_path(first):
        return True  # PACKAGE EXECUTABLE
    if not os.path.isfile(first):
        return False
    return not_a_launch_file(first) == 'a NoDL node definition'


def split_targets(tokens: Sequence[str]) -> tuple[list[Definition], list[str]]:
    """``(definitions, launch files)`` from the command line's targets.

    A token that is a path is a file (a launch file by its name); two other
    tokens in a row are ``PACKAGE EXECUTABLE``.  ValueError for a lone package.
    """
    definitions: list[Definition] = []
    launches: list[str] = []
    index = 0
    while index < len(tokens):
        token = tokens[index]
        if _is_path(token):
            if is_launch_file(token):
                launches.append(token)
            else:
                definitions.append(Definition(file=token))
            index += 1
            continue
        if index + 1 >= len(tokens) or _is_path(tokens[index + 1]):
            raise ValueError(f"'{token}' is neither a file nor a package followed by one of its "
                             'executables (give FILE, PACKAGE EXECUTABLE or a launch file)')
        definitions.append(Definition(package=token, executable=tokens[index + 1]))
        index += 2
    return definitions, launches


def default_node_name(definition: Definition) -> str:
    """The name a definition is placed with by default: the executable, or the file's stem."""
    if definition.executable is not None:
        return definition.executable
    base = os.path.basename(definition.file or 'node')
    for suffix in ('.nodl.yaml', '.nodl.yml', '.nodl.json', '.nodl.xml', '.yaml', '.yml', '.json'):
        if base.endswith(suffix):
            base = base[:-len(suffix)]
            break
    return base.replace('-', '_').replace('.', '_') or 'node'


def split_node_name(text: str) -> tuple[str, str]:
    """``/ns/node`` -> (``/ns``, ``node``); a bare name is in ``/``."""
    if '/' not in text:
        return '/', text
    namespace, _, name = text.rpartition('/')
    return namespace or '/', name


class Placed(NamedTuple):
    """A definition placed as a node: its instance, and where its definition came from."""

    definition: Definition
    instance: NodeInstance
    #: The file the definition was read from.
    file: str
    provenance: Provenance


def place_definitions(definitions: Sequence[Definition], names: Sequence[str] = (), *,
                      remaps: Sequence[str] = (), parameters: Mapping[str, Any] | None = None,
                      client_library: str | None = None, prefixes: list[str] | None = None,
                      folders: Definitions | None = None) -> tuple[list[Placed], list[Diagnostic]]:
    """Resolve each definition (:func:`nodl.targets.resolve.resolve_target`, with the
    definitions ``folders`` in force) and place it (the i-th name places the i-th definition).

    Registered definitions and every ``nodl://`` mixin are looked up in the definitions
    folders, then ``prefixes`` (default: ``AMENT_PREFIX_PATH``).  Definitions that cannot be
    resolved give their diagnostics and no instance.  ValueError for more names than
    definitions, or a name or rule rcl would reject; OSError for a file that cannot be read.
    """
    if len(names) > len(definitions):
        raise ValueError(f'{len(names)} --name options for {len(definitions)} definitions: '
                         'each --name places one definition, in order')
    placed: list[Placed] = []
    diagnostics: list[Diagnostic] = []
    for index, definition in enumerate(definitions):
        target = [definition.file] if definition.file is not None else \
            [definition.package or '', definition.executable or '']
        found = resolve_target(target, client_library=client_library, prefixes=prefixes,
                               definitions=folders)
        if found.node is None:
            diagnostics.extend(found.diagnostics or [Diagnostic(
                Severity.ERROR, f'no node definition for {definition}', (),
                found.source or '<index>', code='NODL601')])
            continue
        text = names[index] if index < len(names) else default_node_name(definition)
        namespace, name = split_node_name(text)
        instance = NodeInstance(found.node, name, namespace, list(remaps), dict(parameters or {}))
        placed.append(Placed(definition, instance, found.source, found.provenance))
    return placed, diagnostics


def instances_from_definitions(definitions: Sequence[Definition], names: Sequence[str] = (), *,
                               remaps: Sequence[str] = (), parameters: Mapping[str, Any] | None = None,
                               client_library: str | None = None, prefixes: list[str] | None = None,
                               folders: Definitions | None = None
                               ) -> tuple[list[NodeInstance], list[Diagnostic]]:
    """The instances of :func:`place_definitions`, and the diagnostics of the definitions
    that do not resolve."""
    placed, diagnostics = place_definitions(definitions, names, remaps=remaps,
                                            parameters=parameters, client_library=client_library,
                                            prefixes=prefixes, folders=folders)
    return [p.instance for p in placed], diagnostics
