"""generate_parameter_library files written from NoDL (``nodl export genparamlib``).

The reading direction (recognising such a file, reading it as an interface
definition) is the generate_parameter_library frontend,
:mod:`nodl.frontends.genparamlib`; this is the writing one.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.genparamlib import IDENTIFIER, MAP_PREFIX
from nodl.validation.parameters import BUILTIN_VALIDATORS

if TYPE_CHECKING:
    from nodl.model import ParameterDefinition

__all__ = ['IDENTIFIER', 'Exported', 'export_genparamlib']

_NOT_EXPORTED = 'NODL864'


class Exported:
    """What :func:`export_genparamlib` produced: the document and what could not be written."""

    def __init__(self, data: dict[str, Any], diagnostics: list[Diagnostic]) -> None:
        #: ``{namespace: {...}}``, ready to dump as YAML.
        self.data = data
        #: Warnings for parameters left out (no generate_parameter_library form).
        self.diagnostics = diagnostics

    def text(self, header: str = '') -> str:
        """The document as YAML (names and descriptions escaped by the YAML emitter)."""
        from nodl.text_safety import dump_yaml, visible

        body = dump_yaml(self.data)
        comment = ''.join(f'# {visible(line)}\n' for line in header.splitlines())
        return comment + body


def _genparamlib_parameter(param: ParameterDefinition) -> dict[str, Any]:
    out = param.to_dict()
    if param.validation:
        # generate_parameter_library calls any name without '<>' as a custom function.
        out['validation'] = {(f'{key}<>' if key in BUILTIN_VALIDATORS else key): args
                             for key, args in param.validation.items()}
    return out


def export_genparamlib(parameters: Mapping[str, ParameterDefinition], namespace: str,
                       file: str = '<definition>') -> Exported:
    """The parameters in generate_parameter_library's format, under ``namespace``.

    Dotted names become nested namespaces; built-in validators are written
    with ``<>``.  A parameter that generate_parameter_library cannot hold (type
    ``none``, a name segment that is not an identifier, a name that is both a
    parameter and a namespace) is left out with a warning.
    """
    if not IDENTIFIER.fullmatch(namespace):
        raise ValueError(f"the namespace '{namespace}' is not a C++ identifier")
    root: dict[str, Any] = {}
    out: list[Diagnostic] = []
    leaves: set[int] = set()

    def skip(name: str, why: str) -> None:
        out.append(Diagnostic(Severity.WARNING, f"parameter '{name}' is not exported: {why}",
                              ('parameters', name), file, code=_NOT_EXPORTED))

    for name, param in parameters.items():
        segments = name.split('.')
        if param.type == 'none':
            skip(name, "generate_parameter_library has no type 'none'")
            continue
        bad = [s for s in segments if not IDENTIFIER.fullmatch(s) or s.startswith(MAP_PREFIX)]
        if bad:
            skip(name, f"'{bad[0]}' is not a C++ identifier, which every part of a "
                 'generate_parameter_library name must be')
            continue
        node = root
        clash = None
        for depth, segment in enumerate(segments[:-1]):
            child = node.setdefault(segment, {})
            if id(child) in leaves:
                clash = '.'.join(segments[:depth + 1])
                break
            node = child
        if clash is None and segments[-1] in node:
            clash = name
        if clash is not None:
            skip(name, f"'{clash}' is both a parameter and a namespace, which "
                 'generate_parameter_library cannot hold')
            continue
        node[segments[-1]] = _genparamlib_parameter(param)
        leaves.add(id(node[segments[-1]]))
    return Exported({namespace: root}, out)
