"""Turning what a caller hands us (text, bytes, a file object, a path) into text.

This is where the hostile-input limits that do not need parsing live: the
size limit and the UTF-8 requirement.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Union

from nodl_schema.diagnostics import Diagnostic, Severity

__all__ = ['MAX_BYTES', 'Source', 'SourceText', 'read_source', 'decode']

#: Documents larger than this are rejected before parsing.
MAX_BYTES = 10 * 1024 * 1024

#: Everything the loaders accept as a document.
Source = Union[str, bytes, bytearray, memoryview, IO[str], IO[bytes], os.PathLike]


@dataclass(frozen=True)
class SourceText:
    """A document's text and the name to use for it in diagnostics."""

    text: str
    file: str


def _problem(file: str, message: str, line: int = 0, column: int = 0) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, (), file, line, column)


def _too_large() -> str:
    return (f'document is larger than the limit of {MAX_BYTES:,} bytes (10 MB); '
            'split it into smaller definitions')


def decode(data: bytes, file: str) -> tuple[str | None, Diagnostic | None]:
    """Decode UTF-8 (a BOM is allowed); anything else is a clear error."""
    if len(data) > MAX_BYTES:
        return None, _problem(file, _too_large())
    if data[:2] in (b'\xff\xfe', b'\xfe\xff'):
        return None, _problem(file, 'document is UTF-16 encoded; NoDL files must be UTF-8', 1, 1)
    try:
        text = data.decode('utf-8')
    except UnicodeDecodeError as exc:
        line = data.count(b'\n', 0, exc.start) + 1
        column = exc.start - (data.rfind(b'\n', 0, exc.start) + 1) + 1
        return None, _problem(
            file,
            f'document is not valid UTF-8 (byte 0x{data[exc.start]:02x} cannot be decoded); '
            'save the file as UTF-8',
            line, column)
    if text.startswith('\ufeff'):
        text = text[1:]
    return text, None


def read_source(source: Source, file: str | None = None) -> tuple[SourceText | None, Diagnostic | None]:
    """Read ``source`` into text.

    ``str`` is document text (not a file name); use :class:`pathlib.Path` for
    a file.  Returns the text or a diagnostic saying why it cannot be used.
    I/O errors (a missing file, a directory) propagate as :class:`OSError`.
    """
    if isinstance(source, os.PathLike):
        path = Path(source)
        name = file or str(path)
        size = path.stat().st_size
        if size > MAX_BYTES:
            return None, _problem(name, _too_large())
        text, problem = decode(path.read_bytes(), name)
        return (SourceText(text, name), None) if text is not None else (None, problem)
    if isinstance(source, str):
        name = file or '<string>'
        if len(source) > MAX_BYTES:
            return None, _problem(name, _too_large())
        return SourceText(source[1:] if source.startswith('\ufeff') else source, name), None
    if isinstance(source, (bytes, bytearray, memoryview)):
        name = file or '<bytes>'
        text, problem = decode(bytes(source), name)
        return (SourceText(text, name), None) if text is not None else (None, problem)
    read = getattr(source, 'read', None)
    if read is None:
        raise TypeError(
            f'cannot read a NoDL document from {type(source).__name__}; '
            'pass text, bytes, a file object or a pathlib.Path')
    name = file or str(getattr(source, 'name', '<stream>'))
    content = read(MAX_BYTES + 1)
    if isinstance(content, str):
        if len(content) > MAX_BYTES:
            return None, _problem(name, _too_large())
        return SourceText(content[1:] if content.startswith('\ufeff') else content, name), None
    text, problem = decode(bytes(content), name)
    return (SourceText(text, name), None) if text is not None else (None, problem)
