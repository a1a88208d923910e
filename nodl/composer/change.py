"""What an operation answers: a :class:`Change`, or a :class:`ComposerError` for a file that
cannot be opened (see :mod:`nodl.composer`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from nodl.diagnostics import Diagnostic, Severity

__all__ = ['Change', 'ComposerError']


class ComposerError(Exception):
    """A composition that cannot be opened or made: carries one coded diagnostic."""

    def __init__(self, diagnostic: Diagnostic) -> None:
        super().__init__(diagnostic.message)
        self.diagnostic = diagnostic


@dataclass
class Change:
    """What an operation did: its diagnostics (errors mean nothing changed), the node it
    concerns, and the remapping rules it wrote or removed (``{'node', 'from', 'to'}``)."""

    diagnostics: list[Diagnostic] = field(default_factory=list)
    node: str | None = None
    remaps: list[dict[str, str]] = field(default_factory=list)
    removed: list[dict[str, str]] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """True when no diagnostic is an error (the operation was done)."""
        return not any(d.severity is Severity.ERROR for d in self.diagnostics)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping."""
        return {'ok': self.ok, 'node': self.node, 'remaps': self.remaps, 'removed': self.removed,
                'diagnostics': [d.to_dict() for d in self.diagnostics]}
