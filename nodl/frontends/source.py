"""Turning what a caller hands us (text, bytes, a file object, a path) into text.

This is where the hostile-input limits that do not need parsing live: the
size limit and the UTF-8 requirement.
"""

from __future__ import annotations

import errno
import os
from collections import namedtuple
from stat import S_ISDIR, S_ISREG
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import IO, Any

from nodl.diagnostics import Diagnostic, Severity

__all__ = ['MAX_BYTES', 'Source', 'SourceText', 'read_source', 'read_limited', 'read_regular', 'decode']

#: Documents larger than this are rejected before parsing.
MAX_BYTES = 10 * 1024 * 1024
# What read_limited asks for at a time once past what a file said it holds (a FIFO, a device).
_CHUNK = 1024 * 1024

#: Everything the loaders accept as a document.
if TYPE_CHECKING:
    Source = str | bytes | bytearray | memoryview | IO[str] | IO[bytes] | os.PathLike[str]
else:
    Source = object


class SourceText(namedtuple('SourceText', ['text', 'file'])):
    """A document's text and the name to use for it in diagnostics."""

    __slots__ = ()


def _problem(file: str, message: str, line: int = 0, column: int = 0,
             code: str = 'NODL002') -> Diagnostic:
    # Every problem found here is about the encoding (NODL002) except the size limit (NODL001).
    return Diagnostic(Severity.ERROR, message, (), file, line, column, code=code)


def _too_large() -> str:
    # Every kind of file is read here (definitions, launch, parameter and policy files):
    # the advice fits them all.
    return (f'file is larger than the limit of {MAX_BYTES:,} bytes (10 MB) that nodl reads; '
            'split it (a definition into mixins, a launch file into includes, a parameter '
            'file into several files)')


def _text_too_large(text: str) -> bool:
    """True if ``text`` is more than :data:`MAX_BYTES` bytes once encoded as UTF-8."""
    size = len(text)
    if size > MAX_BYTES:
        return True
    if 4 * size <= MAX_BYTES or text.isascii():
        return False
    return len(text.encode('utf-8', 'surrogatepass')) > MAX_BYTES


def _check_text(text: str, file: str) -> tuple[SourceText | None, Diagnostic | None]:
    """Apply the limits that :func:`decode` applies to bytes to text given as ``str``."""
    if _text_too_large(text):
        return None, _problem(file, _too_large(), code='NODL001')
    if text.startswith('\ufeff'):
        text = text[1:]
    start = _lone_surrogate(text)
    if start >= 0:
        line = text.count('\n', 0, start) + 1
        column = start - (text.rfind('\n', 0, start) + 1) + 1
        return None, _problem(
            file,
            f'document contains a lone surrogate (U+{ord(text[start]):04X}), which is not '
            'valid Unicode text; NoDL files are UTF-8',
            line, column)
    return SourceText(text, file), None


def _lone_surrogate(text: str) -> int:
    """The index of the first lone surrogate in ``text`` (a Python ``str`` can hold
    them, UTF-8 text cannot), or -1."""
    if text.isascii():
        return -1
    try:
        text.encode('utf-8')  # only a surrogate cannot be encoded
    except UnicodeEncodeError as exc:
        return exc.start
    return -1


def _read_stream(read: Callable[[int], Any]) -> Any:
    """Read up to ``MAX_BYTES + 1`` units, also from streams that return short reads."""
    first = read(MAX_BYTES + 1)
    if not first:
        return first if first is not None else b''
    chunks = [first]
    total = len(first)
    while total <= MAX_BYTES:
        more = read(MAX_BYTES + 1 - total)
        if not more:
            break
        chunks.append(more)
        total += len(more)
    if len(chunks) == 1:
        return first
    return ''.join(chunks) if isinstance(first, str) else b''.join(bytes(c) for c in chunks)


def read_limited(path: str | os.PathLike[str]) -> bytes:
    """A file's bytes, read only up to the size limit plus one byte.

    A FIFO or a device such as /dev/zero reports size 0 and may never end;
    the caller's :func:`decode` rejects what is over the limit.
    """
    fd = os.open(path, os.O_RDONLY)
    try:
        status = os.fstat(fd)
        if S_ISDIR(status.st_mode):  # the error open() gives
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), os.fspath(path))
        return _read_open(fd, status)
    finally:
        os.close(fd)


def read_regular(path: str | os.PathLike[str]) -> bytes | None:
    """A regular file's bytes as :func:`read_limited` reads them; None if there is no such
    file or it is not a regular file (a directory, a FIFO, a device).  One system call
    fewer than asking first (an analysis reads a thousand definitions this way)."""
    try:
        # O_NONBLOCK: opening a FIFO to see what it is must not wait for a writer
        fd = os.open(path, os.O_RDONLY | getattr(os, 'O_NONBLOCK', 0))
    except (FileNotFoundError, NotADirectoryError):
        return None
    try:
        status = os.fstat(fd)
        return _read_open(fd, status) if S_ISREG(status.st_mode) else None
    finally:
        os.close(fd)


def _read_open(fd: int, status: os.stat_result) -> bytes:
    # Through the descriptor, asking first for what the file says it holds (plus a byte, to
    # see that it grew): a read allocates all it asks for, and asking a small definition
    # for the whole limit (10 MB) cost more than the rest of reading it.  Having read all
    # a regular file holds ends the reading (no read only to see the end).
    size = status.st_size if S_ISREG(status.st_mode) else -1
    chunks = []
    total = 0
    ask = min(status.st_size, MAX_BYTES) + 1
    while total <= MAX_BYTES:
        chunk = os.read(fd, min(ask, MAX_BYTES + 1 - total))
        if not chunk:
            break
        chunks.append(chunk)
        total += len(chunk)
        if total == size:
            break
        ask = _CHUNK
    return chunks[0] if len(chunks) == 1 else b''.join(chunks)


def decode(data: bytes, file: str) -> tuple[str | None, Diagnostic | None]:
    """Decode UTF-8 (a BOM is allowed); anything else is a clear error."""
    if len(data) > MAX_BYTES:
        return None, _problem(file, _too_large(), code='NODL001')
    if data[:2] in (b'\xff\xfe', b'\xfe\xff'):
        return None, _problem(file, 'document is UTF-16 encoded; NoDL files must be UTF-8', 1, 1)
    try:
        text = data.decode('utf-8')
    except UnicodeDecodeError as exc:
        line = data.count(b'\n', 0, exc.start) + 1
        line_start = data.rfind(b'\n', 0, exc.start) + 1
        # Columns count characters of the text without its BOM, as in every
        # other diagnostic; everything before the first bad byte is valid UTF-8.
        before = data[line_start:exc.start].decode('utf-8')
        column = len(before[1:] if line_start == 0 and before.startswith('\ufeff') else before) + 1
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
        name = file or os.fspath(source)
        if os.stat(source).st_size > MAX_BYTES:
            return None, _problem(name, _too_large(), code='NODL001')
        text, problem = decode(read_limited(source), name)
        return (SourceText(text, name), None) if text is not None else (None, problem)
    if isinstance(source, str):
        return _check_text(source, file or '<string>')
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
    content = _read_stream(read)
    if isinstance(content, str):
        return _check_text(content, name)
    text, problem = decode(bytes(content), name)
    return (SourceText(text, name), None) if text is not None else (None, problem)
