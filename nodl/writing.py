"""Writing files: atomically, never through a link, never over a file the user wrote.

Every file the toolkit writes goes through :func:`write_file` (reports, logs,
graphs, index markers: always replaceable) or :func:`write_marked` (files
meant to be committed or edited: generated code, converted and described
definitions, parameter files, policies, scaffold files).

* **Atomic.**  The text goes to a temporary file in the target's folder,
  is flushed to the disk (``fsync``), then renamed over the target.  A write
  that fails (a full disk, the file size limit, a read-only folder) leaves
  the previous file as it was and removes the temporary file; the
  :class:`WriteError` names the file.
* **Permissions kept.**  A file that is replaced keeps its mode; a new one
  gets the mode the umask gives (``0o666 & ~umask``) unless asked otherwise.
* **Links replaced, not followed.**  A symbolic link at the output path is
  replaced by the new file; the file it points to is never written.
* **Special files** (``/dev/null``, a FIFO, a terminal) hold no content to
  lose and cannot be renamed over: they are written in place.
* **The content marker.**  A marked file carries one comment line near its
  top, ``nodl: generated; sha256=<hex>``, in the comment syntax of its type
  (``#`` for YAML, Python, CMake, shell; ``//`` for C++; ``<!-- -->`` for
  XML), where ``<hex>`` is the SHA-256 of the file's text without that line.
  :func:`check_replaceable` refuses to replace a file that has no marker (the
  user wrote it: NODL031) or whose text no longer matches it (the user
  edited it: NODL032), unless ``force``.  A file whose text (without the
  marker) is what would be written loses nothing and is always replaceable.
  Formats without comments (JSON) carry no marker: an existing one is
  replaced only with ``force``.
* **Outputs are not inputs.**  :func:`output_is_input` says when an output
  path names one of the inputs (the same file after resolving links, or the
  same device and inode: NODL033); :func:`outputs_are_inputs` checks every
  output option of a command against everything it read.
* **Nothing leaves the output folder.**  A file written under a folder (``-o
  DIR``) is refused when a folder between the two is a symbolic link that
  leads outside it (planted by someone else): :func:`check_within` (NODL708).
  The output folder itself may be a link: it is the user's choice.

Nothing here prints or exits: problems are :class:`WriteError` exceptions
carrying one coded :class:`~nodl.diagnostics.Diagnostic`.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import os
import stat
from collections.abc import Iterable

from nodl.diagnostics import Diagnostic, Severity
from nodl.write_error import WriteError

__all__ = ['WriteError', 'MARKER_TAG', 'comment_style', 'mark', 'unmark', 'marker_state',
           'check_replaceable', 'write_file', 'write_marked', 'marked_text', 'output_is_input',
           'same_file', 'write_problem', 'check_within', 'outputs_are_inputs', 'holds_text']

#: The words of the marker line, before the hash.
MARKER_TAG = 'nodl: generated; sha256='

#: comment style -> (start, end) of a one-line comment.
_COMMENTS: dict[str, tuple[str, str]] = {'#': ('# ', ''), '//': ('// ', ''), 'xml': ('<!-- ', ' -->')}

#: File name endings -> comment style.
_STYLES: tuple[tuple[str, str], ...] = (
    ('.yaml', '#'), ('.yml', '#'), ('.py', '#'), ('.cmake', '#'), ('cmakelists.txt', '#'),
    ('.sh', '#'), ('.bash', '#'), ('.cfg', '#'), ('.toml', '#'), ('.txt', '#'),
    ('.hpp', '//'), ('.h', '//'), ('.hh', '//'), ('.hxx', '//'), ('.cpp', '//'), ('.cc', '//'),
    ('.cxx', '//'), ('.c', '//'), ('.xml', 'xml'), ('.sdf', 'xml'), ('.launch', 'xml'),
    ('.md', 'xml'), ('.html', 'xml'),
)

#: How many lines from the top the marker may be on (after a ``#!`` line or an XML declaration).
_MARKER_WINDOW = 3


def _error(path: str, code: str, message: str) -> WriteError:
    return WriteError(Diagnostic(Severity.ERROR, message, file=path, code=code))


def comment_style(path: str) -> str | None:
    """The comment style (``'#'``, ``'//'``, ``'xml'``) of a file named ``path``; None for JSON and
    the formats without comments."""
    name = os.path.basename(path).lower()
    for ending, style in _STYLES:
        if name.endswith(ending):
            return style
    return None


def _marker_line(text: str, style: str) -> str:

    start, end = _COMMENTS[style]
    digest = hashlib.sha256(text.encode('utf-8', 'surrogatepass')).hexdigest()
    return f'{start}{MARKER_TAG}{digest}{end}'


def _find_marker(text: str) -> tuple[int, int, str] | None:
    """``(start, end, hex)`` of the marker line (its newline included) among the first lines."""
    position = 0
    for _ in range(_MARKER_WINDOW):
        if position >= len(text):
            return None
        newline = text.find('\n', position)
        end = len(text) if newline < 0 else newline + 1
        line = text[position:end].rstrip('\r\n').strip()
        at = line.find(MARKER_TAG)
        if at >= 0:
            hex_digest = line[at + len(MARKER_TAG):at + len(MARKER_TAG) + 64]
            prefix, suffix = line[:at].strip(), line[at + len(MARKER_TAG) + 64:].strip()
            if (prefix in ('#', '//', '<!--') and suffix in ('', '-->') and len(hex_digest) == 64
                    and all(c in '0123456789abcdef' for c in hex_digest)):
                return position, end, hex_digest
        position = end
    return None


def unmark(text: str) -> str:
    """``text`` without its marker line (unchanged if it has none)."""
    found = _find_marker(text)
    return text if found is None else text[:found[0]] + text[found[1]:]


def mark(text: str, style: str) -> str:
    """``text`` with a (fresh) marker line in comment style ``style``.

    The line goes first, or after a first line that must stay first (``#!``,
    an XML declaration, a ``# yaml-language-server:`` modeline); an existing
    marker is replaced.
    """
    body = unmark(text)
    line = _marker_line(body, style)
    newline = '\r\n' if '\r\n' in body.split('\n', 1)[0] + '\n' else '\n'
    first_end = body.find('\n') + 1
    keep_first = body.startswith(('#!', '<?xml', '\ufeff<?xml', '# yaml-language-server:'))
    if keep_first and first_end > 0:
        return body[:first_end] + line + newline + body[first_end:]
    return line + newline + body


def marker_state(text: str) -> str:
    """``'valid'`` (marked, unchanged since), ``'edited'`` (marked, changed since) or ``'absent'``."""

    found = _find_marker(text)
    if found is None:
        return 'absent'
    body = text[:found[0]] + text[found[1]:]
    digest = hashlib.sha256(body.encode('utf-8', 'surrogatepass')).hexdigest()
    return 'valid' if digest == found[2] else 'edited'


def check_replaceable(path: str, new_text: str | None = None, *, force: bool = False) -> Diagnostic | None:
    """Why writing ``path`` would destroy the user's work (NODL031, NODL032, NODL034), or None.

    Nothing there, a symbolic link (replaced, its target untouched), a special
    file, a file with a valid marker, or a file whose text without the marker
    is ``new_text`` without it: None.  ``force`` allows replacing any file but
    never a directory.
    """
    problem = _place_problem(path)
    if problem is not None:
        return problem
    try:
        status = os.lstat(path)
    except OSError:
        return None  # nothing there (or not reachable: the write says why)
    if not stat.S_ISREG(status.st_mode) or force:
        return None
    try:
        with open(path, 'rb') as stream:
            existing = stream.read().decode('utf-8')
    except (OSError, UnicodeDecodeError):
        existing = None
    state = 'absent' if existing is None else marker_state(existing)
    if state == 'valid':
        return None
    if existing is not None and new_text is not None and unmark(existing) == unmark(new_text):
        return None
    if state == 'edited':
        return Diagnostic(Severity.ERROR, 'the file was edited since nodl wrote it (its text no longer '
                          'matches its nodl marker): not replaced; keep your changes elsewhere and '
                          'give --force to replace it', file=path, code='NODL032')
    return Diagnostic(Severity.ERROR, 'the file was not written by nodl (it has no nodl marker): '
                      'not replaced; give another output path, or --force to replace it',
                      file=path, code='NODL031')


def _place_problem(path: str) -> Diagnostic | None:
    if os.path.isdir(path) and not os.path.islink(path):
        return Diagnostic(Severity.ERROR, 'cannot write the file: a directory is in its place; give '
                          'a file path', file=path, code='NODL034')
    return None


def write_problem(path: str, exc: OSError, existed: bool | None) -> Diagnostic:
    """The NODL030 diagnostic of a write of ``path`` that failed with ``exc`` (``existed``: whether
    a previous file was kept; None for a device or FIFO, which keeps nothing)."""

    reason = exc.strerror or type(exc).__name__
    if exc.errno == errno.EFBIG:
        reason += ' (the file size limit)'
    elif exc.errno == errno.ENOSPC:
        reason = 'no space left on the device'
    elif exc.errno == errno.EDQUOT:
        reason = 'the disk quota is exceeded'
    elif exc.errno == errno.ENOENT:
        reason = 'its folder does not exist'
    elif exc.errno in (errno.EACCES, errno.EPERM):
        reason = 'permission denied'
    elif exc.errno == errno.EROFS:
        reason = 'the file system is read-only'
    kept = '' if existed is None else '; the previous file is unchanged' if existed else \
        '; nothing was written'
    return Diagnostic(Severity.ERROR, f'cannot write the file: {reason}{kept}', file=path,
                      code='NODL030')


def _umask_mode() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


def write_file(path: str, data: str | bytes, *, mode: int | None = None,
               make_parents: bool = False, within: str | None = None) -> None:
    """Write ``data`` (text as UTF-8, newlines as given) to ``path`` atomically.

    The mode is ``mode`` if given, else the replaced file's, else what the
    umask gives.  ``make_parents``: create the missing folders first.
    ``within``: the output folder ``path`` must stay in (:func:`check_within`, checked
    before any folder is made).  Raises :class:`WriteError` (NODL030, NODL034,
    NODL708); on failure the previous file is intact.
    """
    raw = data.encode('utf-8', 'surrogatepass') if isinstance(data, str) else data
    problem = _place_problem(path) or (check_within(path, within) if within is not None else None)
    if problem is not None:
        raise WriteError(problem)
    folder = os.path.dirname(os.path.abspath(path))
    try:
        status: os.stat_result | None = os.lstat(path)
    except OSError:
        status = None
    if make_parents and status is None:
        try:
            os.makedirs(folder, exist_ok=True)
        except OSError as exc:
            raise WriteError(write_problem(path, exc, False)) from None
    if status is not None and not stat.S_ISREG(status.st_mode) and not stat.S_ISLNK(status.st_mode):
        _write_in_place(path, raw)  # a device, a FIFO: no content to keep, nothing to rename over
        return
    if mode is None:
        mode = stat.S_IMODE(status.st_mode) if status is not None and stat.S_ISREG(status.st_mode) \
            else _umask_mode()

    try:
        fd, temporary = _create_temporary(folder, os.path.basename(path))
    except OSError as exc:
        raise WriteError(write_problem(path, exc, status is not None)) from None
    try:
        try:
            view = memoryview(raw)
            while view:
                written = os.write(fd, view)
                view = view[written:]
            os.fchmod(fd, mode)
            os.fsync(fd)
        finally:
            os.close(fd)
        os.replace(temporary, path)
    except OSError as exc:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise WriteError(write_problem(path, exc, status is not None)) from None
    _sync_folder(folder)


#: How a temporary file is created: new (never an existing file or a link), private, not inherited.
_TEMPORARY_FLAGS = (os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, 'O_NOFOLLOW', 0)
                    | getattr(os, 'O_CLOEXEC', 0))


def _create_temporary(folder: str, name: str) -> tuple[int, str]:
    """A new file ``.NAME.<random>.nodl-tmp`` in ``folder``, open for writing, mode 0o600:
    what :func:`tempfile.mkstemp` makes (the module itself costs every command that may
    write a file ~4 ms of start-up: shutil, bz2, lzma, random)."""
    for _ in range(100):
        temporary = os.path.join(folder, f'.{name}.{os.urandom(6).hex()}.nodl-tmp')
        try:
            return os.open(temporary, _TEMPORARY_FLAGS, 0o600), temporary
        except FileExistsError:
            continue  # (a name taken: another)
    raise FileExistsError(errno.EEXIST, 'no free temporary file name', folder)


def _write_in_place(path: str, raw: bytes) -> None:
    try:
        with open(path, 'wb') as stream:
            stream.write(raw)
    except OSError as exc:
        raise WriteError(write_problem(path, exc, None)) from None


def _sync_folder(folder: str) -> None:
    """Make the rename durable (best effort: some file systems cannot sync a folder)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_marked(path: str, text: str, *, force: bool = False, style: str | None = None,
                 mode: int | None = None, make_parents: bool = False,
                 within: str | None = None) -> bool:
    """Write ``text`` to ``path`` with a content marker, atomically (see the module doc).

    ``style``: the comment style (default: from the file name; None for a
    format without comments, written unmarked).  Raises :class:`WriteError`
    when the file there is the user's (NODL031) or was edited (NODL032) and
    not ``force``, when ``within`` is given and the file would land outside that folder
    (NODL708, :func:`check_within`), or when the write fails (NODL030).  Returns False when the
    file already holds exactly this text (it is left untouched: its time
    stamp stays, so build systems do not rebuild), True when written.
    """
    final = marked_text(path, text, style)
    outside = check_within(path, within) if within is not None else None
    if outside is not None:
        raise WriteError(outside)
    if holds_text(path, final):
        return False
    problem = check_replaceable(path, final, force=force)
    if problem is not None:
        raise WriteError(problem)
    write_file(path, final, mode=mode, make_parents=make_parents, within=within)
    return True


def holds_text(path: str, text: str) -> bool:
    """Whether ``path`` is a regular file (not a link: it is not followed) holding exactly
    ``text`` (as UTF-8).  A writer leaves such a file untouched, so its time stamp stays and
    build systems do not rebuild; anything unreadable is False (the write says why)."""
    data = text.encode('utf-8', 'surrogatepass')
    try:
        status = os.lstat(path)
        if not stat.S_ISREG(status.st_mode) or status.st_size != len(data):
            return False
        with open(path, 'rb') as stream:
            return stream.read() == data
    except OSError:
        return False


def marked_text(path: str, text: str, style: str | None = None) -> str:
    """The text :func:`write_marked` writes to ``path`` (``text`` with its marker, if the format
    has comments)."""
    chosen = style if style is not None else comment_style(path)
    return text if chosen is None else mark(text, chosen)


def same_file(first: str, second: str) -> bool:
    """Whether two paths name the same file: the same path once links are resolved, or the same
    device and inode (hard links, bind mounts)."""
    if os.path.realpath(first) == os.path.realpath(second):
        return True
    try:
        return os.path.samefile(first, second)
    except OSError:
        return False


def output_is_input(output: str, inputs: Iterable[str], option: str = '-o') -> Diagnostic | None:
    """NODL033 when ``output`` is one of ``inputs`` (see :func:`same_file`), else None."""
    return outputs_are_inputs([(option, output)], inputs)


def _identity(path: str) -> tuple[str, tuple[int, int] | None]:
    """The real path of ``path`` and its device and inode (None when nothing is there)."""
    try:
        status = os.stat(path)
    except (OSError, ValueError):
        return os.path.realpath(path), None
    return os.path.realpath(path), (status.st_dev, status.st_ino)


def outputs_are_inputs(outputs: Iterable[tuple[str, str | None]],
                       inputs: Iterable[str]) -> Diagnostic | None:
    """NODL033 for the first output that is one of ``inputs`` (see :func:`same_file`), else None.

    ``outputs``: ``(option, path)`` pairs (``('-o', 'report.json')``, ``('--log', ...)``); a
    path that is None, empty or ``-`` (standard output) is no file.  ``inputs``: every file the
    command read (repeats and empty strings are fine).  Each file is looked at once, so checking
    a large analysis's files costs one ``stat`` each.
    """
    wanted = [(option, path, _identity(path)) for option, path in outputs
              if path and path != '-']
    if not wanted:
        return None
    seen: set[str] = set()
    for item in inputs:
        if not item or item in seen:
            continue
        seen.add(item)
        real, inode = _identity(item)
        for option, path, (out_real, out_inode) in wanted:
            if real == out_real or (inode is not None and inode == out_inode):
                return Diagnostic(Severity.ERROR, f'{option} names an input of the command ({item}): '
                                  'writing it would destroy the input; give another output path',
                                  file=path, code='NODL033')
    return None


def check_within(path: str, root: str) -> Diagnostic | None:
    """NODL708 when writing ``path`` would put a file outside the output folder ``root``.

    That is when the path leads out of ``root`` (``..``, another absolute path), or when a
    folder between ``root`` and the file is a symbolic link to a place outside ``root`` (its
    real path is compared with the real path of ``root``): someone may have planted it to
    redirect the write.  ``root`` itself may be a link (the user named it); the file itself may
    be a link (it is replaced, not followed: :func:`write_file`); folders that do not exist
    yet are created inside ``root``.
    """
    base = os.path.abspath(root)
    prefix = root.rstrip(os.sep) + os.sep
    # the path as given (not normalised: 'link/..' is not where the kernel would go)
    tail = path[len(prefix):] if path.startswith(prefix) else \
        os.path.relpath(os.path.abspath(path), base)
    parts = [part for part in tail.split(os.sep) if part not in ('', os.curdir)]
    if not parts or os.pardir in parts or os.path.isabs(tail):
        return Diagnostic(Severity.ERROR, f'not written: the path leads outside the output folder '
                          f'{root}; give a path inside it', file=path, code='NODL708')
    real_root = os.path.realpath(base)
    inside = real_root.rstrip(os.sep) + os.sep
    current = base
    for part in parts[:-1]:
        current = os.path.join(current, part)
        if not os.path.lexists(current):
            break  # made by the write, inside root
        real = os.path.realpath(current)
        if real != real_root and not real.startswith(inside):
            link = current if os.path.islink(current) else os.path.dirname(current)
            return Diagnostic(Severity.ERROR, f'not written: {link} is a symbolic link to {real}, '
                              f'outside the output folder {root}; remove the link or give another '
                              'output folder', file=path, code='NODL708')
    return None
