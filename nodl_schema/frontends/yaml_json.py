"""The YAML/JSON frontend: text to plain data, with positions on demand.

YAML and JSON are accepted interchangeably; the format is never chosen by
file extension.  Text that looks like JSON is read with :mod:`json` (fast
and exact JSON number semantics); anything else, or JSON that does not
parse, goes through libyaml.

For YAML the C composer builds the node tree (which carries line and column
marks) and this module constructs the Python values itself.  That is faster
than PyYAML's own constructor, lets us reject duplicate keys (which YAML
loaders silently collapse) and bound alias expansion, and keeps the node
tree so that a diagnostic's document path can be turned into
``line:column`` only when there is a diagnostic to place.

Hostile input is rejected with one clear diagnostic: nesting deeper than
:data:`MAX_DEPTH`, alias expansion beyond :data:`MAX_ALIAS_NODES`, tabs used
for indentation, empty documents and documents that are not a mapping.
"""

from __future__ import annotations

import json
import re

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

import yaml
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from nodl_schema.diagnostics import Diagnostic, DocPath, Severity
from nodl_schema.frontends.source import SourceText

__all__ = ['MAX_DEPTH', 'MAX_ALIAS_NODES', 'ParsedDocument', 'parse_document']

MAX_DEPTH = 100
MAX_ALIAS_NODES = 10_000

_Loader = getattr(yaml, 'CSafeLoader', yaml.SafeLoader)

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
_LEADING = re.compile(r'^[ \t?:-]*', re.M)
_constructor = yaml.constructor.SafeConstructor()


def _quote(value: Any) -> str:
    """A key or value for a one-line message: quoted, escaped and not too long."""
    text = str(value)
    if len(text) > 40:
        text = text[:37] + '...'
    return repr(text)


def _error(file: str, message: str, mark: Any = None, path: DocPath = ()) -> Diagnostic:
    line = mark.line + 1 if mark is not None else 0
    column = mark.column + 1 if mark is not None else 0
    return Diagnostic(Severity.ERROR, message, path, file, line, column)


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
        """
        root = self._node_tree()
        if root is None:
            return (0, 0)
        key_node, node = _walk(root, path)
        mark = key_node.start_mark if anchor == 'key' and key_node is not None else node.start_mark
        return (mark.line + 1, mark.column + 1)

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
    found = None
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


class _Builder:
    """Constructs Python values from a composed node tree."""

    def __init__(self) -> None:
        self.problems: list[tuple[str, Any, Node | None]] = []
        self.memo: dict[int, Any] = {}

    def build(self, node: Node) -> Any:
        cls = node.__class__
        if cls is ScalarNode:
            return self.scalar(node)
        memo = self.memo
        key = id(node)
        if key in memo:
            return memo[key]
        if cls is MappingNode:
            out: dict[Any, Any] = {}
            memo[key] = out
            self.mapping(node, out)
            return out
        out_list: list[Any] = []
        memo[key] = out_list
        if node.tag != _SEQ:
            self.unsupported(node)
        build = self.build
        out_list.extend([build(child) for child in node.value])
        return out_list

    def mapping(self, node: MappingNode, out: dict[Any, Any]) -> None:
        if node.tag != _MAP:
            self.unsupported(node)
        build = self.build
        merges: list[Node] | None = None
        first_keys: dict[Any, Node] | None = None
        for key_node, value_node in node.value:
            if key_node.tag == _MERGE:
                merges = (merges or []) + (
                    list(value_node.value) if isinstance(value_node, SequenceNode) else [value_node])
                continue
            key = build(key_node)
            try:
                seen = key in out
            except TypeError:
                self.problems.append(('keys must be plain scalars (strings), not collections',
                                      key_node.start_mark, None))
                continue
            if seen:
                if first_keys is None:
                    first_keys = {}
                    for k_node, _ in node.value:
                        if k_node.tag != _MERGE and isinstance(k_node, ScalarNode):
                            first_keys.setdefault(build(k_node), k_node)
                first = first_keys.get(key)
                where = f' (first defined at line {first.start_mark.line + 1})' if first is not None else ''
                self.problems.append((
                    f'duplicate key {_quote(key)}{where}; YAML loaders keep only the last value, '
                    'so remove or rename one of them', key_node.start_mark, node))
            out[key] = build(value_node)
        if merges:
            merged: dict[Any, Any] = {}
            for source in reversed(merges):
                value = build(source)
                if isinstance(value, dict):
                    merged.update(value)
                else:
                    self.problems.append(('a merge key (<<) must refer to a mapping',
                                          source.start_mark, None))
            merged.update(out)
            out.clear()
            out.update(merged)

    def scalar(self, node: ScalarNode) -> Any:
        tag = node.tag
        value = node.value
        if tag == _STR:
            return value
        if tag == _INT:
            if value.isascii() and value.isdigit() and (value[0] != '0' or len(value) == 1):
                return int(value)
            try:
                return _constructor.construct_yaml_int(node)
            except (ValueError, IndexError):
                return self.invalid(node, 'an integer')
        if tag == _FLOAT:
            try:
                return _constructor.construct_yaml_float(node)
            except (ValueError, IndexError):
                return self.invalid(node, 'a number')
        if tag == _BOOL:
            try:
                return _BOOLS[value.lower()]
            except KeyError:
                return self.invalid(node, 'a boolean')
        if tag == _NULL:
            return None
        if tag == _TIMESTAMP:
            return value  # NoDL has no date type: keep the text as written
        self.unsupported(node)
        return value

    def invalid(self, node: ScalarNode, kind: str) -> str:
        """An explicit tag (``!!int abc``) on a value that is not of that type."""
        self.problems.append((
            f"{_quote(node.value)} is not {kind}, but it is tagged '{node.tag}'; "
            'remove the tag or fix the value', node.start_mark, None))
        return node.value

    def unsupported(self, node: Node) -> None:
        self.problems.append((
            f"unsupported YAML tag '{node.tag}'; NoDL documents use plain mappings, lists, "
            'strings, numbers, booleans and null', node.start_mark, None))


def _depth_bound(text: str) -> int:
    """A cheap upper bound of the nesting depth (exact check only if it is large)."""
    lead = max(map(len, _LEADING.findall(text)), default=0)
    return text.count('[') + text.count('{') + 2 * lead + 2


def _data_depth(data: Any) -> int:
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


def _deep_nesting(text: str, file: str) -> Diagnostic | None:
    depth = 0
    try:
        for event in yaml.parse(text, Loader=_Loader):
            if isinstance(event, yaml.CollectionStartEvent):
                depth += 1
                if depth > MAX_DEPTH:
                    return _error(file, f'document nests deeper than {MAX_DEPTH} levels; '
                                        'NoDL documents are never this deep', event.start_mark)
            elif isinstance(event, yaml.CollectionEndEvent):
                depth -= 1
    except (yaml.YAMLError, ValueError):
        return None  # the composer reports syntax errors with better context
    return None


def _alias_problem(root: Node, file: str) -> Diagnostic | None:
    """Reject recursive aliases, alias expansion beyond MAX_ALIAS_NODES, and
    aliases that nest the data deeper than MAX_DEPTH collection levels."""
    sizes: dict[int, int] = {}
    heights: dict[int, int] = {}  # collection levels in a node's expanded subtree
    on_stack: set[int] = set()
    shared: list[Node] = []
    too_deep: list[Node] = []

    def size(node: Node, depth: int) -> int | None:
        # ``depth``: collection levels above ``node`` in the expanded data.
        key = id(node)
        if key in sizes:
            shared.append(node)
            if depth + heights[key] > MAX_DEPTH and not too_deep:
                too_deep.append(node)
            return sizes[key]
        if key in on_stack:
            return None
        total = 1
        height = 0
        if isinstance(node, (MappingNode, SequenceNode)):
            on_stack.add(key)
            children = node.value if isinstance(node, SequenceNode) else [n for pair in node.value for n in pair]
            for child in children:
                child_size = size(child, depth + 1)
                if child_size is None:
                    return None
                total += child_size
                height = max(height, heights.get(id(child), 0))
                if total > MAX_ALIAS_NODES + len(sizes) + 1:
                    break
            on_stack.discard(key)
            height += 1
        sizes[key] = total
        heights[key] = height
        return total

    expanded = size(root, 0)
    if expanded is None:
        return _error(file, 'document contains a recursive YAML alias (an anchor used inside itself)',
                      root.start_mark)
    if expanded - len(sizes) > MAX_ALIAS_NODES:
        worst = max(shared, key=lambda n: sizes[id(n)], default=root)
        return _error(file, f'document expands to more than {MAX_ALIAS_NODES:,} nodes through YAML '
                            'aliases ("billion laughs"); write the content out instead of '
                            'multiplying it with aliases', worst.start_mark)
    if too_deep:
        return _error(file, f'document nests deeper than {MAX_DEPTH} levels through YAML aliases; '
                            'NoDL documents are never this deep', too_deep[0].start_mark)
    return None


def _syntax_problem(exc: yaml.YAMLError, text: str, file: str) -> Diagnostic:
    mark = getattr(exc, 'problem_mark', None)
    problem = getattr(exc, 'problem', None) or str(exc)
    context = getattr(exc, 'context', None) or ''
    if isinstance(exc, yaml.reader.ReaderError):
        line, column = _reader_position(exc, text)
        return Diagnostic(Severity.ERROR, f'document contains a character that is not allowed '
                          f'(#x{exc.character:04x}); NoDL files are UTF-8 text', (), file,
                          line, column)
    if (mark is not None and ('cannot start any token' in problem or 'tab character' in problem)
            and _char_at(text, mark) == '\t'):
        return _error(file, 'tab character used for indentation; YAML allows only spaces', mark)
    if 'duplicate anchor' in context:
        first = getattr(exc, 'context_mark', None)
        where = f' (first defined at line {first.line + 1})' if first is not None else ''
        return _error(file, f'YAML anchor defined twice{where}; give each anchor a name of its own',
                      mark)
    if 'expected a single document' in problem + context:
        return _error(file, 'the file holds more than one YAML document; '
                            'put each definition in a file of its own', mark)
    message = f'YAML syntax error: {problem}' + (f' ({context})' if context else '')
    context_mark = getattr(exc, 'context_mark', None)
    if context_mark is not None and mark is not None and context_mark.line != mark.line:
        message += f'; it starts at line {context_mark.line + 1}, column {context_mark.column + 1}'
    return _error(file, message, mark)


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


def parse_document(source: SourceText) -> ParsedDocument:
    """Parse YAML or JSON text into a :class:`ParsedDocument`.

    Never raises for bad input: every problem becomes a diagnostic.
    """
    text = source.text
    file = source.file
    doc = ParsedDocument(source)
    head = text.lstrip()[:1]
    if head in ('{', '['):
        duplicates: list[bool] = []

        def pairs_hook(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
            result = dict(pairs)
            if len(result) != len(pairs):
                duplicates.append(True)
            return result

        try:  # the C scanner raises RecursionError, it does not crash, on deep nesting
            data = json.loads(text, object_pairs_hook=pairs_hook)
        except (ValueError, RecursionError):
            pass  # not JSON after all (YAML flow style is a superset), or far too deep
        else:
            if not duplicates and _data_depth(data) <= MAX_DEPTH:
                doc.data = data
                doc.is_json = True
                _check_top(doc)
                return doc
            # duplicates or deep nesting: the YAML path below places them

    # libyaml's composer recurses in C: nesting must be bounded before it runs.
    if _depth_bound(text) > MAX_DEPTH:
        problem = _deep_nesting(text, file)
        if problem is not None:
            doc.diagnostics.append(problem)
            return doc

    try:
        root = yaml.compose(text, Loader=_Loader)
    except yaml.YAMLError as exc:
        doc.diagnostics.append(_syntax_problem(exc, text, file))
        return doc
    except RecursionError:
        doc.diagnostics.append(_error(file, f'document nests deeper than {MAX_DEPTH} levels'))
        return doc
    except UnicodeEncodeError:  # a lone surrogate in a str
        doc.diagnostics.append(_error(file, 'document contains a character that is not valid '
                                            'Unicode text; NoDL files are UTF-8 text'))
        return doc
    doc._root = root
    doc._composed = True
    if root is None:
        _check_top(doc)  # data is None: the document is empty
        return doc
    if '*' in text:
        problem = _alias_problem(root, file)
        if problem is not None:
            doc.diagnostics.append(problem)
            return doc
    builder = _Builder()
    doc.data = builder.build(root)
    if builder.problems:
        paths = _paths_of(root, {id(m) for _, _, m in builder.problems if m is not None})
        for message, mark, mapping in builder.problems:
            path = paths.get(id(mapping), ()) if mapping is not None else ()
            doc.diagnostics.append(_error(file, message, mark, path))
    _check_top(doc)
    return doc


def _check_top(doc: ParsedDocument) -> None:
    data = doc.data
    if isinstance(data, dict) or doc.diagnostics:
        return
    file = doc.source.file
    if data is None:
        doc.diagnostics.append(Diagnostic(
            Severity.ERROR, 'document is empty; a NoDL document is a mapping that starts with '
            'nodl_version: 2 (or, for a single parameter definition, type: ...)', (), file, 1, 1))
    else:
        line, column = doc.position(())
        doc.diagnostics.append(Diagnostic(
            Severity.ERROR, f'document is {_describe_kind(data)}, not a mapping; a NoDL document '
            'is a mapping of keys such as nodl_version, parameters and publishers',
            (), file, line or 1, column or 1))


def _paths_of(root: Node, targets: set[int]) -> dict[int, DocPath]:
    """The document paths of the nodes in ``targets`` (by id), in one walk of the tree."""
    keys = _Builder()  # its own: building keys again must not add to the reported problems
    found: dict[int, DocPath] = {}
    stack: list[tuple[Node, DocPath]] = [(root, ())]
    seen: set[int] = set()
    while stack and len(found) < len(targets):
        node, path = stack.pop()
        if id(node) in targets:
            found.setdefault(id(node), path)
        if id(node) in seen:
            continue
        seen.add(id(node))
        if isinstance(node, MappingNode):
            for key, value in node.value:
                if isinstance(key, ScalarNode):
                    stack.append((value, path + (keys.scalar(key),)))
        elif isinstance(node, SequenceNode):
            stack.extend((child, path + (i,)) for i, child in enumerate(node.value))
    return found
