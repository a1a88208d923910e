"""A place in a file: the one location type of the toolkit.

The launch reader records where each launched node, remapping rule and parameter source is
written; the resolved node where each entity is declared; findings where they apply.  All
of them are a :class:`Location`, and so is where ``nodl extract`` finds an entity in
source code; each is made once where the text is read and carried from there
(never rebuilt on the way from a launch record to an instance).
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = ['Location']


class Location(NamedTuple):
    """Where something is written: file, 1-based line and column (0 when unknown)."""

    file: str
    line: int = 0
    column: int = 0

    def __str__(self) -> str:
        return f'{self.file}:{self.line}:{self.column}' if self.line else self.file
