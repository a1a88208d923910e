"""Writing a document: every item's gap and text in order, counting lines.

The writers of the three formats share the walk: an item that is not edited is written
as read; an edited or new one is written by the format's ``node``/``group`` functions.
Each node's lines in the written text are recorded (:attr:`Rendered.spans`), so that what
the launch reader reports about the written file (a launched node's place) leads back to
the composition's node.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from nodl.composer.model import ComposedNode, Document, Group, Item, Kept

__all__ = ['Output', 'Rendered', 'reindent', 'render_document']


@dataclass
class Rendered:
    """A document's text and where each node is in it."""

    text: str
    #: node id -> (first line, last line), 1-based, inclusive.
    spans: dict[str, tuple[int, int]] = field(default_factory=dict)


class Output:
    """Text being written, with the current line (1-based)."""

    def __init__(self) -> None:
        self.parts: list[str] = []
        self.line = 1

    def write(self, text: str) -> None:
        """Append ``text``."""
        self.parts.append(text)
        self.line += text.count('\n')

    def text(self) -> str:
        """Everything written."""
        return ''.join(self.parts)


def reindent(text: str, old_column: int, new_indent: str) -> str:
    """``text`` that started at ``old_column`` moved to start after ``new_indent``: every line
    after the first shifted by the difference (lines less indented are left as they are)."""
    delta = len(new_indent) - old_column
    if delta == 0 or '\n' not in text:
        return text
    lines = text.split('\n')
    out = [lines[0]]
    for line in lines[1:]:
        if delta > 0:
            out.append(' ' * delta + line if line.strip() else line)
        else:
            cut = min(-delta, len(line) - len(line.lstrip(' ')))
            out.append(line[cut:])
    return '\n'.join(out)


NodeWriter = Callable[[ComposedNode, str], str]
GroupWriter = Callable[[Group, str], tuple[str, str]]


def render_document(doc: Document, node_text: NodeWriter, group_text: GroupWriter,
                    separator: str = '') -> Rendered:
    """The text of ``doc``: ``node_text(node, indent)`` writes an edited node,
    ``group_text(group, indent)`` an edited group's opening and closing text; ``separator``
    goes after every item but the last (the comma of a Python list), and after the last
    too when ``doc.style['trailing_separator']``."""
    out = Output()
    rendered = Rendered('')
    out.write(doc.header)
    _items(doc.items, out, rendered, node_text, group_text, separator,
           bool(doc.style.get('trailing_separator')))
    out.write(doc.close_gap)
    out.write(doc.trailer)
    rendered.text = out.text()
    return rendered


def _items(items: list[Item], out: Output, rendered: Rendered, node_text: NodeWriter,
           group_text: GroupWriter, separator: str, trailing: bool) -> None:
    for index, item in enumerate(items):
        out.write(item.gap)
        if isinstance(item, Group):
            if item.dirty or item.original is None:
                opening, closing = group_text(item, item.indent)
            else:
                opening, closing = item.open_text, item.close_text
            out.write(opening)
            _items(item.items, out, rendered, node_text, group_text, separator,
                   bool(item.style.get('trailing_separator')))
            out.write(item.close_gap)
            out.write(closing)
        elif isinstance(item, ComposedNode):
            start = out.line
            if item.dirty or item.original is None:
                text = node_text(item, item.indent)
                out.write(text)
                _child_spans(item, text, start, rendered, fresh=True)
            else:
                out.write(item.original)
                _child_spans(item, item.original, start, rendered, fresh=False)
            rendered.spans[item.id] = (start, out.line)
        else:
            assert isinstance(item, Kept)
            out.write(item.text)
        if index < len(items) - 1 or trailing:
            out.write(separator)


def _child_spans(node: ComposedNode, text: str, start: int, rendered: Rendered,
                 fresh: bool) -> None:
    """The spans of a container's composable nodes: each is found in the written text by
    the marker its writer puts in (``style['written_at']``, the line offset), or, for a
    container written as read, by the line each was read at."""
    for child in node.children:
        if fresh:
            offset = child.style.get('written_at', 0)
            lines = child.style.get('written_lines', 0)
        else:
            offset = child.line - node.line
            lines = (child.original or '').count('\n')
        rendered.spans[child.id] = (start + offset, start + offset + lines)
