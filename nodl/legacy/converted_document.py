"""A converted legacy node checked as NoDL v2, placed in the legacy XML file.

A registered legacy node is converted in memory and composed like any node
definition.  What is said about it (a composition error, an entity's
location) is found as a path into the v2 data; :class:`ConvertedDocument`
places that path at the XML element or attribute it came from, through the
conversion's source map (:attr:`Converted.origins
<nodl.legacy.converted.Converted.origins>`), the way
:class:`~nodl.frontends.remapped.RemappedDocument` places a dialect's
rewritten data at the keys the user wrote.  There is no v2 text to point at:
the file is the XML file itself.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nodl.frontends.source import SourceText
from nodl.frontends.yaml_json import ParsedDocument

if TYPE_CHECKING:
    from nodl.diagnostics import DocPath
    from nodl.legacy.converted import Converted
    from nodl.loading import CheckedSource

__all__ = ['ConvertedDocument', 'converted_report']


class ConvertedDocument(ParsedDocument):
    """The v2 data of a converted node, placing every path in the legacy file it came from.

    A path with no position of its own (what the converter added, such as
    ``nodl_version`` or a default QoS) lands on the enclosing entry's element,
    or the ``<node>``.  Keys and values are both placed at the element (or
    attribute): XML has one position for both.
    """

    def __init__(self, converted: Converted) -> None:
        # No text: nothing is ever parsed or composed, every position comes from the map.
        super().__init__(SourceText('', converted.source), converted.data, [], is_json=False)
        self._converted = converted

    def position(self, path: DocPath, anchor: str = 'value') -> tuple[int, int]:
        """``(line, column)`` in the legacy file of the element or attribute ``path`` came from."""
        return self._converted.position(path)


def converted_report(converted: Converted) -> CheckedSource:
    """The converted node checked as a v2 node definition, placed in the legacy file.

    What :func:`~nodl.loading.check_source` gives for the v2 text of
    the conversion, except that ``file`` is the legacy file and every
    diagnostic (and every entity of the composed node) points into it.
    """
    from nodl.loading import CheckedSource
    from nodl.validation import Kind, validate_data

    # The converter writes a node definition (base and main) by construction: no kind to detect.
    data = converted.data
    return CheckedSource(converted.source, Kind.NODE, data, validate_data(data, Kind.NODE),
                  ConvertedDocument(converted))
