"""The reference implementation's ``include`` dialect, read as a NoDL v2 node definition.

The reference implementation and its code generators write a node as one
flat interface plus a list of documents to merge in::

    nodl_version: 2
    include:                                   # also spelled ``includes``
      - ref: nodl://rclcpp/node                # a built-in base description
      - ref: nodl://my_pkg/diagnostics         # a registered interface definition
      - ref: local://common/limits.nodl.yaml   # a file, relative to this one
    codegen: {...}                             # code generator settings: kept as they are
    publishers: [...]

NoDL v2 says the same with layers: a built-in base description becomes
``base``, every other include becomes a mixin (``local://FILE`` the path
``FILE``, which the ``file`` resolver reads relative to the including file),
and the flat interface becomes ``main``.  Diagnostics about the converted
document are placed back at the original keys and lines.
"""

from __future__ import annotations

import re
from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.frontends.remapped import RemappedDocument
from nodl.frontends.yaml_json import ParsedDocument
from nodl.vocabulary import INCLUDE_KEYS, NODE_KEYS
from nodl.wording import described, show

__all__ = [
    'BASE_DESCRIPTIONS',
    'CODEGEN_KEY',
    'INCLUDE_KEYS',
    'LOCAL_SCHEME',
    'IncludeReading',
    'is_include_document',
    'read_include',
    'remapped',
    'uri_problem',
]

#: The reference's built-in base descriptions and the NoDL v2 base each one is.
BASE_DESCRIPTIONS = {
    'nodl://rclcpp/node': 'node',
    'nodl://rclcpp_lifecycle/lifecycle_node': 'lifecycle_node',
}
#: The reference's scheme for files relative to the including document.
LOCAL_SCHEME = 'local://'
#: The code generators' block: kept (the node's ``codegen``), never interpreted.
CODEGEN_KEY = 'codegen'

_DIALECT_CODE = 'NODL851'
_URI_CODE = 'NODL818'
#: What the reference implementation's schema accepts as an include reference.
_URI = re.compile(r'[a-z][a-z0-9+.-]*://[^\s/][^\s]*')
_SCHEME_WORD = re.compile(r'[a-z][a-z0-9+.-]*')
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
    problem = uri_problem(ref)
    if problem is not None:
        out.append(Diagnostic(Severity.ERROR, problem, path + ('ref',), code=_URI_CODE))
        return None
    return ref


def uri_problem(ref: str) -> str | None:
    """What keeps ``ref`` from being an include reference (a ``scheme://body`` URI), or None.

    The reference implementation's schema takes a lower-case scheme, ``://``
    and a body that neither starts with ``/`` nor holds white space; whether
    the scheme has a resolver, and what its body must look like, is decided
    when the reference is resolved (and, for ``nodl://``, by the mixin rules).
    """
    if _URI.fullmatch(ref):
        return None
    shown = show(ref)
    scheme, sep, body = ref.partition(':')
    if sep and _SCHEME_WORD.fullmatch(scheme.lower()) and not body.startswith('//'):
        fixed = f"{scheme.lower()}://{body.lstrip('/')}"
        return (f"{shown} is not a URI: a scheme is followed by '://' (did you mean {show(fixed)}?)")
    if ref.startswith(':') or (sep and not scheme):
        return f"{shown} has no scheme before '://'; write nodl://PACKAGE/NAME or local://FILE"
    if '://' not in ref:
        path = ref.removeprefix('./')
        hint = ('an absolute path cannot name the same file on another machine; use '
                'nodl://PACKAGE/NAME' if ref.startswith('/') else f'write local://{path}')
        return f'{shown} is a path, not a URI ({hint})'
    if _SCHEME_WORD.fullmatch(scheme) is None:
        return (f'{shown} has an invalid scheme {show(scheme)}: a scheme is lower-case letters, '
                "digits, '+', '.' or '-', starting with a letter")
    if not body[2:]:
        return f'{shown} has nothing after the scheme; write nodl://PACKAGE/NAME or local://FILE'
    if body[2:].startswith('/'):
        return (f"{shown} has an empty authority (a '/' right after '://'); a local:// path is "
                'relative to the including file, a nodl:// reference is nodl://PACKAGE/NAME')
    return f'{shown} holds white space; a URI cannot'


def read_include(data: dict[str, Any], announce: bool = True) -> IncludeReading:
    """Read an include-dialect document (see :func:`is_include_document`) as a node definition.

    A document without ``include`` is read too (as a node of its flat interface
    alone): that is what the reference implementation registers in the ament
    index for a node that includes nothing.  ``announce=False`` leaves out the
    warning that names the dialect (for such an installed document, which its
    user cannot convert).  The ``codegen`` block is kept, as the node's ``codegen``.
    """
    present = [key for key in INCLUDE_KEYS if key in data]
    key = present[0] if present else INCLUDE_KEYS[0]
    out: list[Diagnostic] = []
    if len(present) > 1:
        out.append(Diagnostic(Severity.ERROR, "'include' and 'includes' are two spellings of one key; "
                              'list every include under one of them', (present[1],), anchor='key',
                              code=_BOTH_CODE))
    entries = data.get(key)
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
        mixins.append(ref.removeprefix(LOCAL_SCHEME))
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
    if CODEGEN_KEY in data:
        node[CODEGEN_KEY] = data[CODEGEN_KEY]
    node['main'] = main
    layers = ' + '.join(([f'base: {base}'] if base else []) + ([f'{len(mixins)} mixin(s)'] if mixins
                                                                else []) + ['main'])
    if announce and present:
        out.insert(0, Diagnostic(
            Severity.WARNING, f"this file is written in the reference implementation's '{key}' dialect; "
            f'it is read as a node definition ({layers}{", codegen kept" if CODEGEN_KEY in data else ""})'
            '; `nodl convert FILE -o DIR` rewrites it as base + mixins + main', (key,), anchor='key',
            code=_DIALECT_CODE))
    return IncludeReading(key, node, out, mixin_origins, base_origin, data.get(CODEGEN_KEY))


def remapped(parsed: ParsedDocument, reading: IncludeReading) -> ParsedDocument:
    """A document that places diagnostics about ``reading.data`` in ``parsed``'s text."""
    return RemappedDocument(parsed, reading)
