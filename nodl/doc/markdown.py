"""Pages as MyST Markdown (for Sphinx with myst-parser, and rosdoc2).

Every heading carries an explicit target (``(label)=``) and links name those
targets (``[text](#label)``), never a heading's generated anchor.  Text from a
definition is escaped: every ASCII punctuation character gets a backslash
(CommonMark's escape: no ``*``, ``|``, backtick, ``<script>``, brace or ``$``
can start markup), line breaks become spaces (a table row stays one row), and
control and bidirectional characters are shown as escapes
(:func:`nodl.text_safety.visible`).  Code is fenced with more
backticks than it holds.
"""

from __future__ import annotations

import functools
import re
import string

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
    href,
)
from nodl.text_safety import visible

__all__ = ['render_markdown', 'escape']

_SPACES = re.compile(r'\s+')
#: Every ASCII punctuation character, backslash-escaped.
_ESCAPES = str.maketrans({c: '\\' + c for c in string.punctuation})
_BACKTICKS = re.compile('`+')


@functools.lru_cache(maxsize=8192)  # table cells repeat from page to page
def escape(text: str) -> str:
    """``text`` as literal Markdown text, on one line."""
    if text.isprintable():
        return text.translate(_ESCAPES)
    return _SPACES.sub(' ', visible(text)).translate(_ESCAPES)


def _fence(text: str, char: str = '`') -> str:
    longest = max((len(m) for m in re.findall(re.escape(char) + '+', text)), default=0)
    return char * max(3, longest + 1)


@functools.lru_cache(maxsize=4096)  # pages repeat the same names and types many times over
def _literal(text: str) -> str:
    # printable ASCII is what visible() leaves as it is
    shown = ' '.join((text if text.isascii() and text.isprintable() else visible(text)).split())
    if not shown or '|' in shown or '`' in shown or shown != shown.strip():
        return escape(text)  # a code span cannot hold these safely in a table: plain text
    return f'`{shown}`'


def _inline(parts: tuple[Inline, ...], here: str) -> str:
    out = []
    for part in parts:
        if isinstance(part, Link):
            out.append(f'[{escape(part.text)}]({href(here, part, ".md")})')
        elif isinstance(part, Literal):
            out.append(_literal(part.text))
        else:
            out.append(escape(part))
    return ''.join(out)


def _table(table: Table, here: str) -> str:
    head = '| ' + ' | '.join(escape(c) for c in table.columns) + ' |'
    rule = '|' + '|'.join(' --- ' for _ in table.columns) + '|'
    rows = ['| ' + ' | '.join(_inline(cell, here) for cell in row) + ' |' for row in table.rows]
    return '\n'.join([head, rule, *rows])


def render_markdown(page: Page) -> str:
    """The page as MyST Markdown."""
    chunks: list[str] = []
    for block in page.blocks:
        if isinstance(block, Heading):
            chunks.append(f'({block.label})=\n{"#" * block.level} {escape(block.text)}')
        elif isinstance(block, Paragraph):
            chunks.append(_inline(block.parts, page.path))
        elif isinstance(block, Table):
            chunks.append(_table(block, page.path))
        elif isinstance(block, Code):
            fence = _fence(block.text)
            chunks.append(f'{fence}{block.language}\n{block.text.rstrip()}\n{fence}')
        elif isinstance(block, Note):
            text = _inline(block.parts, page.path)
            fence = _fence(text)
            chunks.append(f'{fence}{{{block.kind}}}\n{text}\n{fence}')
        elif isinstance(block, Picture):
            chunks.append(f'![{escape(block.alt)}]({block.file})')
        elif isinstance(block, Contents):
            pages = '\n'.join(block.pages)
            chunks.append(f'```{{toctree}}\n:hidden:\n\n{pages}\n```')
    return '\n\n'.join(chunks) + '\n'
