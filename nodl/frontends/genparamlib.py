"""The generate_parameter_library frontend's reader: such a file recognised and read as NoDL.

A generate_parameter_library file has one top-level key, the namespace of the
generated code, holding nested mappings; a mapping whose ``type`` is a
string is a parameter, named by the keys below the namespace joined with
dots::

    turtle_controller:            # the namespace (not part of the names)
      speed:                      # parameter 'speed'
        type: double
        default_value: 1.0
      pid:
        p: {type: double}         # parameter 'pid.p'
      __map_joints:               # one set of parameters per element of 'joints'
        gain: {type: double}

Its parameter shape is NoDL's (NoDL borrowed it), so every key of a parameter
is carried over as written and checked by the NoDL rules.  Parameters under
``__map_<key>`` segments have no NoDL form yet: they are left out and listed
in one warning.  :func:`nodl.dialects.genparamlib.export_genparamlib` writes the other direction.
"""

from __future__ import annotations

import re
from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.frontends.remapped import RemappedDocument
from nodl.frontends.yaml_json import ParsedDocument
from nodl.vocabulary import INTERFACE_KEYS, NODE_KEYS
from nodl.wording import described, show

__all__ = [
    'IDENTIFIER',
    'MAP_PREFIX',
    'GenParamReading',
    'is_genparamlib_document',
    'not_nodl',
    'read_genparamlib',
    'remapped',
]

#: The segment prefix of generate_parameter_library's mapped parameters.
MAP_PREFIX = '__map_'
#: What a namespace and every segment of a parameter name must be in the generated code.
IDENTIFIER = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')

_NOT_NODL = 'NODL861'
_MAP_SKIPPED = 'NODL862'
_SHAPE = 'NODL863'


def _is_parameter(value: Any) -> bool:
    return isinstance(value, dict) and isinstance(value.get('type'), str)


def _has_parameter(value: Any, depth: int = 0) -> bool:
    if _is_parameter(value):
        return True
    return isinstance(value, dict) and depth < 100 and any(
        _has_parameter(v, depth + 1) for v in value.values())


def is_genparamlib_document(data: Any) -> bool:
    """True if ``data`` is a generate_parameter_library file.

    A mapping without ``nodl_version`` or ``type`` and without any key of a
    NoDL interface or node, whose values are all mappings, with at least one
    parameter (a mapping with a string ``type``) somewhere beneath.
    """
    if not isinstance(data, dict) or not data or 'nodl_version' in data or 'type' in data:
        return False
    if any(key in data for key in INTERFACE_KEYS + NODE_KEYS):
        return False
    return all(isinstance(v, dict) for v in data.values()) and _has_parameter(data)


class GenParamReading:
    """A generate_parameter_library file as a NoDL interface definition.

    ``data`` is the interface definition; ``diagnostics`` have paths in the
    original file (not yet placed); ``skipped`` names the parameters under
    ``__map_`` segments that were left out.
    """

    def __init__(self, namespace: str, data: dict[str, Any], diagnostics: list[Diagnostic],
                 origins: dict[str, DocPath], skipped: list[str]) -> None:
        #: The top-level key: the namespace of the generated code.
        self.namespace = namespace
        self.data = data
        self.diagnostics = diagnostics
        self._origins = origins
        self.skipped = skipped

    def original_path(self, path: DocPath) -> DocPath:
        """Where ``path`` of the interface definition is in the original file."""
        if len(path) >= 2 and path[0] == 'parameters' and path[1] in self._origins:
            return self._origins[path[1]] + path[2:]
        return (self.namespace,) if self.namespace else ()


def _leaves(value: Any, names: list[str], out: list[str]) -> None:
    if _is_parameter(value):
        out.append('.'.join(names))
    elif isinstance(value, dict):
        for key, child in value.items():
            _leaves(child, names + [str(key)], out)


def _walk(mapping: dict[Any, Any], names: list[str], path: DocPath, parameters: dict[str, Any],
          origins: dict[str, DocPath], skipped: list[str], first_map: list[DocPath],
          out: list[Diagnostic]) -> None:
    for key, value in mapping.items():
        here = path + (key,)
        if not isinstance(key, str):
            out.append(Diagnostic(Severity.ERROR, f'{show(key)} is not a name; parameter and '
                                  'namespace names are strings', here, anchor='key', code=_SHAPE))
            continue
        if key.startswith(MAP_PREFIX):
            before = len(skipped)
            _leaves(value, names + [key], skipped)
            if len(skipped) > before and not first_map:
                first_map.append(here)
            continue
        if _is_parameter(value):
            name = '.'.join(names + [key])
            parameters[name] = value
            origins[name] = here
        elif isinstance(value, dict):
            _walk(value, names + [key], here, parameters, origins, skipped, first_map, out)
        else:
            out.append(Diagnostic(
                Severity.ERROR, f'{show(key)} must be a parameter (a mapping with a type) or a '
                f'namespace of parameters (a mapping), not {described(value)}', here, code=_SHAPE))


def read_genparamlib(data: dict[str, Any]) -> GenParamReading:
    """Read a generate_parameter_library file as an interface definition."""
    out: list[Diagnostic] = []
    keys = list(data)
    namespace = str(keys[0]) if keys else ''
    for extra in keys[1:]:
        out.append(Diagnostic(Severity.ERROR, f"a generate_parameter_library file has one top-level "
                              f"key, the namespace of the generated code ('{namespace}'); move "
                              f"'{extra}' under it or into a file of its own", (extra,), anchor='key',
                              code=_SHAPE))
    if namespace and not IDENTIFIER.fullmatch(namespace):
        out.append(Diagnostic(Severity.ERROR, f"the namespace '{namespace}' is not a C++ identifier",
                              (keys[0],), anchor='key', code=_SHAPE))
    parameters: dict[str, Any] = {}
    origins: dict[str, DocPath] = {}
    skipped: list[str] = []
    first_map: list[DocPath] = []
    root = data[keys[0]] if keys else {}
    if isinstance(root, dict):
        _walk(root, [], (keys[0],), parameters, origins, skipped, first_map, out)
    if skipped:
        out.append(Diagnostic(
            Severity.WARNING, f'{len(skipped)} parameter(s) under __map_ segments cannot be '
            f'expressed in NoDL yet and are not converted: {", ".join(skipped)}', first_map[0],
            anchor='key', code=_MAP_SKIPPED))
    interface: dict[str, Any] = {'nodl_version': 2}
    if parameters:
        interface['parameters'] = parameters
    return GenParamReading(namespace, interface, out, origins, skipped)


def remapped(parsed: ParsedDocument, reading: GenParamReading) -> ParsedDocument:
    """A document that places diagnostics about ``reading.data`` in ``parsed``'s text."""
    return RemappedDocument(parsed, reading)


def not_nodl(reading: GenParamReading) -> Diagnostic:
    """The error that says a generate_parameter_library file is not a NoDL document (unplaced)."""
    count = len(reading.data.get('parameters', {})) + len(reading.skipped)
    return Diagnostic(
        Severity.ERROR, f"this is a generate_parameter_library file (namespace '{reading.namespace}', "
        f'{count} parameter(s)), not a NoDL document; convert it with '
        '`nodl convert --from genparamlib FILE -o DIR`', (reading.namespace,), anchor='key',
        code=_NOT_NODL)
