"""Checking many files at once (what ``nodl validate`` does)."""

from __future__ import annotations

import os
import sys

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Iterable

from nodl_schema.diagnostics import Diagnostic, has_errors
from nodl_schema.files import STDIN, find_nodl_files
from nodl_schema.loading import Report, check_source
from nodl_schema.validation.kinds import Kind

__all__ = ['FileResult', 'check_paths']


class FileResult:
    """The outcome for one path: a report, or why it could not be read."""

    def __init__(self, path: str, report: Report | None = None, problem: str | None = None,
                 diagnostics: list[Diagnostic] | None = None) -> None:
        self.path = path
        self.report = report
        self.problem = problem
        self.diagnostics: list[Diagnostic] = diagnostics or []

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
                resolve: bool = False) -> list[FileResult]:
    """Check every NoDL file named by ``paths`` (see :func:`find_nodl_files`).

    With ``resolve``, node definitions are also composed: their mixin
    references must resolve to valid interface definitions.
    """
    results: list[FileResult] = []
    for target in find_nodl_files(paths):
        if target.problem is not None:
            results.append(FileResult(target.path, problem=target.problem))
            continue
        try:
            if target.path == STDIN:
                report = check_source(sys.stdin.buffer.read(), kind=kind, file='<stdin>')
            else:
                report = check_source(_FilePath(target.path), kind=kind, file=target.path)
        except OSError as exc:
            results.append(FileResult(target.path, problem=exc.strerror or str(exc)))
            continue
        diagnostics = report.diagnostics
        if resolve and report.kind is Kind.NODE and not report.has_errors():
            from nodl_schema.composition import compose_report

            diagnostics = compose_report(report)[1]
        results.append(FileResult(report.file, report, diagnostics=diagnostics))
    return results


def failed(result: FileResult, strict: bool) -> bool:
    """True if the file is invalid (with ``strict``, warnings count)."""
    return has_errors(result.diagnostics, strict)
