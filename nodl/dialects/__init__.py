"""Dialects: files users already have, read as NoDL v2.

Two dialects are recognised by content (never by file name):

* ``include`` (:mod:`nodl.dialects.include`): the reference
  implementation's flat interface with ``include: [{ref: URI}, ...]`` (or
  ``includes:``) and an opaque ``codegen`` block.  It is read as a node
  definition: a built-in base description becomes ``base``, the other
  includes become ``mixins`` and the flat interface becomes ``main``.
* ``genparamlib`` (:mod:`nodl.dialects.genparamlib`): a
  generate_parameter_library file, a namespace of parameters.  It is not a
  NoDL document; it is recognised so that ``validate`` can say what it is,
  and converted (``nodl convert --from genparamlib``) or written
  (``nodl export genparamlib``).

:func:`adapt` is what :func:`nodl.loading.check_source` calls on
every parsed document; for a plain NoDL document it only looks at the
top-level keys and returns None.  (Legacy XML has its own frontend:
:mod:`nodl.frontends.legacy_xml`.)
"""

from __future__ import annotations

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

    from nodl.diagnostics import Diagnostic
    from nodl.frontends.yaml_json import ParsedDocument

__all__ = ['INCLUDE', 'GENPARAMLIB', 'DIALECTS', 'recognise', 'Adapted', 'adapt']

#: The dialect names, as ``nodl convert --from`` spells them.
INCLUDE = 'include'
GENPARAMLIB = 'genparamlib'
#: Every dialect read besides NoDL v2 itself: name -> what it is, for messages and help.
DIALECTS = {
    INCLUDE: "the reference implementation's include dialect (flat interface + include: [{ref: ...}])",
    GENPARAMLIB: 'a generate_parameter_library parameter file',
}


def recognise(data: Any) -> str | None:
    """The dialect ``data`` (a parsed document) is written in, or None for NoDL v2 (or anything else)."""
    if not isinstance(data, dict):
        return None
    from nodl.dialects.include import is_include_document

    if is_include_document(data):
        return INCLUDE
    if 'nodl_version' in data or 'type' in data:
        return None
    from nodl.dialects.genparamlib import is_genparamlib_document

    return GENPARAMLIB if is_genparamlib_document(data) else None


class Adapted:
    """A document of a dialect, read for the NoDL loader.

    ``data`` is the NoDL v2 document (None when the dialect is not a NoDL
    document at all); ``document`` places diagnostics about ``data`` in the
    original text, under the original paths; ``diagnostics`` are already
    placed (the dialect's own warning, errors in its own keys).
    """

    def __init__(self, dialect: str, data: Any, document: ParsedDocument,
                 diagnostics: list[Diagnostic], extra: dict[str, Any] | None = None) -> None:
        self.dialect = dialect
        self.data = data
        self.document = document
        self.diagnostics = diagnostics
        #: What the dialect carries that NoDL ignores (the ``codegen`` block).
        self.extra = extra or {}


def adapt(parsed: ParsedDocument, installed: bool = False) -> Adapted | None:
    """Read a parsed document of a dialect (None for a plain NoDL document).

    ``installed``: the document is what the reference implementation's
    ``ament_nodl_register`` installs (resource type ``nodl``): a node's flat
    interface, with or without ``include``, read as an include-dialect node
    without the warning that suggests converting it.  A NoDL v2 node
    definition (``base``, ``main`` or ``mixins``) is still read as one.
    """
    if installed and _installed_reference(parsed.data):
        from nodl.dialects.include import adapt_include

        return adapt_include(parsed, announce=False)
    dialect = recognise(parsed.data)
    if dialect is None:
        return None
    if dialect == INCLUDE:
        from nodl.dialects.include import adapt_include

        return adapt_include(parsed)
    from nodl.dialects.genparamlib import adapt_genparamlib

    return adapt_genparamlib(parsed)


def _installed_reference(data: Any) -> bool:
    """True for a document the reference registers (a mapping with nodl_version, no v2 node key)."""
    from nodl.validation.kinds import NODE_KEYS

    return (isinstance(data, dict) and 'nodl_version' in data
            and not any(key in data for key in NODE_KEYS))
