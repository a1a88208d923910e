"""Checking many files at once (what ``nodl validate`` does)."""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable

from nodl_schema.diagnostics import Diagnostic, Severity
from nodl_schema.files import STDIN, find_nodl_files
from nodl_schema.loading import Report, check_source
from nodl_schema.validation.kinds import Kind

__all__ = ['FileResult', 'check_paths']


@dataclass
class FileResult:
    """The outcome for one path: a report, or why it could not be read."""

    path: str
    report: Report | None = None
    problem: str | None = None
    diagnostics: list[Diagnostic] = field(default_factory=list)

    @property
    def readable(self) -> bool:
        """False if the path could not be read at all (an I/O or usage problem)."""
        return self.problem is None


def check_paths(paths: Iterable[str], kind: Kind | None = None) -> list[FileResult]:
    """Check every NoDL file named by ``paths`` (see :func:`find_nodl_files`)."""
    results: list[FileResult] = []
    for target in find_nodl_files(paths):
        if target.problem is not None:
            results.append(FileResult(target.path, problem=target.problem))
            continue
        try:
            if target.path == STDIN:
                report = check_source(sys.stdin.buffer.read(), kind=kind, file='<stdin>')
            else:
                report = check_source(Path(target.path), kind=kind, file=target.path)
        except OSError as exc:
            results.append(FileResult(target.path, problem=exc.strerror or str(exc)))
            continue
        results.append(FileResult(target.path, report, diagnostics=report.diagnostics))
    return results


def failed(result: FileResult, strict: bool) -> bool:
    """True if the file is invalid (with ``strict``, warnings count)."""
    failing = (Severity.ERROR, Severity.WARNING) if strict else (Severity.ERROR,)
    return any(d.severity in failing for d in result.diagnostics)
