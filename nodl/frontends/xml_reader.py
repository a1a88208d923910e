"""A safe XML reader that keeps the position of every element and attribute.

:func:`load_xml` reads a document (text, bytes, a file object or a path) with
:mod:`xml.parsers.expat` into an :class:`XmlTree` of :class:`XmlElement` objects,
each with the 1-based line and column where it starts; an element's attributes
(:class:`XmlAttribute`) are placed in the start tag when first asked for, so a
reader that only needs their values never pays for it.  It never raises for bad
content: malformed XML is a diagnostic (NODL012), and the tree holds what was
read before the error.  Document type declarations are rejected (NODL013: no
DTD is needed, and entity declarations are how XML bombs work); size and
encoding limits are those of :mod:`nodl.frontends.source`.

The legacy NoDL frontend (:mod:`nodl.frontends.legacy_xml`), the launch
XML frontend and the policy readers are built on it.  Only
:mod:`xml.parsers.expat` is used (it reports positions); dataclasses and
pathlib are not imported at module level, to keep the command line fast.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Callable, Sequence
from functools import partial
from typing import TYPE_CHECKING, Any, NamedTuple
from xml.parsers import expat

from nodl.diagnostics import Diagnostic, Severity

if TYPE_CHECKING:  # pragma: no cover - for type checkers only
    from nodl.frontends.source import Source

__all__ = ['XmlAttribute', 'XmlElement', 'XmlTree', 'load_xml']



class XmlAttribute(NamedTuple):
    """One attribute as written, with the position of its name."""

    name: str
    value: str
    line: int
    column: int


class XmlElement:
    """An element with its attributes (in file order), children and position."""

    __slots__ = ('tag', '_attributes', 'pairs', '_lines', 'children', 'line', 'column', 'text_at')

    def __init__(self, tag: str, attributes: list[XmlAttribute] | None, line: int, column: int, *,
                 pairs: list[str] | None = None, lines: _Lines | None = None) -> None:
        self.tag = tag
        #: The attributes, placed when first read (a reader that never asks where an attribute
        #: is, as the launch reader unless something is wrong, does not pay for placing them).
        self._attributes = attributes
        #: The attribute names and values in the order written: name, value, name, value...
        self.pairs: list[str] = pairs if pairs is not None else [
            part for attribute in attributes or () for part in (attribute.name, attribute.value)]
        self._lines = lines
        self.children: list[XmlElement] = []
        self.line = line
        self.column = column
        #: Where the first non-blank text directly inside the element is, if any.
        self.text_at: tuple[int, int] | None = None

    @property
    def attributes(self) -> list[XmlAttribute]:
        """The attributes in file order, each with the position of its name."""
        if self._attributes is None:
            assert self._lines is not None, 'an element without attributes is made with the lines to place them'
            self._attributes = _place_attributes(self._lines, self.line, self.column, self.pairs)
            self._lines = None
        return self._attributes

    def get(self, name: str) -> XmlAttribute | None:
        """The attribute called ``name``, or None."""
        for attribute in self.attributes:
            if attribute.name == name:
                return attribute
        return None

    def __repr__(self) -> str:
        return f'<XmlElement {self.tag} at {self.line}:{self.column}>'


class XmlTree:
    """A parsed XML file: its root element (None if there is none) and parse problems.

    After a well-formedness error the tree holds what was read before it.
    """

    __slots__ = ('file', 'root', 'diagnostics')

    def __init__(self, file: str, root: XmlElement | None, diagnostics: list[Diagnostic]) -> None:
        self.file = file
        self.root = root
        self.diagnostics = diagnostics


class _Rejected(Exception):
    """Raised inside an expat handler to stop parsing a rejected document."""


_LINE_BREAK = re.compile(r'\r\n|\r|\n')
_ATTRIBUTE = re.compile(r'\s+([^\s=/>]+)\s*=\s*(?:"[^"]*"|\'[^\']*\')')
_TAG_NAME = re.compile(r'<[^\s/>]*')
#: Attribute count -> a start tag with that many attributes (see _start_tag); tags with more
#: attributes than this are placed attribute by attribute.
_START_TAGS: dict[int, re.Pattern[str]] = {}
_MAX_GROUPED = 24
#: ``XmlAttribute(name, value, line, column)`` without the Python-level ``__new__`` a
#: NamedTuple has (a third of the cost of placing an attribute).
_new_attribute: Callable[[tuple[str, str, int, int]], XmlAttribute] = partial(tuple.__new__, XmlAttribute)


class _Lines:
    """Offsets <-> 1-based line and column, counting line breaks as XML does."""

    def __init__(self, text: str) -> None:
        self.text = text
        self._starts: list[int] | None = None

    @property
    def starts(self) -> list[int]:
        """Where each line starts (found when first needed: most documents never need it)."""
        if self._starts is None:
            self._starts = [0] + [m.end() for m in _LINE_BREAK.finditer(self.text)]
        return self._starts

    def offset(self, line: int, column: int) -> int:
        starts = self.starts
        return starts[line - 1] + column - 1 if 0 < line <= len(starts) else -1

    def position(self, offset: int) -> tuple[int, int]:
        starts = self.starts
        index = bisect.bisect_right(starts, offset) - 1
        return index + 1, offset - starts[index] + 1


def _start_tag(count: int) -> re.Pattern[str]:
    """A start tag's name and ``count`` attributes, each name a group (compiled once per count)."""
    pattern = _START_TAGS.get(count)
    if pattern is None:
        pattern = _START_TAGS[count] = re.compile('<[^\\s/>]*' + _ATTRIBUTE.pattern * count)
    return pattern


def _place_attributes(lines: _Lines, line: int, column: int,
                      pairs: Sequence[str]) -> list[XmlAttribute]:
    """Attach to each attribute the position of its name in the start tag."""
    count = len(pairs) // 2
    if not count:
        return []
    text = lines.text
    start = lines.offset(line, column)
    if start >= 0 and count <= _MAX_GROUPED:
        # The usual start tag: one match of a pattern with a group per attribute gives every
        # name's span at once (``regs``); on one line, a column is an offset from the tag's.
        # Expat reports attributes in the order written; the names are compared all the same.
        # Thousands of elements make this the XML reader's hottest loop.
        tag = _start_tag(count).match(text, start)
        if tag is not None and text.find('\n', start, tag.end()) < 0 and \
                text.find('\r', start, tag.end()) < 0:
            spans = tag.regs[1:]
            names = pairs[0::2]
            if [text[i:j] for i, j in spans] == names:
                shift = column - start
                return [_new_attribute((name, value, line, at + shift))
                        for name, value, (at, _) in zip(names, pairs[1::2], spans, strict=True)]
    return _place_attributes_by_name(lines, line, column, pairs, start)


def _place_attributes_by_name(lines: _Lines, line: int, column: int, pairs: Sequence[str],
                              start: int) -> list[XmlAttribute]:
    """:func:`_place_attributes` for a start tag over several lines (or an unexpected one)."""
    text = lines.text
    found: dict[str, tuple[int, int]] = {}
    tag = _TAG_NAME.match(text, start) if start >= 0 else None
    if tag is not None:
        pos = tag.end()
        while True:
            match = _ATTRIBUTE.match(text, pos)
            if match is None:
                break
            at = match.start(1)
            if '\n' in text[start:at] or '\r' in text[start:at]:  # a start tag over several lines
                found.setdefault(match.group(1), lines.position(at))
            else:  # on the tag's line: no search for the line
                found.setdefault(match.group(1), (line, column + at - start))
            pos = match.end()
    out = []
    for index in range(0, len(pairs), 2):
        name = pairs[index]
        at_line, at_column = found.get(name, (line, column))
        out.append(_new_attribute((name, pairs[index + 1], at_line, at_column)))
    return out


def _error(file: str, message: str, line: int = 0, column: int = 0, *, code: str) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, (), file, line, column, code=code)


def _warning(file: str, message: str, line: int = 0, column: int = 0, *, code: str) -> Diagnostic:
    return Diagnostic(Severity.WARNING, message, (), file, line, column, code=code)


_DTD_MESSAGE = ('document type declarations (<!DOCTYPE ...>) are not allowed in NoDL XML: '
                'the format needs no DTD, and entity declarations can expand without '
                'bound (XML bombs); remove the declaration')


#: The expat handlers _parse_xml sets (and unhooks after parsing).
_HANDLERS = ('StartElementHandler', 'EndElementHandler', 'CharacterDataHandler', 'StartDoctypeDeclHandler',
             'EntityDeclHandler', 'XmlDeclHandler')


def _parse_xml(text: str, file: str) -> XmlTree:
    """Parse XML text with expat, keeping positions; rejects DTDs and entities."""
    diagnostics: list[Diagnostic] = []
    lines = _Lines(text)
    stack: list[XmlElement] = []
    roots: list[XmlElement] = []
    parser = expat.ParserCreate(encoding='UTF-8')
    parser.ordered_attributes = True
    parser.buffer_text = True
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)

    def here() -> tuple[int, int]:
        return parser.CurrentLineNumber, parser.CurrentColumnNumber + 1

    def start(tag: str, pairs: list[str]) -> None:
        line, column = here()
        element = XmlElement(tag, None, line, column, pairs=pairs, lines=lines)
        if stack:
            stack[-1].children.append(element)
        else:
            roots.append(element)
        stack.append(element)

    def end(tag: str) -> None:
        stack.pop()

    def characters(data: str) -> None:
        if not stack or stack[-1].text_at is not None:
            return
        stripped = data.lstrip()
        if not stripped:
            return
        line, column = here()
        lead = data[:len(data) - len(stripped)]
        breaks = list(_LINE_BREAK.finditer(lead))
        if breaks:
            line += len(breaks)
            column = len(lead) - breaks[-1].end() + 1
        else:
            column += len(lead)
        stack[-1].text_at = (line, column)

    def reject(*_: Any) -> None:
        # Point at the start of the declaration, not where expat is inside it.
        start = text.rfind('<!', 0, lines.offset(*here()) + 1)
        line, column = lines.position(start) if start >= 0 else here()
        diagnostics.append(_error(file, _DTD_MESSAGE, line, column, code='NODL013'))
        raise _Rejected

    def declaration(version: str | None, encoding: str | None, standalone: int) -> None:
        if encoding and encoding.lower().replace('_', '-') not in ('utf-8', 'utf8'):
            line, column = here()
            diagnostics.append(_warning(
                file, f"the XML declaration says encoding '{encoding}', but NoDL files are "
                'UTF-8 and this one was read as UTF-8; change the declaration', line, column, code='NODL014'))

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = characters
    parser.StartDoctypeDeclHandler = reject
    parser.EntityDeclHandler = reject
    parser.XmlDeclHandler = declaration
    try:
        parser.Parse(text.encode('utf-8'), True)
    except _Rejected:
        pass
    except expat.ExpatError as exc:
        message = expat.ErrorString(exc.code) if exc.code is not None else str(exc)
        diagnostics.append(_error(file, f'malformed XML: {message}', exc.lineno, exc.offset + 1, code='NODL012'))
    finally:
        # The handlers refer to the parser (a reference cycle that would keep the whole
        # tree alive until the next full garbage collection): unhook them now.
        for handler in _HANDLERS:
            setattr(parser, handler, None)
    return XmlTree(file, roots[0] if roots else None, diagnostics)


def load_xml(source: Source, file: str | None = None) -> XmlTree:
    """Read and parse an XML document (text, bytes, a file object or a path).

    Documents over 10 MB, that are not UTF-8, or that contain a DTD are
    rejected with a diagnostic.  I/O errors (a missing file) propagate as
    :class:`OSError`, as in :func:`nodl.check_source`.
    """
    from nodl.frontends.source import read_source

    text, problem = read_source(source, file)
    if text is None:
        assert problem is not None
        return XmlTree(problem.file, None, [problem])
    return _parse_xml(text.text, text.file)

