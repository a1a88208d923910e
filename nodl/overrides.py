"""Silencing and promoting diagnostic codes: ``--ignore`` / ``--error``, and file directives.

Three sources say what to do with a code, from the weakest to the strongest:

1. a file's own first comment lines: ``# nodl: ignore=NODL216`` silences
   warnings and infos of those codes in that file (never an error, which then says
   the directive does not silence it: a file cannot hide its own errors; this is
   what ``nodl describe`` and ``nodl convert`` write, as they cannot know
   descriptions);
2. the nearest ``nodl.toml`` or ``pyproject.toml`` ``[tool.nodl]`` table
   (:mod:`nodl.config`);
3. the command line (``--ignore CODE``, ``--error CODE``), which wins.

This module is used by every verb that reports diagnostics (``validate``,
``check`` and the analysis verbs to come): one :class:`Overrides` value, one
:func:`apply_overrides`.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from nodl.diagnostics import Diagnostic, Severity

__all__ = ['Overrides', 'apply_overrides', 'parse_code_list', 'directive_codes',
           'apply_directives', 'DIRECTIVE']

#: The comment a file uses to silence warnings of some codes for itself.
DIRECTIVE = '# nodl: ignore='

_DIRECTIVE = re.compile(r'#\s*nodl:\s*ignore\s*=\s*([A-Za-z0-9_,\s]+)')
_CODE = re.compile(r'NODL[0-9]{3}')


class Overrides:
    """Which codes to drop (``ignore``) and which to report as errors (``error``)."""

    __slots__ = ('ignore', 'error')

    def __init__(self, ignore: Iterable[str] = (), error: Iterable[str] = ()) -> None:
        self.ignore = frozenset(ignore)
        self.error = frozenset(error)

    def __bool__(self) -> bool:
        return bool(self.ignore or self.error)

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Overrides) and self.ignore == other.ignore
                and self.error == other.error)

    def __hash__(self) -> int:
        return hash((self.ignore, self.error))

    def __repr__(self) -> str:
        return f'Overrides(ignore={sorted(self.ignore)!r}, error={sorted(self.error)!r})'

    def then(self, stronger: Overrides) -> Overrides:
        """These overrides with ``stronger`` ones on top (a code in both: ``stronger`` wins)."""
        return Overrides((self.ignore - stronger.error) | stronger.ignore,
                         (self.error - stronger.ignore) | stronger.error)


def apply_overrides(diagnostics: Iterable[Diagnostic], overrides: Overrides) -> list[Diagnostic]:
    """Drop the ignored codes and turn the promoted ones into errors.

    Diagnostics without a code are kept as they are.
    """
    if not overrides:
        return list(diagnostics)
    out: list[Diagnostic] = []
    for d in diagnostics:
        if d.code in overrides.ignore:
            continue
        if d.code in overrides.error and d.severity is not Severity.ERROR:
            d = d.replace(severity=Severity.ERROR)
        out.append(d)
    return out


def parse_code_list(values: Iterable[str]) -> tuple[list[str], list[str]]:
    """Split repeatable, comma-separated option values into codes.

    Returns ``(codes, unknown)``: codes are upper-cased; ``unknown`` lists the
    words that are not catalogued codes (the caller reports them, with
    :func:`nodl.codes.close_codes` for a hint).
    """
    from nodl.codes import CODES

    codes: list[str] = []
    unknown: list[str] = []
    for value in values:
        for word in value.split(','):
            word = word.strip().upper()
            if not word:
                continue
            (codes if word in CODES else unknown).append(word)
    return codes, unknown


def directive_codes(text: str) -> frozenset[str]:
    """The codes a document silences for itself in its leading comment lines.

    Only comment lines before the first line of content count, so that a
    directive cannot hide in the middle of a file.
    """
    if not text.lstrip().startswith('#') or 'nodl:' not in text:
        return frozenset()
    found: set[str] = set()
    for line in text.splitlines():
        stripped = line.strip()
        if not stripped:
            continue
        if not stripped.startswith('#'):
            break
        match = _DIRECTIVE.match(stripped)
        if match:
            found.update(_CODE.findall(match.group(1).upper()))
    return frozenset(found)


def apply_directives(text: str, diagnostics: list[Diagnostic]) -> list[Diagnostic]:
    """Drop the warnings and infos a document's directive silences.

    Errors always stay: a file cannot hide its own errors (a definition holding a Trojan
    Source character, NODL220, cannot silence it from inside), only ``--ignore`` and the
    configuration can.  An error whose code the directive names says so in its message.
    """
    if not diagnostics:
        return diagnostics
    codes = directive_codes(text)
    if not codes:
        return diagnostics
    out: list[Diagnostic] = []
    for d in diagnostics:
        if d.code not in codes:
            out.append(d)
        elif d.severity is Severity.ERROR:
            out.append(d.replace(message=f"{d.message} (the file's '{DIRECTIVE}{d.code}' does not "
                                 'silence it: a file cannot hide its own errors; --ignore '
                                 f'{d.code} or a nodl.toml can)'))
    return out
