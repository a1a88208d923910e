"""Python values built straight from libyaml's event stream.

libyaml parses; this module turns its events into dicts, lists and scalars
in one pass, without composing a node tree first (a tree of node objects,
each with two position marks, costs more than parsing itself).  The pass
also enforces what a YAML loader does not:

- duplicate keys are problems (with the first key's line), not silently
  collapsed;
- nesting deeper than :data:`MAX_DEPTH` stops the pass at the collection
  that crosses the limit, so no recursion ever sees a deep document; and
  :func:`read` finds flow collections (``[[[[...``) that cross it on one
  line before libyaml reads them (libyaml's scanner reads a line's tokens
  ahead of its events, and has a nesting limit of its own: the toolkit's
  limit and message come first, whatever the parser's limit is);
- alias expansion is counted as aliases are met (an anchored node's
  expanded size and height are known when it ends), so recursive aliases,
  "billion laughs" and aliases that nest the data too deeply stop the pass
  at the alias, and documents without anchors pay nothing for it;
- tags other than YAML's standard scalar, mapping and sequence tags are
  problems;
- merge keys follow the YAML merge-key specification
  (https://yaml.org/type/merge.html), whatever the installed PyYAML does:
  with ``<<: [*a, *b]`` a key of ``*a`` wins over the same key of ``*b``, and
  a key written in the mapping itself wins over every merged one.

Scalars resolve as PyYAML's ``SafeLoader`` resolves them (YAML 1.1, using
PyYAML's own table of implicit resolvers), except timestamps, which stay
text.  Given a ``spans`` dict, the pass also keeps its source map: for each
mapping and sequence, the positions its keys and values start at (read from
the events libyaml made anyway), so a document path is placed without parsing
the text again (see :func:`span_position`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

import re

import yaml
from yaml.events import (
    AliasEvent,
    MappingEndEvent,
    MappingStartEvent,
    ScalarEvent,
    SequenceEndEvent,
    SequenceStartEvent,
    StreamEndEvent,
)
from yaml.nodes import ScalarNode

from nodl.diagnostics import DocPath

try:
    from yaml._yaml import CParser as _CParser
except ImportError:  # PyYAML built without libyaml
    _CParser = None  # type: ignore[misc, assignment]

__all__ = ['MAX_DEPTH', 'MAX_ALIAS_NODES', 'Stop', 'Problem', 'build', 'event_source', 'read',
           'quote', 'span_position']

MAX_DEPTH = 100
MAX_ALIAS_NODES = 10_000

_STR = 'tag:yaml.org,2002:str'
_INT = 'tag:yaml.org,2002:int'
_FLOAT = 'tag:yaml.org,2002:float'
_BOOL = 'tag:yaml.org,2002:bool'
_NULL = 'tag:yaml.org,2002:null'
_MAP = 'tag:yaml.org,2002:map'
_SEQ = 'tag:yaml.org,2002:seq'
_MERGE = 'tag:yaml.org,2002:merge'
_TIMESTAMP = 'tag:yaml.org,2002:timestamp'

_BOOLS = {'yes': True, 'no': False, 'true': True, 'false': False, 'on': True, 'off': False}
#: PyYAML's table of implicit resolvers (first character -> [(tag, pattern)]): one table.
_IMPLICIT = yaml.resolver.Resolver.yaml_implicit_resolvers
_constructor = yaml.constructor.SafeConstructor()

# Diagnostic codes (see nodl.codes).
SYNTAX = 'NODL003'
MULTIPLE_DOCUMENTS = 'NODL005'
DUPLICATE_KEY = 'NODL006'
DUPLICATE_ANCHOR = 'NODL007'
ALIASES = 'NODL008'
TOO_DEEP = 'NODL009'
CONSTRUCT = 'NODL010'

#: A problem that does not stop the pass: ``(code, message, event, path)``;
#: the event's ``start_mark`` places it.
if TYPE_CHECKING:
    Problem = tuple[str, str, Any, DocPath]
else:
    Problem = tuple


class Stop(Exception):
    """A problem that ends the pass (the document cannot be used at all)."""

    def __init__(self, code: str, message: str, mark: Any) -> None:
        super().__init__(message)
        self.code = code
        self.message = message
        self.mark = mark


class _Marker:
    __slots__ = ('name',)

    def __init__(self, name: str) -> None:
        self.name = name

    def __repr__(self) -> str:
        return self.name


_NO_KEY = _Marker('<no key>')
_MERGE_KEY = _Marker('<<')
_MISS = _Marker('<miss>')


def quote(value: Any) -> str:
    """A key or value for a one-line message: quoted, escaped and not too long."""
    text = str(value)
    if len(text) > 40:
        text = text[:37] + '...'
    return repr(text)


# The source map keeps a position as one int, ``line << _COLUMN_BITS | column`` (0-based),
# rather than libyaml's Mark objects: a thousand documents' marks kept alive made every
# garbage collection of an analysis walk them.  A collection is keyed by its start position
# (two collections never start at the same place).
_COLUMN_BITS = 32
_COLUMN_MASK = (1 << _COLUMN_BITS) - 1


def _position(mark: Any) -> int:
    return mark.line << _COLUMN_BITS | mark.column  # type: ignore[no-any-return]


def event_source(text: str) -> Callable[[], Any]:
    """libyaml's parser for ``text`` (PyYAML's own parser if libyaml is missing): a
    function that returns the next event.  Raises :class:`UnicodeEncodeError` for
    text with a lone surrogate."""
    if _CParser is not None:
        return _CParser(text).get_event
    return yaml.SafeLoader(text).get_event


def read(text: str, spans: dict[Any, Any] | None = None,
         seen: list[tuple[str, Any]] | None = None) -> tuple[Any, list[Problem]]:
    """:func:`build` for ``text``, with the toolkit's nesting limit applied first.

    libyaml's scanner reads the tokens of a line ahead of the events the pass
    sees (up to 1,024 characters), and refuses nesting beyond a limit of its
    own (PyYAML 6.0.4: 1,000 levels) with a message of its own.  So before
    libyaml reads the text, this finds where flow collections (``[``, ``{``)
    may first nest deeper than :data:`MAX_DEPTH` (a quick scan: quoted scalars,
    comments and block scalars skipped where they start a node), and
    reads the text only up to there: if the document does cross the limit,
    the pass stops there with :data:`TOO_DEEP` at the collection that
    crosses it, as it does for any other deep document.  Should a parser
    still refuse nesting (text the scan reads as a scalar), the same
    :class:`Stop` is raised instead of its error.  Raises as :func:`build`."""
    cut = _flow_crossing(text)
    if cut >= 0:
        try:  # (the prefix nests at most MAX_DEPTH + 1 levels: no parser limit in reach)
            build(event_source(text[:cut + 1]))
        except Stop as stop:
            if stop.code == TOO_DEEP:
                raise
        except yaml.YAMLError:
            pass  # (the text ends inside the collection: it did not cross the limit)
    try:
        return build(event_source(text), spans, seen)
    except yaml.YAMLError as exc:
        instead = _parser_nesting_limit(text, exc)
        if instead is None:
            raise
        raise instead from None


#: What the flow scan stops at: flow indicators, quotes, comments, block scalar indicators.
_FLOW_SCAN = re.compile(r'''[\[\]{}"'#|>]''')
_BLOCK_HEADER = re.compile(r'[|>][-+0-9]*[ \t]*(?:#[^\n]*)?(?=\r?\n|$)')
#: After these (spaces between), a quote or ``|``/``>`` starts a node; after anything else
#: (``don't``, ``a 'b'``, ``x > y``) it is part of a plain scalar.
_NODE_STARTS = frozenset('\n[{,:?-')


def _before(text: str, at: int) -> tuple[str, int]:
    """The character before ``at`` on its line, spaces skipped (``'\\n'`` at the line's
    start), and where it is."""
    index = at - 1
    while index >= 0 and text[index] in ' \t':
        index -= 1
    if index < 0 or text[index] == '\r':
        return '\n', index
    return text[index], index


def _starts_node(text: str, at: int) -> bool:
    char, index = _before(text, at)
    if char in _NODE_STARTS:
        return True
    start = index  # a property before it: '&anchor "x"', '!!str "x"'
    while start > 0 and text[start - 1] not in ' \t\r\n[{,':
        start -= 1
    return text[start] in '&!'


def _flow_crossing(text: str) -> int:
    """Where flow collections may first nest deeper than :data:`MAX_DEPTH`: the index of the
    ``[`` or ``{`` that would be level ``MAX_DEPTH + 1``, or -1.

    Brackets inside quoted scalars, comments and block scalars are skipped only where
    those start a node, and a closing bracket outside any flow collection (in a plain
    scalar) does not count, so the count is not lower than the real nesting but for a
    plain scalar that looks like the start of a quoted one (``'tis`` opening a line of a
    multi-line plain scalar): :func:`read` then turns the parser's nesting error into the
    toolkit's."""
    if text.count('[') + text.count('{') <= MAX_DEPTH or not _dense_line(text):
        return -1
    depth = 0
    search = _FLOW_SCAN.search
    at = 0
    while True:
        found = search(text, at)
        if found is None:
            return -1
        index = found.start()
        char = text[index]
        at = index + 1
        if char == '[' or char == '{':
            depth += 1
            if depth > MAX_DEPTH:
                return index
        elif char == ']' or char == '}':
            if depth:
                depth -= 1
        elif char == '#':
            if index == 0 or text[index - 1] in ' \t\r\n':
                end = text.find('\n', index)
                at = len(text) if end < 0 else end
        elif char == '"' or char == "'":
            if _starts_node(text, index):
                at = _quote_end(text, index, char)
        elif depth == 0 and _before(text, index)[0] in '\n:-?':  # '|' or '>' in block context
            header = _BLOCK_HEADER.match(text, index)
            if header is not None:
                at = _block_scalar_end(text, index, header.end())
    return -1


def _dense_line(text: str) -> bool:
    """True if a line holds more than :data:`MAX_DEPTH` ``[`` and ``{``.

    Nesting over several lines reaches the pass before a parser reads far ahead (libyaml
    reads ahead within a line), so the pass itself stops it at level ``MAX_DEPTH + 1``;
    only a line that opens more than ``MAX_DEPTH`` collections can take a parser's
    scanner past a limit of ``2 * MAX_DEPTH`` or more before the pass sees level
    ``MAX_DEPTH + 1`` (and should a parser's limit be lower, :func:`read` still turns
    its error into the toolkit's)."""
    lines = text.split('\n')
    if max(map(len, lines)) <= MAX_DEPTH:  # (most documents: no line is that long)
        return False
    return any(line.count('[') + line.count('{') > MAX_DEPTH
               for line in lines if len(line) > MAX_DEPTH)


def _quote_end(text: str, start: int, quote: str) -> int:
    """Just after the quoted scalar that starts at ``start`` (the text's end if it is not
    closed): ``''`` is a quote in single quotes, a backslash escapes in double quotes."""
    at = start + 1
    while True:
        end = text.find(quote, at)
        if end < 0:
            return len(text)
        if quote == "'":
            if text.startswith("''", end):
                at = end + 2
                continue
            return end + 1
        backslashes = end
        while text[backslashes - 1] == '\\':
            backslashes -= 1
        if (end - backslashes) % 2 == 0:
            return end + 1
        at = end + 1


def _block_scalar_end(text: str, indicator: int, header_end: int) -> int:
    """Where the block scalar whose header ends at ``header_end`` ends: at the first line
    (blank lines aside) indented no more than the node it is the value of (the line's
    indentation, or where the key starts after ``- `` entries: never later than YAML ends it)."""
    line_start = text.rfind('\n', 0, indicator) + 1
    line = text[line_start:indicator]
    stripped = line.lstrip(' ')
    while stripped[:2] in ('- ', '? '):
        stripped = stripped[2:].lstrip(' ')
    parent = len(line) - len(stripped)
    at = text.find('\n', header_end)
    while at >= 0:
        start = at + 1
        end = text.find('\n', start)
        content = text[start:] if end < 0 else text[start:end]
        body = content.lstrip(' ')
        if body.strip() and len(content) - len(body) <= parent:
            return start
        at = end
    return len(text)


def _parser_nesting_limit(text: str, exc: Any) -> Stop | None:
    """A parser's own nesting limit reached (text the flow scan took for a scalar): the
    toolkit's :class:`Stop`, placed at the collection that crosses :data:`MAX_DEPTH`
    (found by PyYAML's Python parser, read up to where the parser stopped)."""
    mark = getattr(exc, 'problem_mark', None)
    if mark is None or 'nesting' not in str(getattr(exc, 'problem', '')):
        return None
    lines = text.split('\n', mark.line + 1)
    offset = sum(len(line) + 1 for line in lines[:mark.line]) + mark.column
    message = (f'document nests deeper than {MAX_DEPTH} levels; NoDL documents are never '
               'this deep')
    try:
        build(yaml.SafeLoader(text[:offset + 1]).get_event)
    except Stop as stop:
        if stop.code == TOO_DEEP:
            return stop
    except yaml.YAMLError:
        pass
    return Stop(TOO_DEEP, message, mark)


def _plain_tag(text: str) -> str:
    for tag, pattern in _IMPLICIT.get(text[:1], ()):
        if pattern.match(text):
            return tag  # type: ignore[no-any-return]
    return _STR


def _unsupported(tag: str) -> str:
    return (f"unsupported YAML tag '{tag}'; NoDL documents use plain mappings, lists, "
            'strings, numbers, booleans and null')


def _construct(tag: str, text: str) -> Any:
    """The value of a scalar with a standard tag; ``_MISS`` if the text cannot be one."""
    if tag in (_STR, _TIMESTAMP):  # NoDL has no date type: keep the text as written
        return text
    try:
        if tag == _INT:
            if text.isascii() and text.isdigit() and (text[0] != '0' or len(text) == 1):
                return int(text)
            return _constructor.construct_yaml_int(ScalarNode(tag, text))
        if tag == _FLOAT:
            return _constructor.construct_yaml_float(ScalarNode(tag, text))
    except (ValueError, IndexError):
        return _MISS
    if tag == _BOOL:
        return _BOOLS.get(text.lower(), _MISS)
    if tag == _NULL:
        return None
    return _MISS


_KINDS = {_INT: 'an integer', _FLOAT: 'a number', _BOOL: 'a boolean'}


def _tagged(event: Any, problems: list[Problem]) -> Any:
    """A scalar with an explicit tag (``!!int "12"``, ``!foo x``)."""
    tag = event.tag
    if tag == '!':  # the non-specific tag: a string
        return event.value
    value = _construct(tag, event.value)
    if value is _MISS:
        kind = _KINDS.get(tag)
        if kind is None:
            problems.append((CONSTRUCT, _unsupported(tag), event, ()))
        else:
            problems.append((CONSTRUCT, f"{quote(event.value)} is not {kind}, but it is tagged "
                             f"'{tag}'; remove the tag or fix the value", event, ()))
        return event.value
    return value


def _path(stack: list[tuple[Any, ...]]) -> DocPath:
    """The document path of the collection being built (for a problem's path)."""
    path: list[Any] = []
    for frame in stack[1:]:
        container, is_map, key = frame[0], frame[1], frame[2]
        path.append(key if is_map else len(container))
    return tuple(path)


def _merged(out: dict[Any, Any], merges: list[tuple[Any, Any]], problems: list[Problem]) -> None:
    """Apply merge keys: earlier merged mappings win over later ones, own keys over all."""
    sources: list[tuple[Any, Any]] = []
    for value, event in merges:
        if isinstance(value, list):
            sources.extend((item, event) for item in value)
        else:
            sources.append((value, event))
    merged: dict[Any, Any] = {}
    for value, event in reversed(sources):
        if isinstance(value, dict):
            merged.update(value)
        else:
            problems.append((CONSTRUCT, 'a merge key (<<) must refer to a mapping', event, ()))
    merged.update(out)
    out.clear()
    out.update(merged)


def build(get_event: Callable[[], Any], spans: dict[Any, Any] | None = None,
          seen: list[tuple[str, Any]] | None = None) -> tuple[Any, list[Problem]]:
    """Read one document's events and return its data and its problems.

    ``get_event`` comes from :func:`event_source`.  Raises :class:`Stop` for
    a problem that makes the document unusable, and PyYAML's ``YAMLError``
    for a syntax error.  With ``spans``, the document's source map is kept
    there (read it with :func:`span_position`; only for a document without
    problems).  With ``seen``, every anchor, alias and merge key is listed
    there in document order, as ``('anchor' | 'alias' | 'merge', mark)``
    (for readers that refuse them, such as rcl's parameter-file parser).
    """
    problems: list[Problem] = []
    get_event()  # StreamStartEvent
    event = get_event()
    if event.__class__ is StreamEndEvent:
        return None, problems  # no document at all
    # Parser state of the collection being built.  ``stack`` holds the
    # enclosing collections' states; the document level is a state with no container.
    cur: Any = None
    is_map = False
    key: Any = _NO_KEY
    key_event: Any = None
    key_events: list[Any] | None = None
    events: list[Any] = []  # where the values of the collection being built start
    merges: list[tuple[Any, Any]] | None = None
    start: Any = None
    anchored: Any = None
    stack: list[tuple[Any, ...]] = []
    root: Any = None
    anchors: dict[str, list[Any]] = {}
    cache: dict[str, Any] = {}  # plain scalar text -> value
    count = 0  # nodes seen, aliases counted as the nodes they expand to
    expanded = 0  # nodes added by aliases
    deepest = 0
    while True:
        event = get_event()
        cls = event.__class__
        if cls is ScalarEvent:
            count += 1
            text = event.value
            if event.tag is not None:
                value = _tagged(event, problems)
            elif event.style:  # quoted or a block scalar: text
                value = text
            else:
                value = cache.get(text, _MISS)
                if value is _MISS:
                    tag = _plain_tag(text)
                    if tag == _MERGE and is_map and key is _NO_KEY:
                        value = _MERGE_KEY
                        if seen is not None:
                            seen.append(('merge', event.start_mark))
                    else:
                        value = _construct(tag, text)
                        if value is _MISS:  # '<<' as a value, '=': tags NoDL has no use for
                            problems.append((CONSTRUCT, _unsupported(tag), event, ()))
                            value = text
                        else:
                            cache[text] = value
            if event.anchor is not None:
                if event.anchor in anchors:
                    _anchor_twice(anchors[event.anchor][1], event)
                anchors[event.anchor] = [value, event, 1, 0]
                if seen is not None:
                    seen.append(('anchor', event.start_mark))
        elif cls is MappingStartEvent or cls is SequenceStartEvent:
            count += 1
            tag = event.tag
            if cls is MappingStartEvent:
                new: Any = {}
                if tag is not None and tag != '!' and tag != _MAP:
                    problems.append((CONSTRUCT, _unsupported(tag), event, ()))
            else:
                new = []
                if tag is not None and tag != '!' and tag != _SEQ:
                    problems.append((CONSTRUCT, _unsupported(tag), event, ()))
            stack.append((cur, is_map, key, key_event, key_events, merges, start, anchored, events))
            cur, is_map, key, key_event, merges, start, anchored = (
                new, cls is MappingStartEvent, _NO_KEY, None, None, event, None)
            key_events = [] if is_map else None
            events = []
            depth = len(stack)
            if event.anchor is not None:
                if event.anchor in anchors:
                    _anchor_twice(anchors[event.anchor][1], event)
                anchors[event.anchor] = [new, event, None, 0]  # open: an alias to it recurses
                if seen is not None:
                    seen.append(('anchor', event.start_mark))
                anchored = (count - 1, deepest)
                deepest = depth - 1
            if depth > deepest:
                deepest = depth
                if depth > MAX_DEPTH:
                    raise Stop(TOO_DEEP, f'document nests deeper than {MAX_DEPTH} levels; NoDL '
                                         'documents are never this deep', event.start_mark)
            continue
        elif cls is MappingEndEvent or cls is SequenceEndEvent:
            value = cur
            event = start
            if merges is not None:
                _merged(value, merges, problems)
            if anchored is not None:
                entry = anchors[start.anchor]
                entry[2] = count - anchored[0]
                entry[3] = deepest - len(stack) + 1
                deepest = max(deepest, anchored[1])
            if spans is not None and merges is None:  # (merged mappings are placed by composing)
                mark = start.start_mark
                # (tuples of ints and strings: the collector stops tracking them)
                spans[mark.line << _COLUMN_BITS | mark.column] = (
                    (tuple(value), tuple([_position(e.start_mark) for e in key_events or ()]),
                     tuple(events)) if is_map else (None, None, tuple(events)))
            cur, is_map, key, key_event, key_events, merges, start, anchored, events = stack.pop()
        elif cls is AliasEvent:
            if seen is not None:
                seen.append(('alias', event.start_mark))
            entry = anchors.get(event.anchor)  # type: ignore[assignment]
            if entry is None:
                raise Stop(SYNTAX, f"YAML alias '*{event.anchor}' refers to no anchor; define "
                                   f"'&{event.anchor}' before using it", event.start_mark)
            value, size, height = entry[0], entry[2], entry[3]
            if size is None:
                raise Stop(ALIASES, 'document contains a recursive YAML alias (an anchor used '
                                    'inside itself)', event.start_mark)
            count += size
            expanded += size
            if expanded > MAX_ALIAS_NODES:
                raise Stop(ALIASES, f'document expands to more than {MAX_ALIAS_NODES:,} nodes '
                                    'through YAML aliases ("billion laughs"); write the content '
                                    'out instead of multiplying it with aliases', event.start_mark)
            if height:
                reach = len(stack) + height
                if reach > MAX_DEPTH:
                    raise Stop(TOO_DEEP, f'document nests deeper than {MAX_DEPTH} levels through '
                                         'YAML aliases; NoDL documents are never this deep',
                               event.start_mark)
                if reach > deepest:
                    deepest = reach
            event = entry[1]  # problems about the value point where it is written
        else:  # DocumentEndEvent
            break
        # Attach ``value`` (whose position is ``event``'s) to the collection being built.
        if is_map:
            if key is _NO_KEY:
                key = value
                key_event = event
                continue
            if key is _MERGE_KEY:
                if merges is None:
                    merges = []
                merges.append((value, event))
            else:
                size = len(cur)
                try:
                    cur[key] = value
                except TypeError:
                    problems.append((CONSTRUCT, 'keys must be plain scalars (strings), not '
                                                'collections', key_event, ()))
                else:
                    if len(cur) == size:
                        problems.append(_duplicate(cur, key, key_event, key_events, stack))
                    else:
                        key_events.append(key_event)  # type: ignore[union-attr]
                        mark = event.start_mark
                        events.append(mark.line << _COLUMN_BITS | mark.column)
            key = _NO_KEY
        elif cur is not None:
            cur.append(value)
            mark = event.start_mark
            events.append(mark.line << _COLUMN_BITS | mark.column)
        else:
            root = value
            if spans is not None:
                spans['root'] = _position(event.start_mark)
    event = get_event()
    if event.__class__ is not StreamEndEvent:
        raise Stop(MULTIPLE_DOCUMENTS, 'the file holds more than one YAML document; put each '
                                       'definition in a file of its own', event.start_mark)
    return root, problems


def span_position(spans: dict[Any, Any], path: DocPath, anchor: str = 'value'
                  ) -> tuple[int, int] | None:
    """1-based ``(line, column)`` of the key (``anchor='key'``) or value at ``path``, from the
    source map :func:`build` kept in ``spans``; None when the map cannot say (a path that does
    not exist, a key that is not a string, a merged mapping): compose the node tree then."""
    mark = spans.get('root')  # (only start positions are kept: the events are let go)
    if mark is None:
        return None
    key_mark = None
    for part in path:
        span = spans.get(mark)
        if span is None:
            return None
        keys, key_marks, marks = span
        if keys is not None:
            # a string key is written as its own text, so it is the key the node tree would find
            if part.__class__ is not str or part not in keys:
                return None
            index = keys.index(part)
            key_mark = key_marks[index]
        else:
            if part.__class__ is not int or not 0 <= part < len(marks):
                return None
            key_mark, index = None, part
        mark = marks[index]
    if anchor == 'key' and key_mark is not None:
        mark = key_mark
    return ((mark >> _COLUMN_BITS) + 1, (mark & _COLUMN_MASK) + 1)


def _anchor_twice(first: Any, event: Any) -> None:
    raise Stop(DUPLICATE_ANCHOR, f'YAML anchor defined twice (first defined at line '
                                 f'{first.start_mark.line + 1}); give each anchor a name of its '
                                 'own', event.start_mark)


def _duplicate(mapping: dict[Any, Any], key: Any, key_event: Any, key_events: Any,
               stack: list[tuple[Any, ...]]) -> Problem:
    first = key_events[list(mapping).index(key)]
    return (DUPLICATE_KEY, f'duplicate key {quote(key)} (first defined at line '
                           f'{first.start_mark.line + 1}); YAML loaders keep only the last value, '
                           'so remove or rename one of them', key_event, _path(stack))
