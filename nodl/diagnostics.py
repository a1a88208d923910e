"""Diagnostics: what every check yields, and the one exception the API raises.

Checks never raise for a problem in a user's document.  They yield
:class:`Diagnostic` objects that say what is wrong, where (file, line,
column and document path) and how bad it is.  The outer API collects them
all and raises :class:`ValidationError` once, carrying every one.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from nodl.text_safety import visible

__all__ = [
    'Severity',
    'Diagnostic',
    'ValidationError',
    'DocPath',
    'format_path',
    'Diagnosed',
]

#: A location inside a document: mapping keys and sequence indices.
if TYPE_CHECKING:
    DocPath = tuple[str | int, ...]
else:
    DocPath = tuple


class Severity(str, enum.Enum):
    """How bad a diagnostic is. Only errors make a document invalid."""

    ERROR = 'error'
    WARNING = 'warning'
    INFO = 'info'

    def __str__(self) -> str:
        """``FILE:LINE:COL: severity: message [path] [CODE]`` (position, path and code when known)."""
        return self.value


_PLAIN_KEY_CHARS = frozenset('abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_<>:')


def format_path(path: DocPath) -> str:
    """Render a document path: ``main.parameters.gain.default_value``.

    Sequence indices are written ``[0]``; keys that are not plain words
    (for example a parameter called ``pid.kp``) are quoted: ``["pid.kp"]``.
    """
    out: list[str] = []
    for part in path:
        if isinstance(part, int) and not isinstance(part, bool):
            out.append(f'[{part}]')
            continue
        if not isinstance(part, str):  # YAML allows keys such as null, true or 1.5
            part = 'null' if part is None else str(part).lower() if isinstance(part, bool) else str(part)
        if part and set(part) <= _PLAIN_KEY_CHARS:
            out.append(f'.{part}' if out else part)
        else:
            quoted = part.replace('\\', '\\\\').replace('"', '\\"')
            if not quoted.isprintable():  # a path is shown on one line: no control or bidi character
                quoted = visible(quoted, one_line=True)
            out.append(f'["{quoted}"]')
    return ''.join(out)


class Diagnostic:
    """One problem (or remark) found in a document.

    ``line`` and ``column`` are 1-based; 0 means the position is unknown
    (for example for a document given as a plain dict).  ``anchor`` says
    whether the diagnostic points at a mapping ``key`` or at its ``value``.
    Diagnostics are immutable values.
    """

    __slots__ = ('severity', 'message', 'path', 'file', 'line', 'column', 'anchor', 'code', 'related')
    _FIELDS = __slots__

    severity: Severity
    message: str
    path: DocPath
    file: str
    line: int
    column: int
    anchor: str
    #: The stable code (``NODL101``); see :mod:`nodl.codes`. Empty when not yet coded.
    code: str
    #: Other places that matter (for example the layer a value overrides): ``(file, line, column, message)``.
    related: tuple[tuple[str, int, int, str], ...]

    def __init__(self, severity: Severity, message: str, path: DocPath = (), file: str = '<string>',
                 line: int = 0, column: int = 0, anchor: str = 'value', code: str = '',
                 related: Iterable[tuple[str, int, int, str]] = ()) -> None:
        # A plain class rather than a dataclass: importing dataclasses costs
        # the command line ~20 ms of start-up.
        set_ = object.__setattr__
        set_(self, 'severity', Severity(severity))
        set_(self, 'message', message)
        set_(self, 'path', tuple(path))
        set_(self, 'file', file)
        set_(self, 'line', line)
        set_(self, 'column', column)
        set_(self, 'anchor', anchor)
        set_(self, 'code', code)
        set_(self, 'related', tuple(related))

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError('Diagnostic is immutable; use .at() or .replace()')

    def __reduce__(self) -> tuple[Any, ...]:
        # Pickled by its fields (a launch read in a child process sends its diagnostics back).
        return (Diagnostic, tuple(getattr(self, f) for f in self._FIELDS))

    def _key(self) -> tuple[Any, ...]:
        return tuple(getattr(self, f) for f in self._FIELDS)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Diagnostic) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        fields = ', '.join(f'{f}={getattr(self, f)!r}' for f in self._FIELDS)
        return f'Diagnostic({fields})'

    def replace(self, **changes: Any) -> Diagnostic:
        """A copy with some fields changed."""
        values = {f: getattr(self, f) for f in self._FIELDS}
        values.update(changes)
        return Diagnostic(**values)

    @property
    def path_text(self) -> str:
        """The document path as text (``main.publishers[0].type``)."""
        return format_path(self.path)

    def at(self, file: str, line: int, column: int) -> Diagnostic:
        """Return a copy placed at ``file:line:column``."""
        return self.replace(file=file, line=line, column=column)

    def __str__(self) -> str:
        """``FILE:LINE:COL: severity: message [path] [CODE]`` (position, path and code when known)."""
        where = self.file
        if self.line:
            where += f':{self.line}:{self.column}'
        text = f'{where}: {self.severity}: {self.message}'
        if self.path:
            text += f' [{self.path_text}]'
        if self.code:
            text += f' [{self.code}]'
        return text

    def to_dict(self) -> dict[str, object]:
        """The diagnostic as a JSON-ready mapping.

        ``related`` is a list of ``{file, line, column, message}`` objects.
        """
        return {
            'file': self.file,
            'line': self.line,
            'column': self.column,
            'path': self.path_text,
            'severity': self.severity.value,
            'code': self.code,
            'message': self.message,
            'related': [{'file': f, 'line': li, 'column': c, 'message': m}
                        for f, li, c, m in self.related],
        }


class Diagnosed:
    """What a result holding ``diagnostics`` says of them: its ``errors`` and whether it is
    ``ok`` (no error).  A mixin (no slots of its own) for the readers' results."""

    __slots__ = ()
    diagnostics: list[Diagnostic]

    @property
    def errors(self) -> list[Diagnostic]:
        """The diagnostics of severity error."""
        return [d for d in self.diagnostics if d.severity is Severity.ERROR]

    @property
    def ok(self) -> bool:
        """True if no diagnostic is an error."""
        return not self.errors


def has_errors(diagnostics: Iterable[Diagnostic], strict: bool = False) -> bool:
    """True if any diagnostic is an error (with ``strict``, a warning too)."""
    failing = (Severity.ERROR, Severity.WARNING) if strict else (Severity.ERROR,)
    return any(d.severity in failing for d in diagnostics)


class ValidationError(ValueError):
    """An invalid NoDL document. Carries every diagnostic found, not just the first."""

    def __init__(self, diagnostics: Sequence[Diagnostic]):
        self.diagnostics: list[Diagnostic] = list(diagnostics)
        super().__init__('\n'.join(str(d) for d in self.errors or self.diagnostics))

    @property
    def errors(self) -> list[Diagnostic]:
        """Only the diagnostics of severity error."""
        return [d for d in self.diagnostics if d.severity is Severity.ERROR]
