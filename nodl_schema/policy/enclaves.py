"""Which enclave each node runs in: one per node, one per namespace, or a mapping file.

* ``node`` (the default): the enclave path is the node's fully qualified name,
  so every node gets its own identity and exactly its own permissions;
* ``namespace``: the nodes of one namespace share an enclave named after it;
* a mapping file (YAML): ``enclave path: [node name or pattern, ...]``,
  e.g. ``/robot/sensors: [/robot/lidar, /robot/camera_*]``.  Patterns are
  shell-style (``*``, ``?``, ``[...]``) on fully qualified node names; the
  first enclave (in file order) with a matching entry wins.  A node no entry
  matches is an error (NODL610), as is an enclave path that is not a valid
  absolute ROS namespace, which is what SROS 2 requires of enclave names.

Several nodes in one enclave keep a profile each; DDS grants the enclave the
union of its profiles.
"""

from __future__ import annotations

import fnmatch
import os
from typing import Iterable, NamedTuple

from nodl_schema.diagnostics import Diagnostic, Severity

__all__ = ['ENCLAVE_MODES', 'EnclaveMapping', 'load_enclave_mapping', 'assign_enclaves',
           'enclave_path_error']

#: The built-in ways to cut a system into enclaves.
ENCLAVE_MODES = ('node', 'namespace')


def enclave_path_error(path: str) -> str | None:
    """Why ``path`` is not a valid enclave name (None: it is)."""
    from nodl_schema.naming import namespace_error

    if not path.startswith('/'):
        return 'an enclave path is absolute (starts with /)'
    return namespace_error(path)


class EnclaveMapping(NamedTuple):
    """A mapping file: ``(enclave path, patterns, (line, column))`` in file order."""

    file: str
    entries: list[tuple[str, list[str], tuple[int, int]]]


def _problem(file: str, message: str, line: int = 0, column: int = 0) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, (), file, line, column, code='NODL610')


def load_enclave_mapping(path: str) -> tuple[EnclaveMapping | None, list[Diagnostic]]:
    """Read a mapping file; (None, problems) if it cannot be used.  OSError if unreadable."""
    from pathlib import Path

    from nodl_schema.frontends.source import read_source
    from nodl_schema.frontends.yaml_json import parse_document

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
        entries.append((key, patterns, (line, column)))
    if problems:
        return None, problems
    return EnclaveMapping(path, entries), []


def assign_enclaves(fqns: Iterable[str], how: str | EnclaveMapping = 'node'
                    ) -> tuple[dict[str, str], list[Diagnostic]]:
    """Node fully qualified name -> enclave path, and the nodes no mapping entry matches."""
    out: dict[str, str] = {}
    problems: list[Diagnostic] = []
    for fqn in fqns:
        if isinstance(how, EnclaveMapping):
            found = next((path for path, patterns, _ in how.entries
                          if any(fnmatch.fnmatchcase(fqn, p) for p in patterns)), None)
            if found is None:
                problems.append(_problem(how.file, f'no enclave of {os.path.basename(how.file)} '
                                         f'lists the node {fqn}: add it (or a pattern matching it)'))
                continue
            out[fqn] = found
        elif how == 'namespace':
            out[fqn] = fqn.rsplit('/', 1)[0] or '/'
        elif how == 'node':
            out[fqn] = fqn
        else:
            raise ValueError(f'unknown enclave mode {how!r}; expected one of: {", ".join(ENCLAVE_MODES)} '
                             'or a mapping file')
    return out, problems
