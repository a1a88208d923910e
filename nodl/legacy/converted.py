"""One converted legacy node, and where each part of its v2 document came from.

:class:`Converted` is what :func:`nodl.legacy.convert_legacy` returns
per ``<node>``: the v2 node definition (a plain dict), the conversion's
diagnostics, and a source map, ``origins``, from paths of the v2 document
(``('main', 'publishers', 0)``, ``('main', 'parameters', 'rate', 'type')``)
to the line and column, in the legacy XML file, of the element or attribute
each entry came from.  :func:`nodl.legacy.converted_document.converted_report`
checks the v2 document with that map, so what is said about the node (and
where its entities are) points into the XML file the user wrote.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from nodl.diagnostics import Diagnosed, Diagnostic, DocPath

if TYPE_CHECKING:  # pragma: no cover
    from nodl.frontends.legacy_xml import LegacyNode
    from nodl.model import Node

__all__ = ['Converted', 'Origins', 'origin_of']

#: v2 document path -> 1-based ``(line, column)`` in the legacy file.
Origins = dict[DocPath, tuple[int, int]]


def origin_of(origins: Origins, path: DocPath) -> tuple[int, int]:
    """Where ``path`` came from: its own position, else that of the nearest enclosing entry.

    A path the converter made up (``nodl_version``, ``base``, a default QoS)
    lands on the element of the entry holding it, or the ``<node>`` itself;
    ``(1, 1)`` only when the map knows nothing at all.
    """
    while path:
        found = origins.get(path)
        if found is not None:
            return found
        path = path[:-1]
    return origins.get((), (1, 1))


class Converted(Diagnosed):
    """One converted node: its file name, v2 node definition (a plain dict) and diagnostics.

    ``diagnostics`` are those of the conversion (placed in the legacy file);
    the legacy document's own diagnostics stay on the document.  ``origins``
    maps paths of ``data`` to their positions in the legacy file (see
    :func:`origin_of`).
    """

    __slots__ = ('file_name', 'data', 'diagnostics', 'source', 'node', 'origins')

    def __init__(self, file_name: str, data: dict[str, Any], diagnostics: list[Diagnostic],
                 source: str, node: LegacyNode, origins: Origins | None = None) -> None:
        self.file_name = file_name
        self.data = data
        self.diagnostics = diagnostics
        #: The legacy file it was converted from (as named in diagnostics).
        self.source = source
        self.node = node
        #: v2 document path -> (line, column) of the XML element or attribute it came from.
        self.origins: Origins = origins if origins is not None else {(): (node.line, node.column)}

    @property
    def document(self) -> Node | None:
        """The converted node definition as the typed model (None if it is not valid).

        The converter keeps a mapping while it works, so that whatever the v2
        schema refuses can be placed at the legacy element it came from; what
        is written is built from this model.
        """
        if not self.ok:
            return None
        from nodl.model import Node

        return Node.from_dict(self.data)

    def position(self, path: DocPath) -> tuple[int, int]:
        """``(line, column)`` in the legacy file of what ``path`` of ``data`` came from."""
        return origin_of(self.origins, path)

    def __repr__(self) -> str:
        return (f'Converted(file_name={self.file_name!r}, source={self.source!r}, '
                f'diagnostics={len(self.diagnostics)})')
