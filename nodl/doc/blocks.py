"""The pieces a page is made of: headings, paragraphs, tables, code, notes, a picture.

A page is a list of blocks holding plain text (never markup): each renderer
escapes that text for its format.  Links name a target label and, when the
target is on another page, that page's path; labels are made only of
``[a-z0-9-]`` (:func:`label`), so they are the same explicit target in every
format and never need escaping.
"""

from __future__ import annotations

import functools
import posixpath
import re
from dataclasses import dataclass, field

__all__ = ['Link', 'Literal', 'Inline', 'Heading', 'Paragraph', 'Table', 'Code', 'Note', 'Picture',
           'Contents', 'Block', 'Page', 'label', 'text_of', 'href']


@dataclass(frozen=True)
class Link:
    """A link to the target ``label`` on the page ``page`` (None: this page)."""

    text: str
    label: str
    page: str | None = None


@dataclass(frozen=True)
class Literal:
    """Text shown as code (a name, a type): escaped, in a monospaced font."""

    text: str


#: A piece of running text.
Inline = str | Link | Literal


@dataclass(frozen=True)
class Heading:
    """A heading (level 1 is the page title) with its explicit target."""

    level: int
    text: str
    label: str


@dataclass(frozen=True)
class Paragraph:
    """Running text."""

    parts: tuple[Inline, ...]


@dataclass(frozen=True)
class Table:
    """A table: a header row, then rows of cells (each cell running text)."""

    columns: tuple[str, ...]
    rows: tuple[tuple[tuple[Inline, ...], ...], ...]


@dataclass(frozen=True)
class Code:
    """A block of code (``yaml``, ``text``)."""

    language: str
    text: str


@dataclass(frozen=True)
class Note:
    """An admonition: ``warning`` or ``note``."""

    kind: str
    parts: tuple[Inline, ...]


@dataclass(frozen=True)
class Picture:
    """The system's graph: SVG text (drawn by the analysis's graph), a file name to keep it in
    next to the page, and the words shown where it cannot be drawn."""

    svg: str
    file: str
    alt: str


@dataclass(frozen=True)
class Contents:
    """The pages below this one (for Sphinx's table of contents; HTML links them in a table)."""

    pages: tuple[str, ...]


Block = Heading | Paragraph | Table | Code | Note | Picture | Contents


@dataclass
class Page:
    """One page: where it goes (``rover_base/motor_controller``, without an extension), its
    title's label and its blocks."""

    path: str
    title: str
    label: str
    blocks: list[Block] = field(default_factory=list)

    def heading(self, level: int, text: str, label: str) -> None:
        """Append a heading."""
        self.blocks.append(Heading(level, text, label))

    def paragraph(self, *parts: Inline) -> None:
        """Append a paragraph (nothing for no text)."""
        if any(parts):
            self.blocks.append(Paragraph(tuple(p for p in parts if p)))


_NOT_LABEL = re.compile(r'[^a-z0-9]+')


@functools.lru_cache(maxsize=8192)  # the same labels are made for every page that links them
def label(*parts: str) -> str:
    """An explicit target's name: the parts lowered, every run of other characters a ``-``
    (``('type', 'std_msgs/msg/String')`` -> ``type-std-msgs-msg-string``)."""
    words = (_NOT_LABEL.sub('-', part.lower()).strip('-') for part in parts)
    return '-'.join(w for w in words if w) or 'x'


def text_of(parts: tuple[Inline, ...] | list[Inline]) -> str:
    """The words of running text, without links or code (for tests and plain text)."""
    return ''.join(p if isinstance(p, str) else p.text for p in parts)


def href(here: str, link: Link, extension: str) -> str:
    """The address of ``link`` from the page ``here`` (``a/b``): ``#label`` on the same page,
    else the other page's file relative to this one, with ``#label``."""
    if link.page is None or link.page == here:
        return f'#{link.label}'
    target = posixpath.relpath(link.page + extension, posixpath.dirname(here) or '.')
    return f'{target}#{link.label}'
