"""The reference implementation's ``include`` dialect, read as a NoDL v2 node definition.

The reference implementation and its code generators write a node as one
flat interface plus a list of documents to merge in::

    nodl_version: 2
    include:                                   # also spelled ``includes``
      - ref: nodl://rclcpp/node                # a built-in base description
      - ref: nodl://my_pkg/diagnostics         # a registered interface definition
      - ref: local://common/limits.nodl.yaml   # a file, relative to this one
    codegen: {...}                             # code generator settings: kept, not read
    publishers: [...]

NoDL v2 says the same with layers: a built-in base description becomes
``base``, every other include becomes a mixin (``local://FILE`` the path
``FILE``, which the ``file`` resolver reads relative to the including file),
and the flat interface becomes ``main``.  Diagnostics about the converted
document are placed back at the original keys and lines.
"""

from __future__ import annotations

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

    from nodl_schema.dialects import Adapted

from nodl_schema.diagnostics import Diagnostic, DocPath, Severity
from nodl_schema.dialects.remapped import RemappedDocument
from nodl_schema.frontends.yaml_json import ParsedDocument
from nodl_schema.validation.kinds import INCLUDE_KEYS, NODE_KEYS

__all__ = ['INCLUDE_KEYS', 'BASE_DESCRIPTIONS', 'LOCAL_SCHEME', 'CODEGEN_KEY',
           'is_include_document', 'IncludeReading', 'read_include', 'remapped', 'adapt_include']

#: The reference's built-in base descriptions and the NoDL v2 base each one is.
BASE_DESCRIPTIONS = {
    'nodl://rclcpp/node': 'node',
    'nodl://rclcpp_lifecycle/lifecycle_node': 'lifecycle_node',
}
#: The reference's scheme for files relative to the including document.
LOCAL_SCHEME = 'local://'
#: The code generators' block: kept (``IncludeReading.codegen``), never read.
CODEGEN_KEY = 'codegen'

_DIALECT_CODE = 'NODL851'
_ENTRY_CODE = 'NODL852'
_BOTH_CODE = 'NODL853'


def is_include_document(data: Any) -> bool:
    """True if ``data`` is written in the include dialect (an include key, no v2 node key)."""
    return (isinstance(data, dict) and any(key in data for key in INCLUDE_KEYS)
            and not any(key in data for key in NODE_KEYS))


class IncludeReading:
    """An include-dialect document as a NoDL v2 node definition.

    ``data`` is the node definition; ``diagnostics`` (paths in the original
    document, not yet placed) are the dialect warning and errors in the
    include entries; :meth:`original_path` maps a path of ``data`` back to
    the original document.
    """

    def __init__(self, key: str, data: dict[str, Any], diagnostics: list[Diagnostic],
                 mixin_origins: list[int], base_origin: int | None, codegen: Any) -> None:
        #: ``include`` or ``includes``, as written.
        self.key = key
        self.data = data
        self.diagnostics = diagnostics
        self._mixin_origins = mixin_origins
        self._base_origin = base_origin
        #: The ``codegen`` block as written (None without one).
        self.codegen = codegen

    def original_path(self, path: DocPath) -> DocPath:
        """Where ``path`` of the node definition is in the original document."""
        if not path:
            return ()
        head = path[0]
        if head == 'main':
            return path[1:]
        if head == 'mixins':
            if len(path) > 1 and isinstance(path[1], int) and 0 <= path[1] < len(self._mixin_origins):
                return (self.key, self._mixin_origins[path[1]], 'ref') + path[2:]
            return (self.key,)
        if head == 'base':
            return (self.key,) if self._base_origin is None else (self.key, self._base_origin, 'ref')
        return path


def _entry_error(message: str, path: DocPath, anchor: str = 'value') -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, path, anchor=anchor, code=_ENTRY_CODE)


def _reference(entry: Any, path: DocPath, out: list[Diagnostic]) -> str | None:
    """The ``ref`` of one include entry, or None (with an error)."""
    from nodl_schema.validation.messages import described, show

    if isinstance(entry, str):
        out.append(_entry_error(f"an include entry is a mapping {{ref: URI}}; write "
                                f"'- ref: {entry}'", path))
        return None
    if not isinstance(entry, dict):
        out.append(_entry_error(f'an include entry is a mapping {{ref: URI}}, not {described(entry)}',
                                path))
        return None
    for key in entry:
        if key != 'ref':
            out.append(_entry_error(f"unknown key {show(key)} in an include entry; expected only 'ref'",
                                    path + (key,), 'key'))
    if 'ref' not in entry:
        out.append(_entry_error("an include entry needs 'ref' (nodl://PACKAGE/NAME or local://FILE)",
                                path))
        return None
    ref = entry['ref']
    if not isinstance(ref, str) or not ref:
        out.append(_entry_error(f"'ref' is a reference such as nodl://PACKAGE/NAME or local://FILE, "
                                f'not {described(ref)}', path + ('ref',)))
        return None
    return ref


def read_include(data: dict[str, Any]) -> IncludeReading:
    """Read an include-dialect document (see :func:`is_include_document`) as a node definition."""
    from nodl_schema.validation.messages import described

    present = [key for key in INCLUDE_KEYS if key in data]
    key = present[0]
    out: list[Diagnostic] = []
    if len(present) > 1:
        out.append(Diagnostic(Severity.ERROR, "'include' and 'includes' are two spellings of one key; "
                              'list every include under one of them', (present[1],), anchor='key',
                              code=_BOTH_CODE))
    entries = data[key]
    if entries is None:
        entries = []
    elif not isinstance(entries, list):
        out.append(_entry_error(f"'{key}' is a list of {{ref: URI}} entries, not {described(entries)}",
                                (key,)))
        entries = []
    base: str | None = None
    base_origin: int | None = None
    mixins: list[str] = []
    mixin_origins: list[int] = []
    for index, entry in enumerate(entries):
        ref = _reference(entry, (key, index), out)
        if ref is None:
            continue
        if ref in BASE_DESCRIPTIONS:
            # lifecycle_node's description includes node's: the larger one wins.
            if base is None or BASE_DESCRIPTIONS[ref] == 'lifecycle_node':
                base, base_origin = BASE_DESCRIPTIONS[ref], index
            continue
        mixins.append(ref[len(LOCAL_SCHEME):] if ref.startswith(LOCAL_SCHEME) else ref)
        mixin_origins.append(index)
    main: dict[str, Any] = {'nodl_version': 2}
    main.update((k, v) for k, v in data.items()
                if k not in INCLUDE_KEYS and k != CODEGEN_KEY and k != 'nodl_version')
    node: dict[str, Any] = {}
    if 'nodl_version' in data:
        node['nodl_version'] = data['nodl_version']
    if base is not None:
        node['base'] = base
    if mixins:
        node['mixins'] = mixins
    node['main'] = main
    layers = ' + '.join(([f'base: {base}'] if base else []) + ([f'{len(mixins)} mixin(s)'] if mixins
                                                                else []) + ['main'])
    out.insert(0, Diagnostic(
        Severity.WARNING, f"this file is written in the reference implementation's '{key}' dialect; "
        f'it is read as a node definition ({layers}){"; codegen is ignored" if CODEGEN_KEY in data else ""}'
        '; `nodl convert FILE -o DIR` rewrites it as base + mixins + main', (key,), anchor='key',
        code=_DIALECT_CODE))
    return IncludeReading(key, node, out, mixin_origins, base_origin, data.get(CODEGEN_KEY))


def remapped(parsed: ParsedDocument, reading: IncludeReading) -> ParsedDocument:
    """A document that places diagnostics about ``reading.data`` in ``parsed``'s text."""
    return RemappedDocument(parsed, reading)


def adapt_include(parsed: ParsedDocument) -> Adapted:
    """The loader's view of an include-dialect document (an :class:`~nodl_schema.dialects.Adapted`)."""
    from nodl_schema.dialects import INCLUDE, Adapted

    reading = read_include(parsed.data)
    placed = [parsed.place(d) for d in reading.diagnostics]
    return Adapted(INCLUDE, reading.data, remapped(parsed, reading), placed,
                   {CODEGEN_KEY: reading.codegen} if reading.codegen is not None else None)
