"""Validation of a document of a known kind: structure, then semantics."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.validation.interfaces import check_interface
from nodl.validation.kinds import Kind
from nodl.validation.names import check_parameter_name, check_ros_name
from nodl.validation.parameters import check_parameter, check_parameter_type, check_validator_name
from nodl.validation.references import check_reference
from nodl.validation.structure import Check, SchemaCompiler
from nodl.validation.types import check_action_type, check_msg_type, check_srv_type

__all__ = ['validate_data', 'FORMATS']

#: The ``format`` values of the shipped schemas, checked by Python code.
FORMATS = {
    'nodl-ros-name': check_ros_name,
    'nodl-msg-type': check_msg_type,
    'nodl-srv-type': check_srv_type,
    'nodl-action-type': check_action_type,
    'nodl-parameter-type': check_parameter_type,
    'nodl-parameter-name': check_parameter_name,
    'nodl-validator-name': check_validator_name,
    'nodl-reference': check_reference,
}


_compiler: SchemaCompiler | None = None


def _structure(kind: Kind) -> Check:
    # One compiler for every kind: it caches what the schema files share.
    global _compiler
    if _compiler is None:
        _compiler = SchemaCompiler(FORMATS)
    return _compiler.compile_ref(f'{kind.value}.schema.json')


def _check_node(data: Any, out: list[Diagnostic]) -> None:
    if not isinstance(data, dict):
        return
    check_interface(data.get('main'), ('main',), out)
    mixins = data.get('mixins')
    if not isinstance(mixins, list):
        return
    seen: dict[str, int] = {}
    for index, mixin in enumerate(mixins):
        path: DocPath = ('mixins', index)
        if isinstance(mixin, dict):
            check_interface(mixin, path, out)
        elif isinstance(mixin, str):
            if mixin in seen:
                out.append(Diagnostic(Severity.WARNING, f"mixin '{mixin}' is listed twice "
                                      f'(first as mixins[{seen[mixin]}])', path, code='NODL218'))
            else:
                seen[mixin] = index


def validate_data(data: Any, kind: Kind) -> list[Diagnostic]:
    """Every diagnostic for ``data`` read as a document of ``kind``.

    Diagnostics carry document paths but no positions; the caller places
    them in the source text (see :class:`~nodl.frontends.yaml_json.ParsedDocument`).
    """
    out: list[Diagnostic] = []
    _structure(kind)(data, (), out)
    if kind is Kind.PARAMETER:
        check_parameter(data, (), out)
    elif kind is Kind.INTERFACE:
        check_interface(data, (), out)
    else:
        _check_node(data, out)
    return out
