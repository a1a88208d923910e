"""Reading documents into text (nodl.frontends.source).

Covers every kind of input the loaders accept (str, bytes, bytearray,
memoryview, text and binary file objects, pathlib.Path and other
os.PathLike), the UTF-8 rules (BOM allowed, UTF-16 and invalid UTF-8
rejected with a position), the 10 MB size limit for every kind of input, and
the errors that propagate (TypeError, OSError).
"""

from __future__ import annotations

import io
import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from nodl import ValidationError, check_source, load_nodl
from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.source import MAX_BYTES, SourceText, decode, read_source

FRONTENDS = Path(__file__).parent / 'fixtures' / 'frontends'
REPO = Path(__file__).resolve().parent.parent

DOC = 'type: string\ndescription: "café €"\n'
BOM = '\ufeff'
UTF8_BOM = b'\xef\xbb\xbf'
TOO_LARGE = ('file is larger than the limit of 10,485,760 bytes (10 MB) that nodl reads; '
             'split it (a definition into mixins, a launch file into includes, a parameter '
             'file into several files)')


def read_ok(source, file=None) -> SourceText:  # type: ignore[no-untyped-def]
    """read_source that must succeed."""
    text, problem = read_source(source, file)
    assert problem is None, f'unexpected problem: {problem}'
    assert isinstance(text, SourceText)
    return text


def read_problem(source, file=None) -> Diagnostic:  # type: ignore[no-untyped-def]
    """read_source that must fail with one diagnostic."""
    text, problem = read_source(source, file)
    assert text is None, f'expected a problem, got text {text!r:.80}'
    assert isinstance(problem, Diagnostic)
    assert problem.severity is Severity.ERROR
    assert '\n' not in problem.message
    return problem


class Chunky(io.RawIOBase):
    """A raw binary stream that returns at most ``chunk`` bytes per read (like a pipe)."""

    def __init__(self, data: bytes, chunk: int = 3) -> None:
        self.data = data
        self.chunk = chunk
        self.reads = 0

    def readable(self) -> bool:
        return True

    def read(self, size: int = -1) -> bytes:  # type: ignore[override]
        self.reads += 1
        limit = self.chunk if size < 0 else min(size, self.chunk)
        out, self.data = self.data[:limit], self.data[limit:]
        return out


class PathLike:
    """An os.PathLike that is not a pathlib.Path."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def __fspath__(self) -> str:
        return str(self.path)


# --- str ---------------------------------------------------------------------

def test_str_is_document_text_not_a_file_name() -> None:
    text = read_ok(DOC)
    assert text.text == DOC
    assert text.file == '<string>'
    # A str that looks like a file name is still text.
    assert read_ok('examples/max_speed.nodl.yaml').text == 'examples/max_speed.nodl.yaml'


def test_str_file_argument_names_the_document() -> None:
    assert read_ok(DOC, 'given.yaml').file == 'given.yaml'


def test_str_leading_bom_is_removed_and_only_the_leading_one() -> None:
    assert read_ok(BOM + DOC).text == DOC
    inner = 'description: "a\ufeffb"\n'
    assert read_ok(inner).text == inner


def test_empty_str_is_empty_text() -> None:
    assert read_ok('').text == ''


def test_str_with_a_lone_surrogate_is_rejected_with_its_position() -> None:
    problem = read_problem('type: string\ndescription: ab\ud800\n')
    assert 'surrogate' in problem.message and 'U+D800' in problem.message
    assert (problem.line, problem.column) == (2, 16)
    report = check_source('type: string\ndescription: \udfff\n')
    assert len(report.diagnostics) == 1
    assert 'surrogate' in report.diagnostics[0].message


# --- bytes, bytearray, memoryview -----------------------------------------------

@pytest.mark.parametrize('kind', [bytes, bytearray, memoryview])
def test_binary_buffers_are_decoded_as_utf8(kind) -> None:  # type: ignore[no-untyped-def]
    text = read_ok(kind(DOC.encode('utf-8')))
    assert text.text == DOC
    assert text.file == '<bytes>'
    assert read_ok(kind(DOC.encode('utf-8')), 'b.yaml').file == 'b.yaml'


@pytest.mark.parametrize('kind', [bytes, bytearray, memoryview])
def test_binary_buffers_drop_a_utf8_bom(kind) -> None:  # type: ignore[no-untyped-def]
    assert read_ok(kind(UTF8_BOM + DOC.encode('utf-8'))).text == DOC


def test_empty_bytes_is_empty_text() -> None:
    assert read_ok(b'').text == ''


# --- file objects --------------------------------------------------------------

def test_text_stream_without_a_name() -> None:
    text = read_ok(io.StringIO(DOC))
    assert text.text == DOC
    assert text.file == '<stream>'


def test_binary_stream_without_a_name() -> None:
    text = read_ok(io.BytesIO(DOC.encode('utf-8')))
    assert text.text == DOC
    assert text.file == '<stream>'


def test_text_stream_drops_a_bom() -> None:
    assert read_ok(io.StringIO(BOM + DOC)).text == DOC


def test_binary_stream_drops_a_bom() -> None:
    assert read_ok(io.BytesIO(UTF8_BOM + DOC.encode('utf-8'))).text == DOC


def test_open_text_file_uses_its_name(tmp_path: Path) -> None:
    path = tmp_path / 'doc.yaml'
    path.write_text(DOC, encoding='utf-8')
    with open(path, encoding='utf-8') as stream:
        text = read_ok(stream)
    assert (text.text, text.file) == (DOC, str(path))


def test_open_binary_file_uses_its_name_and_keeps_bytes_exact(tmp_path: Path) -> None:
    path = tmp_path / 'doc.yaml'
    data = DOC.replace('\n', '\r\n').encode('utf-8')
    path.write_bytes(data)
    with open(path, 'rb') as stream:
        text = read_ok(stream)
    assert text.text == data.decode('utf-8')  # no newline translation for binary input
    assert text.file == str(path)
    with open(path, 'rb') as stream:
        assert read_ok(stream, 'override.yaml').file == 'override.yaml'


def test_open_file_with_utf8_bom_in_binary_and_text_mode() -> None:
    expected = 'type: string\ndescription: starts with a BOM\n'
    with open(FRONTENDS / 'utf8_bom.yaml', 'rb') as stream:
        assert read_ok(stream).text == expected
    with open(FRONTENDS / 'utf8_bom.yaml', encoding='utf-8') as stream:
        assert read_ok(stream).text == expected


def test_a_stream_with_short_reads_is_read_to_the_end() -> None:
    stream = Chunky(DOC.encode('utf-8'), chunk=3)
    assert read_ok(stream).text == DOC
    assert stream.reads > 3


def test_a_stream_is_never_read_without_a_bound() -> None:
    calls: list[int] = []

    class Recording(io.StringIO):
        def read(self, size: int | None = -1) -> str:
            calls.append(-1 if size is None else size)
            return super().read(size)

    read_ok(Recording(DOC))
    assert calls and calls[0] == MAX_BYTES + 1  # never an unbounded read()
    assert all(0 < size <= MAX_BYTES + 1 for size in calls)


# --- paths -------------------------------------------------------------------

def test_path_is_read_and_named_by_its_path(tmp_path: Path) -> None:
    path = tmp_path / 'doc.nodl.yaml'
    path.write_bytes(DOC.encode('utf-8'))
    text = read_ok(path)
    assert (text.text, text.file) == (DOC, str(path))
    assert read_ok(path, 'shown.yaml').file == 'shown.yaml'


def test_other_pathlike_objects_are_paths(tmp_path: Path) -> None:
    path = tmp_path / 'doc.yaml'
    path.write_text(DOC, encoding='utf-8')
    text = read_ok(PathLike(path))
    assert (text.text, text.file) == (DOC, str(path))


def test_path_with_utf8_bom() -> None:
    text = read_ok(FRONTENDS / 'utf8_bom.yaml')
    assert text.text == 'type: string\ndescription: starts with a BOM\n'
    assert not text.text.startswith(BOM)


def test_path_keeps_crlf_line_endings_as_written() -> None:
    # invalid_utf8.yaml has CRLF endings; a valid CRLF document must keep them.
    data = (FRONTENDS / 'same_data.yaml').read_bytes().replace(b'\n', b'\r\n')
    assert read_ok(data).text == data.decode('utf-8')


def test_missing_path_raises_oserror(tmp_path: Path) -> None:
    missing = tmp_path / 'nope.yaml'
    with pytest.raises(FileNotFoundError):
        read_source(missing)
    with pytest.raises(OSError):
        check_source(missing)
    with pytest.raises(OSError):
        load_nodl(missing)


def test_directory_path_raises_oserror(tmp_path: Path) -> None:
    with pytest.raises(OSError):
        read_source(tmp_path)


# --- unsupported input types -----------------------------------------------------

@pytest.mark.parametrize('source', [42, 4.2, None, ['type: int'], {'type': 'int'}, object()],
                         ids=['int', 'float', 'None', 'list', 'dict', 'object'])
def test_unsupported_types_raise_typeerror(source) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(TypeError) as info:
        read_source(source)
    assert type(source).__name__ in str(info.value)
    assert 'pathlib.Path' in str(info.value)
    with pytest.raises(TypeError):
        check_source(source)
    with pytest.raises(TypeError):
        load_nodl(source)


# --- encodings ---------------------------------------------------------------------

@pytest.mark.parametrize('name', ['utf16le_bom.yaml', 'utf16be_bom.yaml'])
def test_utf16_with_bom_is_rejected(name: str) -> None:
    path = FRONTENDS / name
    for source in (path, path.read_bytes(), io.BytesIO(path.read_bytes())):
        problem = read_problem(source)
        assert 'UTF-16' in problem.message and 'UTF-8' in problem.message
        assert (problem.line, problem.column) == (1, 1)


def test_utf16_file_is_one_error_for_load_nodl() -> None:
    with pytest.raises(ValidationError) as info:
        load_nodl(FRONTENDS / 'utf16le_bom.yaml')
    assert len(info.value.diagnostics) == 1
    assert 'UTF-16' in str(info.value)
    assert str(info.value).startswith(str(FRONTENDS / 'utf16le_bom.yaml') + ':1:1: error:')


@pytest.mark.parametrize('data, line, column, byte', [
    (b'\xff', 1, 1, 0xff),
    (b'type: int\ndescription: \xc3\x28\n', 2, 14, 0xc3),
    (b'type: int\r\ndescription: x\xe9y\r\n', 2, 15, 0xe9),
    (b'a: 1\n\n\nb: \x80', 4, 4, 0x80),
    (b'a: \xe2\x82', 1, 4, 0xe2),                     # truncated at the end
    (b'a: \xc0\xaf', 1, 4, 0xc0),                     # overlong encoding
    (b'a: \xed\xa0\x80', 1, 4, 0xed),                 # an encoded surrogate
    (b'k: \xc3\xa9\xe2\x82\xac\xff', 1, 6, 0xff),     # columns count characters, not bytes
    (b'\xef\xbb\xbfa: \xfe', 1, 4, 0xfe),             # the BOM is not a column
    (b'\xef\xbb\xbf\xfe', 1, 1, 0xfe),
], ids=['first', 'line2', 'crlf', 'blank-lines', 'truncated', 'overlong', 'surrogate',
        'after-multibyte', 'after-bom', 'right-after-bom'])
def test_invalid_utf8_reports_line_and_column_of_the_bad_byte(
        data: bytes, line: int, column: int, byte: int) -> None:
    problem = read_problem(data)
    assert (problem.line, problem.column) == (line, column)
    assert f'byte 0x{byte:02x}' in problem.message
    assert 'not valid UTF-8' in problem.message
    # decode() is the same check for callers that already hold bytes.
    text, direct = decode(data, 'x.yaml')
    assert text is None and direct is not None
    assert (direct.file, direct.line, direct.column) == ('x.yaml', line, column)


def test_invalid_utf8_file_is_placed_in_path_stream_and_check_source() -> None:
    path = FRONTENDS / 'invalid_utf8.yaml'
    for source in (path, path.read_bytes()):
        problem = read_problem(source)
        assert (problem.line, problem.column) == (2, 21)
    with open(path, 'rb') as stream:
        problem = read_problem(stream)
    assert (problem.file, problem.line, problem.column) == (str(path), 2, 21)
    report = check_source(path)
    assert [(d.line, d.column, d.file) for d in report.diagnostics] == [(2, 21, str(path))]
    assert report.kind is None
    with pytest.raises(ValidationError) as info:
        load_nodl(path)
    assert str(info.value) == (f'{path}:2:21: error: document is not valid UTF-8 '
                               '(byte 0xff cannot be decoded); save the file as UTF-8 [NODL002]')


def test_a_text_file_opened_with_the_wrong_encoding_is_the_callers_problem() -> None:
    # Decoding a text stream is the caller's job; read_source takes its str as is.
    with open(FRONTENDS / 'invalid_utf8.yaml', encoding='latin-1') as stream:
        text = read_ok(stream)
    assert 'Ã©' in text.text


# --- the size limit ------------------------------------------------------------------

def test_the_limit_is_ten_mebibytes() -> None:
    assert MAX_BYTES == 10 * 1024 * 1024


def _payload(size: int) -> bytes:
    head = b'type: string\ndescription: "'
    return head + b'x' * (size - len(head) - 2) + b'"\n'


def test_exactly_the_limit_is_accepted_for_every_input_kind(tmp_path: Path) -> None:
    data = _payload(MAX_BYTES)
    assert len(data) == MAX_BYTES
    path = tmp_path / 'limit.yaml'
    path.write_bytes(data)
    text = data.decode('ascii')
    for source in (data, bytearray(data), memoryview(data), text, io.BytesIO(data),
                   io.StringIO(text), path):
        assert len(read_ok(source).text) == MAX_BYTES, type(source).__name__


def test_one_byte_over_the_limit_is_one_clear_error_for_every_input_kind(tmp_path: Path) -> None:
    data = _payload(MAX_BYTES + 1)
    path = tmp_path / 'big.yaml'
    path.write_bytes(data)
    text = data.decode('ascii')
    sources = {'bytes': data, 'bytearray': bytearray(data), 'memoryview': memoryview(data),
               'str': text, 'BytesIO': io.BytesIO(data), 'StringIO': io.StringIO(text),
               'Path': path, 'PathLike': PathLike(path)}
    for kind, source in sources.items():
        problem = read_problem(source)
        assert problem.message == TOO_LARGE, kind
        assert (problem.line, problem.column) == (0, 0), kind
    with open(path, 'rb') as stream:
        assert read_problem(stream).message == TOO_LARGE
    with open(path, encoding='utf-8') as stream:
        assert read_problem(stream).message == TOO_LARGE


def test_too_large_is_a_single_error_from_the_public_api() -> None:
    data = _payload(MAX_BYTES + 1)
    report = check_source(data)
    assert [str(d) for d in report.diagnostics] == [f'<bytes>: error: {TOO_LARGE} [NODL001]']
    with pytest.raises(ValidationError) as info:
        load_nodl(data.decode('ascii'), file='big.yaml')
    assert str(info.value) == f'big.yaml: error: {TOO_LARGE} [NODL001]'


def test_str_limit_counts_utf8_bytes_not_characters() -> None:
    # 3 bytes per character: under the limit in characters, over it in bytes.
    over = 'description: ' + '€' * (MAX_BYTES // 3)
    assert len(over) <= MAX_BYTES < len(over.encode('utf-8'))
    assert read_problem(over).message == TOO_LARGE
    assert read_problem(io.StringIO(over)).message == TOO_LARGE
    # The same text as bytes is rejected too: every input kind agrees.
    assert read_problem(over.encode('utf-8')).message == TOO_LARGE
    under = 'description: ' + '€' * ((MAX_BYTES - 20) // 3)
    assert len(under.encode('utf-8')) <= MAX_BYTES
    assert read_ok(under).text == under


def test_huge_sparse_file_is_rejected_without_reading_it(tmp_path: Path) -> None:
    path = tmp_path / 'sparse.yaml'
    with open(path, 'wb') as stream:
        stream.truncate(2 * 1024 ** 3)  # 2 GiB, no blocks on disk
    start = time.perf_counter()
    problem = read_problem(path)
    assert time.perf_counter() - start < 1.0
    assert problem.message == TOO_LARGE
    assert problem.file == str(path)


def test_stream_over_the_limit_is_not_read_beyond_it() -> None:
    stream = io.BytesIO(_payload(3 * MAX_BYTES))
    assert read_problem(stream).message == TOO_LARGE
    assert stream.tell() <= MAX_BYTES + 1


def test_endless_device_is_rejected_not_read_forever() -> None:
    # /dev/zero reports size 0 and never ends: only the first MAX_BYTES + 1 may be read.
    script = textwrap.dedent('''
        from pathlib import Path
        from nodl.frontends.source import read_source
        text, problem = read_source(Path('/dev/zero'))
        print(problem.message if problem else 'NO PROBLEM')
    ''')
    env = dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    result = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True,
                            timeout=60, cwd=REPO, env=env)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == TOO_LARGE


def test_read_limited_reads_what_open_reads(tmp_path: Path) -> None:
    # read_limited asks for the size the file reports, not for the whole limit.
    from nodl.frontends.source import read_limited

    for size in (0, 1, 900, 70_000, 3 * 1024 * 1024 + 7, MAX_BYTES, MAX_BYTES + 5):
        path = tmp_path / f'f{size}'
        path.write_bytes(bytes(i % 251 for i in range(size)))
        expected = path.read_bytes()[:MAX_BYTES + 1]
        assert read_limited(path) == expected
        assert read_limited(str(path)) == expected
    if os.path.exists('/proc/version'):  # a regular file that says it holds nothing
        with open('/proc/version', 'rb') as f:
            assert read_limited('/proc/version') == f.read()
    with pytest.raises(IsADirectoryError) as by_open:
        open(tmp_path, 'rb')  # noqa: SIM115  (refused: nothing to close)
    with pytest.raises(IsADirectoryError) as by_read:
        read_limited(tmp_path)
    assert str(by_read.value) == str(by_open.value)
    with pytest.raises(FileNotFoundError) as by_open:
        open(tmp_path / 'missing', 'rb')  # noqa: SIM115  (refused: nothing to close)
    with pytest.raises(FileNotFoundError) as by_read:
        read_limited(tmp_path / 'missing')
    assert str(by_read.value) == str(by_open.value)


def test_read_regular_reads_a_regular_file_and_nothing_else(tmp_path: Path) -> None:
    from nodl.frontends.source import read_limited, read_regular

    file = tmp_path / 'a.nodl.yaml'
    file.write_bytes(b'nodl_version: 2\n' * 1000)
    assert read_regular(file) == read_limited(file) == file.read_bytes()
    assert read_regular(tmp_path / 'missing.yaml') is None
    assert read_regular(file / 'below') is None  # a path through a file
    assert read_regular(tmp_path) is None  # a directory
    fifo = tmp_path / 'fifo'
    os.mkfifo(fifo)
    start = time.monotonic()
    assert read_regular(fifo) is None  # without waiting for a writer
    assert time.monotonic() - start < 5
