"""The reference API's schema and validation, done by the toolkit's validator.

:func:`load_schema` is the document schema in the reference implementation's
shape (one flat interface, ``include`` and ``codegen``), made from the
toolkit's own schema files; :func:`validate` checks a plain dict against it
with the toolkit's validator, so an invalid document is refused with
:class:`ValidationError`, which carries the toolkit's coded diagnostics.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING

from nodl.frontends.include import BASE_DESCRIPTIONS, uri_problem
from nodl.frontends.source import read_source
from nodl.frontends.yaml_json import parse_document
from nodl.schemas import bundled_schema
from nodl.validation.engine import FORMATS
from nodl.validation.interfaces import check_interface
from nodl.validation.structure import SchemaCompiler
from nodl.wording import described, kind_of

if TYPE_CHECKING:
    from typing import Any

    from nodl.frontends.source import Source
    from nodl.frontends.yaml_json import ParsedDocument
    from nodl.validation.structure import Check

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.diagnostics import ValidationError as _NodlValidationError

__all__ = ['ValidationError', 'load_schema', 'validate', 'check_text']

#: The name the schema's checks and its ``$ref`` s are compiled under.
_SCHEMA_NAME = 'nodl_schema:document'
#: A format of this schema only: an include reference, ``<scheme>://<body>``.
_URI_FORMAT = 'nodl-include-uri'


class ValidationError(_NodlValidationError):
    """An invalid NoDL document (where the reference raises jsonschema's ``ValidationError``).

    A :class:`ValueError` carrying every diagnostic (:attr:`diagnostics`, each
    with a code and, for a document read from a file, ``file:line:col``).
    :attr:`message` and :attr:`path` describe the first error, as the
    attributes of the same names do on jsonschema's error.
    """

    @property
    def message(self) -> str:
        """The first error's message."""
        first = (self.errors or self.diagnostics)[:1]
        return first[0].message if first else ''

    @property
    def path(self) -> DocPath:
        """Where the first error is in the document (keys and list indices)."""
        first = (self.errors or self.diagnostics)[:1]
        return first[0].path if first else ()


_schema: dict[str, Any] | None = None
_check: Check | None = None


def load_schema() -> dict[str, Any]:
    """The NoDL document schema in the reference implementation's shape (draft 7).

    Self-contained (every ``$ref`` points into its own ``definitions``) and
    made once: every call returns the same dict, which must not be modified.
    """
    global _schema
    if _schema is None:
        _schema = _reference_shape()
    return _schema


def _reference_shape() -> dict[str, Any]:
    bundled = bundled_schema('interface')
    definitions: dict[str, Any] = bundled['definitions']
    interface = copy.deepcopy(definitions['interface'])
    properties: dict[str, Any] = interface['properties']
    properties['include'] = {
        'type': 'array',
        'description': 'Documents merged into this one, each a {ref: URI}; resolved recursively. '
                       'Including one document twice, or two documents declaring the same entity '
                       'name in one category, is an error.',
        'items': {'$ref': '#/definitions/reference'},
    }
    definitions['reference'] = {
        'type': 'object',
        'additionalProperties': False,
        'required': ['ref'],
        'properties': {'ref': {
            'type': 'string',
            'format': _URI_FORMAT,
            # For other validators (the format is the toolkit's): '<scheme>://<body>'.
            'pattern': r'^[a-z][a-z0-9+.-]*://[^\s/][^\s]*$',
            'description': 'A URI whose scheme picks a registered resolver: nodl://PACKAGE/NAME '
                           '(the ament index), local://PATH (relative to the including file).',
        }},
    }
    lifecycle = next(ref for ref, base in BASE_DESCRIPTIONS.items() if base == 'lifecycle_node')
    interface['x-nodl-key-hints'] = {
        'base': f"'base' is a NoDL v2 node key; here a base is included: "
                f"include: [{{ref: {lifecycle}}}]",
        'main': "'main' is a NoDL v2 node key; here the interface is written at the top level",
        'mixins': "'mixins' is a NoDL v2 node key; here other documents are listed under "
                  "include: [{ref: URI}]",
        'includes': "the key is 'include' (a list of {ref: URI})",
    }
    schema: dict[str, Any] = {
        '$schema': 'http://json-schema.org/draft-07/schema#',
        '$id': 'urn:nodl:schema:2:reference-document',
        'title': 'NoDL document (reference implementation layout)',
        'description': "A node's interface as one document: parameters and endpoints at the top "
                       'level, other documents merged in with include.',
    }
    schema.update(interface)
    schema['definitions'] = definitions
    return schema


def _uri_check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
    if not isinstance(value, str):
        out.append(Diagnostic(Severity.ERROR, f"'ref' is a URI such as nodl://PACKAGE/NAME or "
                              f'local://FILE, not {described(value)}', path, code='NODL852'))
        return
    problem = uri_problem(value)
    if problem is not None:
        out.append(Diagnostic(Severity.ERROR, problem, path, code='NODL818'))


def _compiled() -> Check:
    global _check
    if _check is None:
        schema = load_schema()

        class _Compiler(SchemaCompiler):
            """Resolves this schema's own ``$ref`` s in the dict rather than in a shipped file."""

            def compile_ref(self, file_name: str, pointer: str = '') -> Check:
                if file_name != _SCHEMA_NAME:
                    return super().compile_ref(file_name, pointer)
                node: Any = schema
                for part in [p for p in pointer.split('/') if p]:
                    node = node[part]
                cell: list[Check] = []
                key = (file_name, pointer)
                known = self._compiled.get(key)
                if known is not None:
                    return known
                self._compiled[key] = lambda v, p, o: cell[0](v, p, o)
                cell.append(self.compile(node, file_name))
                self._compiled[key] = cell[0]
                return cell[0]

        _check = _Compiler({**FORMATS, _URI_FORMAT: _uri_check}).compile_ref(_SCHEMA_NAME)
    return _check


def diagnose(data: Any) -> list[Diagnostic]:
    """Every diagnostic for ``data`` read as a document (paths, no positions)."""
    if not isinstance(data, dict):
        return [Diagnostic(Severity.ERROR, f'a NoDL document is a mapping at the top level, not '
                           f'{kind_of(data)}', (), code='NODL011')]
    out: list[Diagnostic] = []
    _compiled()(data, (), out)
    check_interface(data, (), out)
    return out


def validate(data: dict[str, Any]) -> None:
    """Validate a plain dict as a NoDL document; raises :class:`ValidationError` on an error.

    Warnings (a parameter without a description, ...) do not make it invalid.
    """
    diagnostics = [d.at('<dict>', 0, 0) for d in diagnose(data)]
    if any(d.severity is Severity.ERROR for d in diagnostics):
        raise ValidationError(diagnostics)


def check_text(source: Source, file: str | None = None) -> Any:
    """Read, parse and validate document text (``file`` names it in diagnostics); returns the data.

    A path (:class:`os.PathLike`) is read as the file.  Raises :class:`ValidationError`,
    with the diagnostics at ``file:line:col``, for text that is not a valid document.
    """
    text, problem = read_source(source, file)
    if text is None:
        assert problem is not None
        raise ValidationError([problem])
    parsed: ParsedDocument = parse_document(text)
    if parsed.diagnostics:
        raise ValidationError(list(parsed.diagnostics))
    placed = sorted((parsed.place(d) for d in diagnose(parsed.data)),
                    key=lambda d: (d.line, d.column))
    if any(d.severity is Severity.ERROR for d in placed):
        raise ValidationError(placed)
    return parsed.data
