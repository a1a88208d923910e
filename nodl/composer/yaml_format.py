"""Launch YAML: read into items with the exact text of each, written back as read or anew.

Each entry of the ``launch:`` list (``- node: ...``) is an item; its text runs from its
``-`` to the end of its last value (comments after it belong to the next item's gap).  A
``node``/``node_container``'s ``param`` entries ``{name: ..., value: ...}`` and ``remap``
entries ``{from: ..., to: ...}`` with literal text are editable; everything else is kept
verbatim (moved as a block when the entry is written anew).
"""

from __future__ import annotations

from typing import Any

import yaml
from yaml.nodes import MappingNode, ScalarNode, SequenceNode

from nodl.composer.model import ComposedNode, Document, Group, Item, Kept, Param, Remap
from nodl.composer.rendering import reindent
from nodl.composer.values import yaml_needs_type, yaml_value_text
from nodl.composer.xml_format import ReadError
from nodl.launch.params import get_typed_value, type_from_identifier

__all__ = ['group_yaml', 'new_yaml', 'node_yaml', 'push_yaml', 'read_yaml']

_NODE_KEYS = ('pkg', 'exec', 'name', 'namespace')
_COMPOSABLE_KEYS = ('pkg', 'plugin', 'name', 'namespace')
_PUSH = ('push-ros-namespace', 'push_ros_namespace')


def _end(node: Any) -> int:
    """The index after the last character of a YAML node's own text."""
    if isinstance(node, MappingNode) and not node.flow_style and node.value:
        return max(_end(node.value[-1][0]), _end(node.value[-1][1]))
    if isinstance(node, SequenceNode) and not node.flow_style and node.value:
        return _end(node.value[-1])
    end = int(node.end_mark.index)
    return end


def _scalar(node: Any) -> str | None:
    return str(node.value) if isinstance(node, ScalarNode) else None


def _literal(text: str | None) -> bool:
    return text is None or '$(' not in text


class _Reader:
    def __init__(self, text: str) -> None:
        self.source = text
        self.count = 0

    def next_id(self, prefix: str) -> str:
        self.count += 1
        return f'{prefix}{self.count}'

    def dash(self, node: Any) -> int:
        """The index of the ``-`` before a sequence entry."""
        start = int(node.start_mark.index)
        i = start - 1
        while i >= 0 and self.source[i] in ' \t':
            i -= 1
        return i if i >= 0 and self.source[i] == '-' else start

    def column(self, index: int) -> int:
        return index - (self.source.rfind('\n', 0, index) + 1)

    def items(self, sequence: Any, after: int) -> tuple[list[Item], int]:
        out: list[Item] = []
        for entry in sequence.value:
            start = self.dash(entry)
            end = _end(entry)
            item = self.item(entry, start, end)
            item.gap = self.source[after:start]
            out.append(item)
            after = end
        return out, after

    def item(self, entry: Any, start: int, end: int) -> Item:
        text = self.source[start:end]
        line = entry.start_mark.line + 1
        column = self.column(start)
        if not isinstance(entry, MappingNode) or len(entry.value) != 1:
            return Kept(text, 'an entry that is not one tag', line, column=column)
        key, value = entry.value[0]
        tag = _scalar(key) or ''
        if tag == 'group' and not (isinstance(value, MappingNode) and value.flow_style):
            return self.group(value, text, start, end, line, column)
        if tag in ('node', 'node_container') and isinstance(value, MappingNode) \
                and not value.flow_style:
            node = self.node(value, 'node' if tag == 'node' else 'container', line, column)
            node.original = text
            return node
        return Kept(text, f'{tag}', line, column=column)

    def group(self, value: Any, text: str, start: int, end: int, line: int, column: int) -> Item:
        children = value if isinstance(value, SequenceNode) else None
        conditional = False
        if isinstance(value, MappingNode):
            for k, v in value.value:
                if _scalar(k) == 'children' and isinstance(v, SequenceNode):
                    children = v
                elif _scalar(k) in ('if', 'unless'):
                    conditional = True
        if children is None or not children.value or children.flow_style:
            return Kept(text, 'group', line, column=column)
        group = Group(self.next_id('g'), None, line=line, indent=' ' * column, original=text,
                      conditional=conditional)
        first = self.dash(children.value[0])
        group.open_text = self.source[start:first]
        # the opening ends at the first entry's dash: its gap is empty
        group.items, last = self.items(children, first)
        group.close_text = self.source[last:end]
        for item in group.items:
            if isinstance(item, Kept) and item.what in _PUSH:
                try:
                    data = yaml.safe_load(item.text[1:])
                    namespace = data[item.what].get('namespace') if isinstance(data, dict) \
                        and isinstance(data.get(item.what), dict) else None
                except yaml.YAMLError:
                    namespace = None
                if isinstance(namespace, str) and _literal(namespace):
                    group.namespace = namespace
                else:
                    group.namespace_unknown = True
        return group

    def entry_text(self, node: Any) -> tuple[str, int, int]:
        """A sequence entry's text from its dash, its line and column."""
        start = self.dash(node)
        return self.source[start:_end(node)], node.start_mark.line + 1, self.column(start)

    def key_text(self, key: Any, value: Any) -> tuple[str, int, int]:
        start = key.start_mark.index
        return self.source[start:_end(value)], key.start_mark.line + 1, self.column(start)

    def node(self, value: Any, kind: str, line: int, column: int) -> ComposedNode:
        names = _COMPOSABLE_KEYS if kind == 'composable' else _NODE_KEYS
        fields = {_scalar(k): _scalar(v) for k, v in value.value}
        node = ComposedNode(self.next_id('n'), kind, fields.get('pkg') or '',
                            fields.get('exec') if kind != 'composable' else None,
                            plugin=fields.get('plugin') if kind == 'composable' else None,
                            name=fields.get('name'), namespace=fields.get('namespace'),
                            line=line, indent=' ' * column)
        reasons = []
        if 'if' in fields or 'unless' in fields:
            reasons.append('a condition decides whether it is launched')
        if not all(_literal(fields.get(k)) for k in names):
            reasons.append('its package, name or namespace is a substitution')
        if not fields.get('pkg') or not (fields.get('exec') or fields.get('plugin')):
            reasons.append('it gives no package or executable')
        node.style['keys'] = [_scalar(k) for k, _ in value.value]  # written back in this order
        for k, v in value.value:
            key = _scalar(k)
            if key in names and _scalar(v) is not None:
                continue
            if key == 'param' and isinstance(v, SequenceNode) and not v.flow_style:
                for entry in v.value:
                    node.params.append(self.param(entry))
            elif key == 'remap' and isinstance(v, SequenceNode) and not v.flow_style:
                for entry in v.value:
                    node.remaps.append(self.remap(entry))
            elif key == 'composable_node' and kind == 'container' and \
                    isinstance(v, SequenceNode) and not v.flow_style:
                for entry in v.value:
                    if isinstance(entry, MappingNode) and not entry.flow_style:
                        text, child_line, child_column = self.entry_text(entry)
                        child = self.node(entry, 'composable', child_line, child_column)
                        child.original = text
                        node.children.append(child)
                    else:
                        text, child_line, child_column = self.entry_text(entry)
                        node.extra.append(Kept(text, 'a composable node', child_line,
                                               column=child_column))
                node.style['composable_key'] = True
            else:
                text, kept_line, kept_column = self.key_text(k, v)
                node.extra.append(Kept(text, f'{key}', kept_line, column=kept_column))
        if reasons:
            node.editable, node.read_only_reason = False, '; '.join(reasons)
        return node

    def param(self, entry: Any) -> Param | Kept:
        text, line, column = self.entry_text(entry)
        if isinstance(entry, MappingNode):
            keys = {_scalar(k): v for k, v in entry.value}
            if set(keys) <= {'name', 'value', 'type'} and 'name' in keys and 'value' in keys:
                name = _scalar(keys['name'])
                try:
                    data = yaml.safe_load(self.source[entry.start_mark.index:_end(entry)])
                except yaml.YAMLError:
                    data = None
                raw = data.get('value') if isinstance(data, dict) else None
                literal = all(_literal(x) for x in (raw if isinstance(raw, list) else [raw])
                              if isinstance(x, str))
                if name and _literal(name) and literal and raw is not None and \
                        all(isinstance(v, ScalarNode) or v.flow_style for v in keys.values()):
                    typed = _typed(raw, data.get('type'))
                    if typed is not _NO_VALUE:
                        return Param(name, typed, text)
            what = 'a parameter file' if 'from' in keys else 'a parameter entry'
            return Kept(text, what, line, column=column)
        return Kept(text, 'a parameter entry', line, column=column)

    def remap(self, entry: Any) -> Remap | Kept:
        text, line, column = self.entry_text(entry)
        if isinstance(entry, MappingNode):
            keys = {_scalar(k): _scalar(v) for k, v in entry.value}
            source, target = keys.get('from'), keys.get('to')
            if set(keys) == {'from', 'to'} and source and target and _literal(source) \
                    and _literal(target):
                return Remap(source, target, text)
        return Kept(text, 'a remapping rule', line, column=column)


_NO_VALUE = object()


def _typed(raw: Any, type_name: Any) -> Any:
    """A YAML ``value`` as launch_yaml types it (strings are typed again), or _NO_VALUE."""
    try:
        data_type = type_from_identifier(type_name) if isinstance(type_name, str) else None
        if isinstance(raw, str):
            return get_typed_value(raw, data_type)
        return raw
    except Exception:  # noqa: BLE001 - launch reports it; the composer keeps the entry
        return _NO_VALUE


def read_yaml(text: str) -> Document:
    """The items of a launch YAML file (ReadError when it is not YAML or not ``launch:``)."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as exc:
        mark = getattr(exc, 'problem_mark', None)
        raise ReadError(f'not YAML: {getattr(exc, "problem", None) or exc}',
                        mark.line + 1 if mark else 0, mark.column + 1 if mark else 0) from None
    if not isinstance(root, MappingNode) or len(root.value) != 1 or \
            _scalar(root.value[0][0]) != 'launch':
        raise ReadError("a YAML launch file is one mapping with the key 'launch'", 1, 1)
    key, value = root.value[0]
    reader = _Reader(text)
    if not isinstance(value, SequenceNode) or not value.value or value.flow_style:
        start = key.start_mark.index
        return Document('yaml', text[:start] + 'launch:', [], '',
                        '\n' if not text[_end(value):].strip() else text[_end(value):])
    first = reader.dash(value.value[0])
    items, last = reader.items(value, first)
    doc = Document('yaml', text[:first], items, '', text[last:])
    doc.indent = ' ' * reader.column(first)
    if items:
        doc.items[0].gap = ''
    doc.style['next_id'] = reader.count
    return doc


def new_yaml() -> Document:
    """An empty launch YAML document."""
    return Document('yaml', 'launch:', [], '', '\n', indent='  ')


def _flow_scalar(text: str) -> str:
    return yaml_value_text(text)


def param_yaml(param: Param) -> str:
    """A ``param`` entry in flow style."""
    type_ = yaml_needs_type(param.value)
    typed = f', type: {type_}' if type_ else ''
    return f'- {{name: {_flow_scalar(param.name)}, value: {yaml_value_text(param.value)}{typed}}}'


def node_yaml(node: ComposedNode, indent: str) -> str:
    """A node entry (``- node:``, ``- node_container:``, or a composable node's mapping),
    written anew from the model; its kept pieces as read, and its keys in the order the file
    gave them (an edit moves nothing else)."""
    if node.kind == 'composable':
        lines = [('plugin', node.plugin), ('pkg', node.package)]
        inner = indent + '  '
        head = ''
    else:
        lines = [('pkg', node.package), ('exec', node.executable)]
        inner = indent + '    '
        head = '- node:' if node.kind == 'node' else '- node_container:'
    lines += [('name', node.name), ('namespace', node.namespace)]
    entries = inner + '  '
    # key -> its lines (each without the line break and indentation that come before it)
    chunks: dict[str, list[str]] = {}
    for key, value in lines:
        if value is not None:
            chunks[key] = [f'{key}: {_flow_scalar(value)}']
    if node.params:
        chunks['param'] = ['param:'] + [
            f'\n{entries}' + (reindent(param.text, param.column, entries) if isinstance(param, Kept)
                              else param.original if param.original is not None
                              else param_yaml(param)) for param in node.params]
    if node.remaps:
        chunks['remap'] = ['remap:'] + [
            f'\n{entries}' + (reindent(remap.text, remap.column, entries) if isinstance(remap, Kept)
                              else remap.original or f'- {{from: {_flow_scalar(remap.source)}, '
                                                     f'to: {_flow_scalar(remap.target)}}}')
            for remap in node.remaps]
    extras: list[tuple[str, str]] = [(kept.what, reindent(kept.text, kept.column, inner))
                                     for kept in node.extra if kept.what != 'a composable node']
    in_list = [kept for kept in node.extra if kept.what == 'a composable node']
    listed = bool(node.children or in_list)
    order = [k for k in node.style.get('keys', []) if k in chunks
             or (k == 'composable_node' and listed) or any(what == k for what, _ in extras)]
    order += [k for k in ('plugin', 'pkg', 'exec', 'name', 'namespace', 'param', 'remap')
              if k in chunks and k not in order]
    order += [what for what, _ in extras if what not in order]
    if listed and 'composable_node' not in order:
        order.append('composable_node')
    out: list[str] = []

    def put(text: str) -> None:
        first = not out and node.kind == 'composable'
        out.append(text if first else f'\n{inner}{text}')

    for key in order:
        if key == 'composable_node':
            put('composable_node:')
            _children_yaml(node, entries, in_list, out)
            continue
        if key in chunks:
            put(''.join(chunks.pop(key)))
        for index, (what, text) in enumerate(extras):
            if what == key:
                put(text)
                extras[index] = ('', '')
    return head + ''.join(out)


def _children_yaml(node: ComposedNode, entries: str, kept: list[Kept], out: list[str]) -> None:
    """A container's composable nodes, then those kept as written, appended to ``out`` (the
    entry's text so far)."""
    lines_before = ''.join(out).count('\n')
    for child in node.children:
        if child.dirty or child.original is None:
            child_text = '- ' + node_yaml(child, entries)
        else:
            child_text = reindent(child.original, len(child.indent), entries)
        child.style['written_at'] = lines_before + 1
        child.style['written_lines'] = child_text.count('\n')
        out.append(f'\n{entries}{child_text}')
        lines_before += 1 + child_text.count('\n')
    out.extend(f'\n{entries}' + reindent(k.text, k.column, entries) for k in kept)


def group_yaml(group: Group, indent: str) -> tuple[str, str]:
    """A group's opening and closing text (a new group: ``- group:`` with ``children:``)."""
    if group.original is not None:
        return group.open_text, group.close_text
    return f'- group:\n{indent}    children:\n', ''


def push_yaml(namespace: str) -> str:
    """A ``push-ros-namespace`` entry."""
    return f'- push-ros-namespace: {{namespace: {_flow_scalar(namespace)}}}'
