"""A dialect document read as NoDL, whose diagnostics land at the keys the user wrote.

The include dialect and generate_parameter_library files are rewritten into
NoDL data before they are checked.  A diagnostic about the rewritten data has
a path into that data; :class:`RemappedDocument` turns it into the path and
position of the original text, through the reading's ``original_path``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any, Protocol

    from nodl.diagnostics import Diagnostic, DocPath

    class Reading(Protocol):
        """What a dialect reader returns: the NoDL data and the way back to the original keys."""

        @property
        def data(self) -> dict[str, Any]: ...

        def original_path(self, path: DocPath) -> DocPath: ...

from nodl.frontends.yaml_json import ParsedDocument

__all__ = ['RemappedDocument']


class RemappedDocument(ParsedDocument):
    """The original parsed text, placing diagnostics about the rewritten data at the original keys."""

    def __init__(self, parsed: ParsedDocument, reading: Reading) -> None:
        super().__init__(parsed.source, reading.data, [], parsed.is_json)
        self._original = parsed
        self._reading = reading

    def position(self, path: DocPath, anchor: str = 'value') -> tuple[int, int]:
        """The position of ``path`` of the rewritten data in the original text."""
        return self._original.position(self._reading.original_path(path), anchor)

    def place(self, diagnostic: Diagnostic) -> Diagnostic:
        """Place a diagnostic about the rewritten data; its path becomes the original one."""
        if diagnostic.line:
            return diagnostic
        path = self._reading.original_path(diagnostic.path)
        line, column = self._original.position(path, diagnostic.anchor)
        return diagnostic.replace(path=path, file=self.source.file, line=line, column=column)
