"""Rendering diagnostics for people (text) and for tools (JSON)."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterable

from nodl.diagnostics import Diagnostic, Severity

__all__ = ['Tally', 'plural', 'without_info', 'format_text', 'format_json', 'summary_line']


class Tally:
    """Counts for the summary line."""

    def __init__(self) -> None:
        self.files = 0
        self.errors = 0
        self.warnings = 0
        self.infos = 0
        self.diagnostics: list[Diagnostic] = []

    def add(self, diagnostics: Iterable[Diagnostic]) -> None:
        """Count and keep diagnostics."""
        for d in diagnostics:
            self.diagnostics.append(d)
            if d.severity is Severity.ERROR:
                self.errors += 1
            elif d.severity is Severity.WARNING:
                self.warnings += 1
            else:
                self.infos += 1


def without_info(diagnostics: Iterable[Diagnostic]) -> list[Diagnostic]:
    """The diagnostics a user sees by default: errors and warnings."""
    return [d for d in diagnostics if d.severity is not Severity.INFO]


def plural(count: int, word: str) -> str:
    return f'{count} {word}{"" if count == 1 else "s"}'


def summary_line(tally: Tally) -> str:
    """``N files, N errors, N warnings``."""
    return ', '.join((plural(tally.files, 'file'), plural(tally.errors, 'error'),
                      plural(tally.warnings, 'warning')))


def format_text(diagnostics: Iterable[Diagnostic]) -> str:
    """One ``FILE:LINE:COL: severity: message`` line per diagnostic."""
    return ''.join(f'{d}\n' for d in diagnostics)


def format_json(diagnostics: Iterable[Diagnostic]) -> str:
    """A JSON array of diagnostic objects (file, line, column, path, severity, message)."""
    import json

    return json.dumps([d.to_dict() for d in diagnostics], indent=2) + '\n'
