"""The YAML/JSON frontend: text to plain data, with positions on demand.

JSON is strict: a file named ``*.json``, or a document whose first
non-blank character is ``{``, is read with :mod:`json` only (exact JSON
number semantics), and text that is not valid JSON there (a comment, a
trailing comma, single quotes, an unquoted key, ``NaN``) is an error at
JSON's line and column, never re-read as YAML.  Anything else is YAML.

YAML is parsed by libyaml, and :mod:`~nodl.frontends.yaml_events`
builds the Python values straight from its event stream, rejecting
duplicate keys (which YAML loaders silently collapse), bounding nesting and
alias expansion, and refusing tags NoDL has no use for.  No node tree is
kept: the same pass keeps a source map (where each key and value starts),
and a document path is turned into ``line:column`` from it; only what the
map cannot place (JSON, a path that does not exist, merge keys) composes the
tree, once per document.

Hostile input is rejected with one clear diagnostic: nesting deeper than
:data:`MAX_DEPTH`, alias expansion beyond :data:`MAX_ALIAS_NODES`, tabs used
for indentation, empty documents and documents that are not a mapping.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

import yaml
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.frontends import yaml_events
from nodl.frontends.source import SourceText
from nodl.frontends.yaml_events import MAX_ALIAS_NODES, MAX_DEPTH
from nodl.text_safety import line_column, locate_unsafe, offset_of

__all__ = ['MAX_DEPTH', 'MAX_ALIAS_NODES', 'ParsedDocument', 'parse_document', 'is_strict_json']

_Loader = getattr(yaml, 'CSafeLoader', yaml.SafeLoader)

_MERGE = 'tag:yaml.org,2002:merge'
#: A JSON string, or one of the constants Python's json accepts and JSON does not.
_CONSTANT = r'"(?:[^"\\]|\\.)*"|(-?Infinity|NaN)'
_JSON_RULES = ('this is read as strict JSON: no comments, trailing commas, single quotes, '
               'unquoted keys or NaN')
JSON_SYNTAX = 'NODL016'


def _error(file: str, message: str, code: str, mark: Any = None, path: DocPath = ()) -> Diagnostic:
    line = mark.line + 1 if mark is not None else 0
    column = mark.column + 1 if mark is not None else 0
    return Diagnostic(Severity.ERROR, message, path, file, line, column, code=code)


class ParsedDocument:
    """A parsed document: its data, parse problems, and a way to place paths."""

    # A plain class: importing dataclasses costs the command line ~15 ms of start-up.
    def __init__(self, source: SourceText, data: Any = None,
                 diagnostics: list[Diagnostic] | None = None, is_json: bool = False) -> None:
        self.source = source
        self.data = data
        self.diagnostics: list[Diagnostic] = diagnostics if diagnostics is not None else []
        self.is_json = is_json
        self._root: Node | None = None
        self._composed = False
        #: The source map of :func:`yaml_events.build` (None: place by composing the tree).
        self._spans: dict[Any, Any] | None = None
        #: The YAML anchors, aliases and merge keys of the text, in order, as ``(kind, line,
        #: column)`` (kind ``anchor``, ``alias`` or ``merge``): for readers that refuse them.
        self.aliasing: list[tuple[str, int, int]] = []

    @property
    def ok(self) -> bool:
        """True if the text parsed into a mapping without errors."""
        return not self.diagnostics and isinstance(self.data, dict)

    def _node_tree(self) -> Node | None:
        if not self._composed:
            self._composed = True
            try:
                self._root = yaml.compose(self.source.text, Loader=_Loader)
            except (yaml.YAMLError, ValueError, RecursionError):
                self._root = None
        return self._root

    def position(self, path: DocPath, anchor: str = 'value') -> tuple[int, int]:
        """1-based ``(line, column)`` of the key or value at ``path``.

        When the path does not exist (a missing key), the deepest existing
        ancestor is used.  ``(0, 0)`` if the text cannot be placed at all.
        The anchors ``key-char`` and ``value-char`` place the first unsafe character (see
        :mod:`nodl.text_safety`) of that key or value, where the text shows it.
        """
        if anchor.endswith('-char'):
            return self._character_position(path, anchor[:-5])
        if self._spans is not None:
            found = yaml_events.span_position(self._spans, path, anchor)
            if found is not None:
                return found
        root = self._node_tree()
        if root is None:
            return (0, 0)
        key_node, node = _walk(root, path)
        mark = key_node.start_mark if anchor == 'key' and key_node is not None else node.start_mark
        return (mark.line + 1, mark.column + 1)

    def _character_position(self, path: DocPath, anchor: str) -> tuple[int, int]:
        line, column = self.position(path, anchor)
        value: Any = self.data
        if anchor == 'key':
            value = path[-1] if path else None
        else:
            for part in path:
                try:
                    value = value[part]
                except (KeyError, IndexError, TypeError):
                    return line, column
        if not line or not isinstance(value, str):
            return line, column
        text = self.source.text
        found = locate_unsafe(text, offset_of(text, line, column), value)
        return line_column(text, found) if found >= 0 else (line, column)

    def place(self, diagnostic: Diagnostic) -> Diagnostic:
        """Return ``diagnostic`` with this document's file, line and column."""
        if diagnostic.line:
            return diagnostic
        line, column = self.position(diagnostic.path, diagnostic.anchor)
        return diagnostic.at(self.source.file, line, column)


def _walk(root: Node, path: DocPath) -> tuple[Node | None, Node]:
    key_node: Node | None = None
    node = root
    for part in path:
        if isinstance(node, MappingNode):
            found = _find_pair(node, part)
            if found is None:
                break
            key_node, node = found
        elif isinstance(node, SequenceNode) and isinstance(part, int) and 0 <= part < len(node.value):
            key_node, node = None, node.value[part]
        else:
            break
    return key_node, node


def _find_pair(mapping: MappingNode, part: Any) -> tuple[Node, Node] | None:
    text = str(part).lower() if isinstance(part, bool) else str(part)
    merged: list[Node] = []
    found: tuple[Node, Node] | None = None
    for key, value in mapping.value:
        if key.tag == _MERGE:
            merged.extend(value.value if isinstance(value, SequenceNode) else [value])
        elif isinstance(key, ScalarNode) and key.value == text:
            found = (key, value)  # the last one wins, as in the data
    if found is None:
        for source in merged:
            if isinstance(source, MappingNode):
                found = _find_pair(source, part)
                if found is not None:
                    break
    return found


def _syntax_problem(exc: yaml.YAMLError, text: str, file: str) -> Diagnostic:
    mark = getattr(exc, 'problem_mark', None)
    problem = getattr(exc, 'problem', None) or str(exc)
    context = getattr(exc, 'context', None) or ''
    if isinstance(exc, yaml.reader.ReaderError):
        line, column = _reader_position(exc, text)
        return Diagnostic(Severity.ERROR, f'document contains a character that is not allowed '
                          f'(#x{exc.character:04x}); NoDL files are UTF-8 text', (), file,
                          line, column, code='NODL002')
    if (mark is not None and ('cannot start any token' in problem or 'tab character' in problem)
            and _char_at(text, mark) == '\t'):
        return _error(file, 'tab character used for indentation; YAML allows only spaces', 'NODL004',
                      mark)
    message = f'YAML syntax error: {problem}' + (f' ({context})' if context else '')
    context_mark = getattr(exc, 'context_mark', None)
    if context_mark is not None and mark is not None and context_mark.line != mark.line:
        message += f'; it starts at line {context_mark.line + 1}, column {context_mark.column + 1}'
    return _error(file, message, 'NODL003', mark)


def _reader_position(exc: Any, text: str) -> tuple[int, int]:
    """1-based line and column of a reader error (libyaml counts UTF-8 bytes)."""
    position = getattr(exc, 'position', None)
    if not isinstance(position, int) or position < 0:
        return (0, 0)
    if exc.encoding != 'unicode':  # libyaml: a byte offset into the UTF-8 text
        position = len(text.encode('utf-8', 'surrogatepass')[:position].decode('utf-8', 'replace'))
    line = text.count('\n', 0, position) + 1
    column = position - (text.rfind('\n', 0, position) + 1) + 1
    return (line, column)


def _char_at(text: str, mark: Any) -> str:
    lines = text.split('\n', mark.line + 1)
    line = lines[mark.line] if mark.line < len(lines) else ''
    return line[mark.column:mark.column + 1]


def _describe_kind(value: Any) -> str:
    if isinstance(value, list):
        return 'a list'
    if isinstance(value, str):
        return 'a string'
    if isinstance(value, bool):
        return 'a boolean'
    if isinstance(value, (int, float)):
        return 'a number'
    return type(value).__name__


def is_strict_json(source: SourceText) -> bool:
    """True if ``source`` is read as strict JSON: a ``.json`` file, or text whose first
    non-blank character is ``{``."""
    file: str = source.file
    if file.lower().endswith('.json'):
        return True
    text: str = source.text
    for char in text:
        if char not in ' \t\r\n':  # JSON's whitespace
            return char == '{'
    return False


def parse_document(source: SourceText) -> ParsedDocument:
    """Parse YAML or JSON text into a :class:`ParsedDocument`.

    Never raises for bad input: every problem becomes a diagnostic.
    """
    doc = ParsedDocument(source)
    if is_strict_json(source):
        _parse_json(doc)
    else:
        _parse_yaml(doc)
    if doc.diagnostics and doc.data is None:
        doc._composed = True  # nothing to place by path; and never compose what was refused
    _check_top(doc)
    return doc


def _parse_yaml(doc: ParsedDocument) -> None:
    text, file = doc.source
    spans: dict[Any, Any] = {}
    seen: list[tuple[str, Any]] = []
    try:
        doc.data, problems = yaml_events.read(text, spans, seen)
    except yaml_events.Stop as stop:
        doc.diagnostics.append(_error(file, stop.message, stop.code, stop.mark))
    except yaml.YAMLError as exc:
        doc.diagnostics.append(_syntax_problem(exc, text, file))
    except UnicodeEncodeError:  # a lone surrogate in a str
        doc.diagnostics.append(_error(file, 'document contains a character that is not valid '
                                            'Unicode text; NoDL files are UTF-8 text', 'NODL002'))
    else:
        if not problems:  # (a duplicate key or a bad key leaves the map behind the data)
            doc._spans = spans
        doc.aliasing = [(kind, mark.line + 1, mark.column + 1) for kind, mark in seen]
        for code, message, event, path in problems:
            doc.diagnostics.append(_error(file, message, code, event.start_mark, path))


class _Constant(Exception):
    """``NaN``, ``Infinity`` or ``-Infinity``: Python's json accepts them, JSON does not."""


def _reject_constant(name: str) -> Any:
    raise _Constant(name)


def _parse_json(doc: ParsedDocument) -> None:
    import json  # not on the command line's start-up path for YAML files

    text, file = doc.source
    doc.is_json = True
    duplicates: list[bool] = []

    def pairs(items: list[tuple[str, Any]]) -> dict[str, Any]:
        result = dict(items)
        if len(result) != len(items):
            duplicates.append(True)
        return result

    try:
        data = json.loads(text, object_pairs_hook=pairs, parse_constant=_reject_constant)
    except json.JSONDecodeError as exc:
        doc.diagnostics.append(Diagnostic(
            Severity.ERROR, f'JSON syntax error: {exc.msg}; {_json_hint(text, exc.pos)}', (), file,
            exc.lineno, exc.colno, code=JSON_SYNTAX))
        return
    except _Constant as exc:
        token = str(exc)
        import re

        where = next((m.start(1) for m in re.finditer(_CONSTANT, text) if m.group(1)), 0)
        line = text.count('\n', 0, where) + 1
        column = where - (text.rfind('\n', 0, where) + 1) + 1
        doc.diagnostics.append(Diagnostic(
            Severity.ERROR, f'JSON syntax error: {token} is not a JSON value; write a number or '
            'null (this is read as strict JSON)', (), file, line, column, code=JSON_SYNTAX))
        return
    except RecursionError:  # far deeper than MAX_DEPTH: placed below
        data = None
        duplicates.append(True)
    doc.data = data
    if duplicates or text.count('[') + text.count('{') > MAX_DEPTH:
        _json_problems(doc, bool(duplicates))


def _json_hint(text: str, pos: int) -> str:
    """What is probably wrong at ``pos``, for the YAML habits JSON does not allow."""
    char = text[pos:pos + 1]
    if char == '/' or char == '#':
        return 'JSON has no comments (this is read as strict JSON)'
    if char == "'":
        return 'JSON strings and keys take double quotes (this is read as strict JSON)'
    if char in ('}', ']') and text[:pos].rstrip().endswith(','):
        return 'JSON allows no trailing comma (this is read as strict JSON)'
    if char.isalpha() or char == '_':
        return 'JSON keys and strings are quoted (this is read as strict JSON)'
    return _JSON_RULES


def _json_problems(doc: ParsedDocument, duplicates: bool) -> None:
    """Duplicate keys and deep nesting in valid JSON, placed by reading it as YAML
    (JSON is YAML flow syntax; json itself reports neither with a position)."""
    text, file = doc.source
    try:
        _, problems = yaml_events.read(text)
    except yaml_events.Stop as stop:
        doc.diagnostics.append(_error(file, stop.message, stop.code, stop.mark))
        doc.data = None
        return
    except (yaml.YAMLError, UnicodeEncodeError):
        problems = []
    for code, message, event, path in problems:
        doc.diagnostics.append(_error(file, message, code, event.start_mark, path))
    if doc.data is None and not doc.diagnostics or _depth(doc.data) > MAX_DEPTH:
        doc.diagnostics.append(_error(file, f'document nests deeper than {MAX_DEPTH} levels; '
                                            'NoDL documents are never this deep', 'NODL009'))
        doc.data = None
    elif duplicates and not doc.diagnostics:
        doc.diagnostics.append(_error(file, 'duplicate key in a JSON object; JSON readers keep only '
                                            'the last value, so remove or rename one of them',
                                      'NODL006'))


def _depth(data: Any) -> int:
    """How deeply lists and mappings nest in loaded data (iteratively)."""
    deepest = 0
    stack = [(data, 1)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, dict):
            item = item.values()
        elif not isinstance(item, list):
            continue
        deepest = max(deepest, depth)
        stack.extend((child, depth + 1) for child in item if isinstance(child, (dict, list)))
    return deepest


def _check_top(doc: ParsedDocument) -> None:
    data = doc.data
    if isinstance(data, dict) or doc.diagnostics:
        return
    file = doc.source.file
    if data is None:
        doc.diagnostics.append(Diagnostic(
            Severity.ERROR, 'document is empty; a NoDL document is a mapping that starts with '
            'nodl_version: 2 (or, for a single parameter definition, type: ...)', (), file, 1, 1,
            code='NODL011'))
    else:
        line, column = doc.position(())
        doc.diagnostics.append(Diagnostic(
            Severity.ERROR, f'document is {_describe_kind(data)}, not a mapping; a NoDL document '
            'is a mapping of keys such as nodl_version, parameters and publishers',
            (), file, line or 1, column or 1, code='NODL011'))
