"""Which enclave each node runs in: one per node, one per namespace, or a mapping file.

* ``node`` (the default): the enclave path is the node's fully qualified name,
  so every node gets its own identity and exactly its own permissions;
* ``namespace``: the nodes of one namespace share an enclave named after it;
* a mapping file (YAML): ``enclave path: [node name or pattern, ...]``,
  e.g. ``/robot/sensors: [/robot/lidar, /robot/camera_*]``.  Entries are
  fully qualified node names or shell-style patterns (``*``, ``?``,
  ``[...]``) of them.  A node listed by name belongs to that enclave; a node
  only patterns match belongs to the enclave of those patterns.  Every
  ambiguity is an error (NODL610), since a node runs with exactly one
  identity: a node listed by name under two enclaves, or matched by patterns
  of two enclaves and listed by name under none; so are a node no entry
  matches, an enclave path that is not a valid absolute ROS namespace (what
  SROS 2 requires of enclave names) and an entry that is not an absolute
  name or pattern.  A name that matches no node of the system is a warning
  (NODL613: a typo there would let a pattern place the node elsewhere).

Several nodes in one enclave keep a profile each; DDS grants the enclave the
union of its profiles.

A composable node runs in its container's process, and a process has one
enclave (its context's, shared by every node in it): whatever the mode, a
composable node is in its container's enclave.  A mapping may list it there
or not at all; listing it under another enclave is an error (NODL610).
"""

from __future__ import annotations

import fnmatch
import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import NamedTuple

from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.source import read_source
from nodl.frontends.yaml_json import parse_document
from nodl.naming import full_name_error, namespace_error
from nodl.policy.names import has_wildcard

__all__ = ['ENCLAVE_MODES', 'EnclaveMapping', 'load_enclave_mapping', 'assign_enclaves',
           'enclave_path_error']

#: The built-in ways to cut a system into enclaves.
ENCLAVE_MODES = ('node', 'namespace')


def enclave_path_error(path: str) -> str | None:
    """Why ``path`` is not a valid enclave name (None: it is)."""
    if not path.startswith('/'):
        return 'an enclave path is absolute (starts with /)'
    return namespace_error(path)


class EnclaveMapping(NamedTuple):
    """A mapping file: ``(enclave path, patterns, (line, column))`` in file order."""

    file: str
    entries: list[tuple[str, list[str], tuple[int, int]]]
    #: ``(enclave path, entry)`` -> ``(line, column)`` of the entry (empty: unknown).
    places: dict[tuple[str, str], tuple[int, int]] = {}

    def place(self, path: str, entry: str) -> tuple[int, int]:
        """Where the entry ``entry`` of enclave ``path`` is written, else where the enclave is."""
        found = self.places.get((path, entry))
        if found is not None:
            return found
        return next((where for key, _, where in self.entries if key == path), (0, 0))


def entry_error(entry: str) -> str | None:
    """Why ``entry`` of a mapping file is neither a fully qualified node name nor a pattern of one."""
    if not entry.startswith('/'):
        return 'entries are fully qualified node names or patterns, starting with /'
    if has_wildcard(entry):
        return None
    return full_name_error(entry)


def _problem(file: str, message: str, line: int = 0, column: int = 0) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, (), file, line, column, code='NODL610')


def load_enclave_mapping(path: str) -> tuple[EnclaveMapping | None, list[Diagnostic]]:
    """Read a mapping file; (None, problems) if it cannot be used.  OSError if unreadable."""
    text, problem = read_source(Path(path), path)
    if text is None:
        assert problem is not None
        return None, [problem]
    doc = parse_document(text)
    if doc.diagnostics:
        return None, list(doc.diagnostics)
    data = doc.data
    if not isinstance(data, dict) or not data:
        return None, [_problem(path, 'an enclave mapping is a mapping of enclave paths to lists of '
                               'node names or patterns, e.g. "/robot/sensors: [/robot/lidar]"', 1, 1)]
    entries = []
    places: dict[tuple[str, str], tuple[int, int]] = {}
    problems = []
    for key, value in data.items():
        line, column = doc.position((key,), 'key')
        if not isinstance(key, str):
            problems.append(_problem(path, f'enclave path {key!r} is not a string', line, column))
            continue
        error = enclave_path_error(key)
        if error is not None:
            problems.append(_problem(path, f'{key!r} is not an enclave path: {error}', line, column))
            continue
        patterns = [value] if isinstance(value, str) else value
        if not isinstance(patterns, list) or not patterns or \
                not all(isinstance(p, str) and p for p in patterns):
            vline, vcolumn = doc.position((key,))
            problems.append(_problem(path, f'the nodes of enclave {key!r} are a list of node names '
                                     'or patterns', vline, vcolumn))
            continue
        for index, entry in enumerate(patterns):
            eline, ecolumn = doc.position((key, index)) if isinstance(value, list) else \
                doc.position((key,))
            places[(key, entry)] = (eline, ecolumn)
            error = entry_error(entry)
            if error is not None:
                problems.append(_problem(path, f'{entry!r} (enclave {key!r}) is not a node name or '
                                         f'pattern: {error}', eline, ecolumn))
        entries.append((key, patterns, (line, column)))
    if problems:
        return None, problems
    return EnclaveMapping(path, entries, places), []


def assign_enclaves(fqns: Iterable[str], how: str | EnclaveMapping = 'node',
                    containers: Mapping[str, str] | None = None
                    ) -> tuple[dict[str, str], list[Diagnostic]]:
    """Node fully qualified name -> enclave path, and the nodes no mapping entry matches.

    ``containers`` maps composable nodes to the container they are loaded
    into: each is put in its container's enclave (when the container is one
    of ``fqns``).
    """
    out: dict[str, str] = {}
    problems: list[Diagnostic] = []
    fqns = list(fqns)
    present = set(fqns)
    hosted = {node: container for node, container in (containers or {}).items()
              if node in present and container in present and node != container}
    for fqn in fqns:
        if fqn in hosted:
            continue
        if isinstance(how, EnclaveMapping):
            found, problem = _mapped(how, fqn)
            if problem is not None:
                problems.append(problem)
            if found is not None:
                out[fqn] = found
        elif how == 'namespace':
            out[fqn] = fqn.rsplit('/', 1)[0] or '/'
        elif how == 'node':
            out[fqn] = fqn
        else:
            raise ValueError(f'unknown enclave mode {how!r}; expected one of: {", ".join(ENCLAVE_MODES)} '
                             'or a mapping file')
    for fqn, container in hosted.items():
        target = out.get(container)
        if target is None:
            continue  # the container has no enclave: reported for the container
        if isinstance(how, EnclaveMapping):
            found, problem = _mapped(how, fqn, required=False)
            if problem is not None or (found is not None and found != target):
                problems.append(problem or _problem(
                    how.file, f'{fqn} is loaded into the container {container}, whose enclave is '
                    f'{target!r}, but {os.path.basename(how.file)} puts it in {found!r}: a process '
                    'has one enclave, shared by every node in it; list it with its container or '
                    'not at all', *how.place(found or '', fqn)))
                continue
        out[fqn] = target
    if isinstance(how, EnclaveMapping):
        problems += _unused_names(how, set(fqns))
    return out, problems


def _mapped(mapping: EnclaveMapping, fqn: str, required: bool = True
            ) -> tuple[str | None, Diagnostic | None]:
    """The enclave of ``fqn`` in ``mapping`` (None and why when there is not exactly one;
    no problem when there is none and ``required`` is false)."""
    by_name: dict[str, str] = {}  # enclave path -> the entry naming the node
    by_pattern: dict[str, str] = {}  # enclave path -> the first pattern matching the node
    for path, entries, _ in mapping.entries:
        for entry in entries:
            if not has_wildcard(entry):
                if entry == fqn:
                    by_name.setdefault(path, entry)
            elif fnmatch.fnmatchcase(fqn, entry):
                by_pattern.setdefault(path, entry)
    found = by_name or by_pattern
    if len(found) == 1:
        return next(iter(found)), None
    file = os.path.basename(mapping.file)
    if not found and not required:
        return None, None
    if not found:
        line, column = mapping.entries[0][2] if mapping.entries else (0, 0)
        return None, _problem(mapping.file, f'no enclave of {file} lists the node {fqn}: add it (or a '
                              'pattern matching it)', line, column)
    (first, first_entry), (second, second_entry) = list(found.items())[:2]
    line, column = mapping.place(second, second_entry)
    how = 'lists it by name' if by_name else 'has a pattern matching it'
    fix = 'list it under one enclave only' if by_name \
        else 'list it by name under the one it belongs to, or make the patterns disjoint'
    return None, _problem(mapping.file, f'the node {fqn} is in two enclaves of {file}: {first!r} and '
                          f'{second!r} each {how} ({first_entry!r} at line '
                          f'{mapping.place(first, first_entry)[0]}, {second_entry!r} here); a node runs '
                          f'with one identity: {fix}', line, column)


def _unused_names(mapping: EnclaveMapping, fqns: set[str]) -> list[Diagnostic]:
    """A warning for each node name of ``mapping`` that is no node of the system."""
    out = []
    for path, entries, _ in mapping.entries:
        for entry in entries:
            if not has_wildcard(entry) and entry not in fqns:
                line, column = mapping.place(path, entry)
                out.append(Diagnostic(
                    Severity.WARNING, f'{entry} (enclave {path!r}) is no node of the system: a '
                    'misspelt name leaves its node to a pattern or unassigned', (), mapping.file,
                    line, column, code='NODL613'))
    return out
