"""Pages as reStructuredText (for Sphinx).

Every heading is preceded by its explicit target (``.. _label:``) and links
are ``:ref:`` roles to those targets.  Text from a definition is escaped:
every ASCII punctuation character gets a backslash (no ``*``, ``|``,
backtick, ``_`` or ``..`` can start markup), line breaks become spaces (a
table cell stays one cell), control and bidirectional characters are shown
as escapes.  Inline markup next to a word is separated by an escaped space,
which reStructuredText reads as nothing.
"""

from __future__ import annotations

import re
import string
import unicodedata

from nodl.doc.blocks import (
    Code,
    Contents,
    Heading,
    Inline,
    Link,
    Literal,
    Note,
    Page,
    Paragraph,
    Picture,
    Table,
)
from nodl.text_safety import visible

__all__ = ['render_rst', 'escape']

_SPACES = re.compile(r'\s+')
#: Every ASCII punctuation character, backslash-escaped.
_ESCAPES = str.maketrans({c: '\\' + c for c in string.punctuation})
_UNDERLINES = {1: '=', 2: '-', 3: '~', 4: '^', 5: '"'}


def escape(text: str) -> str:
    """``text`` as literal reStructuredText, on one line."""
    shown = text if text.isprintable() else _SPACES.sub(' ', visible(text))
    return shown.translate(_ESCAPES)


def _width(text: str) -> int:
    return sum(2 if unicodedata.east_asian_width(c) in 'WF' else 1 for c in text)


def _markup(part: Link | Literal) -> str | None:
    shown = ' '.join(visible(part.text).split())
    if isinstance(part, Link):
        return f':ref:`{escape(part.text)} <{part.label}>`'
    if not shown or '`' in shown or '\\' in shown:
        return None  # an inline literal cannot hold these: plain text instead
    return f'``{shown}``'


def _inline(parts: tuple[Inline, ...]) -> str:
    out = ''
    for part in parts:
        markup = _markup(part) if isinstance(part, (Link, Literal)) else None
        if markup is None:
            out += escape(part if isinstance(part, str) else part.text)
            continue
        if out and not out[-1].isspace():
            out += '\\ '  # inline markup must follow a space: an escaped one reads as nothing
        out += markup + '\\ '
    return out.replace('\\ \\ ', '\\ ').removesuffix('\\ ')


def _table(table: Table) -> str:
    lines = ['.. list-table::', '   :header-rows: 1', '']
    for row in ((tuple((c,) for c in table.columns)), *table.rows):
        for i, cell in enumerate(row):
            text = _inline(cell)
            lines.append(f'   {"* -" if i == 0 else "  -"} {text}'.rstrip())
    return '\n'.join(lines)


def render_rst(page: Page) -> str:
    """The page as reStructuredText."""
    chunks: list[str] = []
    for block in page.blocks:
        if isinstance(block, Heading):
            text = escape(block.text)
            line = _UNDERLINES.get(block.level, '"') * max(_width(text), 4)
            over = f'{line}\n' if block.level == 1 else ''
            chunks.append(f'.. _{block.label}:\n\n{over}{text}\n{line}')
        elif isinstance(block, Paragraph):
            chunks.append(_inline(block.parts))
        elif isinstance(block, Table):
            chunks.append(_table(block))
        elif isinstance(block, Code):
            body = '\n'.join(f'   {line}'.rstrip() for line in block.text.rstrip().splitlines())
            chunks.append(f'.. code-block:: {block.language}\n\n{body}')
        elif isinstance(block, Note):
            chunks.append(f'.. {block.kind}::\n\n   {_inline(block.parts)}')
        elif isinstance(block, Picture):
            chunks.append(f'.. image:: {block.file}\n   :alt: {escape(block.alt)}')
        elif isinstance(block, Contents):
            pages = '\n'.join(f'   {p}' for p in block.pages)
            chunks.append(f'.. toctree::\n   :hidden:\n\n{pages}')
    return '\n\n'.join(chunks) + '\n'
