"""Checking many files at once (what ``nodl validate`` does)."""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable, Iterator

from nodl.diagnostics import Diagnostic, has_errors
from nodl.files import STDIN, describe_os_error, iter_nodl_files
from nodl.frontends.source import MAX_BYTES, read_limited
from nodl.loading import CheckedSource, check_source
from nodl.validation.kinds import Kind

__all__ = ['FileResult', 'check_paths', 'iter_check_paths', 'failed']


class FileResult:
    """The outcome for one path: a report, or why it could not be read."""

    def __init__(self, path: str, report: CheckedSource | None = None, problem: str | None = None,
                 diagnostics: list[Diagnostic] | None = None, note: str | None = None) -> None:
        self.path = path
        self.report = report
        self.problem = problem
        self.diagnostics: list[Diagnostic] = diagnostics or []
        #: A remark that is not a result (a file a scan skipped, a pipe read that waits).
        self.note = note

    @property
    def readable(self) -> bool:
        """False if the path could not be read at all (an I/O or usage problem)."""
        return self.problem is None


class _FilePath(os.PathLike):  # type: ignore[type-arg]
    """A path without importing pathlib (it costs the command line start-up time)."""

    def __init__(self, path: str) -> None:
        self._path = path

    def __fspath__(self) -> str:
        return self._path


def check_paths(paths: Iterable[str], kind: Kind | None = None,
                resolve: bool = False, *, client_library: str | None = None) -> list[FileResult]:
    """Check every NoDL file named by ``paths`` (see :func:`find_nodl_files`).

    With ``resolve``, node definitions are also composed (on the base of
    ``client_library``, rclpy by default; ValueError for an unknown one):
    their mixin references must resolve to valid interface definitions and
    the layers must agree.  Notes (see :func:`iter_check_paths`) are left out.
    """
    return [r for r in iter_check_paths(paths, kind, resolve, client_library=client_library)
            if r.note is None]


def iter_check_paths(paths: Iterable[str], kind: Kind | None = None,
                     resolve: bool = False, *, client_library: str | None = None,
                     types: bool = False, package_dir: str | None = None,
                     build: bool = False) -> Iterator[FileResult]:
    """Check the files named by ``paths`` one at a time, yielding each result as soon as it is known.

    ``resolve`` and ``client_library`` as for :func:`check_paths`.  With ``types``
    (implied by ``package_dir``), every endpoint type is also checked against the
    installed interfaces (one index snapshot for the whole run; see
    :func:`nodl.interface_types.check.check_types`): ``package_dir`` is the
    package the files belong to (its own types resolve from its source, and its
    ``package.xml`` must declare each interface package); a registered definition is
    checked against its installed package's manifest.  ``build``: checked while the
    package builds (a declared but uninstalled dependency is a warning).

    Besides one result per file (a report, or the problem that kept it from
    being read), it yields notes (``result.note``): a file a directory scan
    skipped, or a named pipe about to be read that has no writer yet (the
    read waits for one).
    """
    index = None
    if types or package_dir is not None:
        from nodl.interface_types import interface_index

        index = interface_index([package_dir] if package_dir is not None else [])
    for target in iter_nodl_files(paths):
        if target.skipped is not None:
            yield FileResult(target.path, note=f'skipped: {target.skipped}')
            continue
        if target.problem is not None:
            yield FileResult(target.path, problem=target.problem)
            continue
        try:
            if target.path == STDIN:
                report = check_source(sys.stdin.buffer.read(), kind=kind, file='<stdin>')
            elif target.special == 'named pipe':
                data = _read_pipe_if_written(target.path)
                if data is None:
                    yield FileResult(target.path, note='is a named pipe: waiting for a program to '
                                                       'write to it (Ctrl-C to stop)')
                    data = read_limited(target.path)
                report = check_source(data, kind=kind, file=target.path)
            else:
                report = check_source(_FilePath(target.path), kind=kind, file=target.path)
        except OSError as exc:
            yield FileResult(target.path, problem=describe_os_error(exc))
            continue
        diagnostics = report.diagnostics
        if resolve and report.kind is Kind.NODE and not report.has_errors():
            from nodl.composition import compose_report
            from nodl.composition.bases import DEFAULT_CLIENT_LIBRARY

            diagnostics = compose_report(report, client_library=client_library or DEFAULT_CLIENT_LIBRARY)[1]
        if index is not None and report.kind in (Kind.NODE, Kind.INTERFACE):
            diagnostics = _with_types(report, diagnostics, index, package_dir, build)
        yield FileResult(report.file, report, diagnostics=diagnostics)


def _with_types(report: CheckedSource, diagnostics: list[Diagnostic], index: object,
                package_dir: str | None, build: bool) -> list[Diagnostic]:
    """``diagnostics`` and those of the type check; a short name the check resolved
    (NODL253, which names the full form) replaces the generic NODL205."""
    from nodl.interface_types.check import check_types, manifest_for
    from nodl.interface_types.resolve import InterfaceIndex

    assert isinstance(index, InterfaceIndex)
    manifest = manifest_for(report.file, package_dir) if report.file != '<stdin>' or package_dir else None
    found = check_types(report, index, manifest, build=build)
    resolved = {d.path for d in found if d.code == 'NODL253'}
    kept = [d for d in diagnostics if not (d.code == 'NODL205' and d.path in resolved)]
    return sorted(kept + found, key=lambda d: (d.file != report.file, d.line, d.column))


def _read_pipe_if_written(path: str) -> bytes | None:
    """A named pipe's content if a writer has it open; None if opening it would wait for one."""
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        try:
            first = os.read(fd, 65536)
        except BlockingIOError:  # a writer is there, it has not written yet
            first = None
        if first == b'':  # no writer (or one that wrote nothing): a plain open would wait
            return None
        os.set_blocking(fd, True)
        chunks = [first] if first else []
        total = len(first or b'')
        while total <= MAX_BYTES:
            chunk = os.read(fd, MAX_BYTES + 1 - total)
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
        return b''.join(chunks)
    finally:
        os.close(fd)


def failed(result: FileResult, strict: bool) -> bool:
    """True if the file is invalid (with ``strict``, warnings count)."""
    return has_errors(result.diagnostics, strict)
