"""Launch XML: read into items with the exact text of each, written back as read or anew.

The reader keeps every element's bytes (expat reports where each starts and ends): a
``node``, ``node_container`` or ``group`` becomes an item the composer understands,
anything else a :class:`~nodl.composer.model.Kept` piece.  A node's ``param name= value=``
and ``remap from= to=`` children with literal text are editable; a ``param from=`` (a
file), substitutions, ``env`` and other children and attributes are kept verbatim.
"""

from __future__ import annotations

import xml.parsers.expat
from dataclasses import dataclass, field

from nodl.composer.model import ComposedNode, Document, Group, Item, Kept, Param, Remap
from nodl.composer.rendering import reindent
from nodl.composer.values import xml_value
from nodl.launch.params import get_typed_value, type_from_identifier

__all__ = ['ReadError', 'escape', 'group_xml', 'new_xml', 'node_xml', 'read_xml']

#: The attributes of a node entry the composer edits.
_NODE_ATTRS = ('pkg', 'exec', 'name', 'namespace')
_COMPOSABLE_ATTRS = ('pkg', 'plugin', 'name', 'namespace')
_PUSH = ('push-ros-namespace', 'push_ros_namespace')


class ReadError(Exception):
    """A launch file the composer cannot read: ``(message, line, column)``."""

    def __init__(self, message: str, line: int = 0, column: int = 0) -> None:
        super().__init__(message)
        self.message, self.line, self.column = message, line, column


@dataclass
class _Element:
    tag: str
    attrs: list[tuple[str, str]]
    start: int
    start_end: int
    end: int = 0
    line: int = 0
    column: int = 0
    children: list[_Element] = field(default_factory=list)

    def attr(self, name: str) -> str | None:
        return next((v for k, v in self.attrs if k == name), None)


def _tag_end(raw: bytes, start: int) -> int:
    """The index after the ``>`` of the tag starting at ``start`` (quotes respected)."""
    quote = 0
    i = start
    while i < len(raw):
        c = raw[i]
        if quote:
            if c == quote:
                quote = 0
        elif c in (0x22, 0x27):
            quote = c
        elif c == 0x3E:
            return i + 1
        i += 1
    return len(raw)


def _parse(raw: bytes) -> _Element:
    parser = xml.parsers.expat.ParserCreate()
    parser.ordered_attributes = True
    stack: list[_Element] = []
    root: list[_Element] = []

    def start(tag: str, attrs: list[str]) -> None:
        at = parser.CurrentByteIndex
        element = _Element(tag, list(zip(attrs[::2], attrs[1::2], strict=True)), at, _tag_end(raw, at),
                           line=parser.CurrentLineNumber, column=parser.CurrentColumnNumber)
        if stack:
            stack[-1].children.append(element)
        else:
            root.append(element)
        stack.append(element)

    def end(tag: str) -> None:
        element = stack.pop()
        if raw[element.start_end - 2:element.start_end] == b'/>':
            element.end = element.start_end
        else:
            element.end = _tag_end(raw, parser.CurrentByteIndex)

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    try:
        parser.Parse(raw, True)
    except xml.parsers.expat.ExpatError as exc:
        raise ReadError(f'not well-formed XML: {xml.parsers.expat.ErrorString(exc.code)}',
                        exc.lineno, exc.offset + 1) from None
    return root[0]


def escape(text: str) -> str:
    """``text`` for an attribute value in double quotes."""
    return (text.replace('&', '&amp;').replace('<', '&lt;').replace('>', '&gt;')
            .replace('"', '&quot;').replace('\n', '&#10;').replace('\t', '&#9;'))


def _literal(text: str | None) -> bool:
    return text is None or '$(' not in text


class _Reader:
    def __init__(self, raw: bytes) -> None:
        self.raw = raw
        self.count = 0

    def text(self, start: int, end: int) -> str:
        return self.raw[start:end].decode('utf-8')

    def column_of(self, element: _Element) -> str:
        line_start = self.raw.rfind(b'\n', 0, element.start) + 1
        prefix = self.text(line_start, element.start)
        return prefix if not prefix.strip() else ' ' * len(prefix)

    def next_id(self, prefix: str) -> str:
        self.count += 1
        return f'{prefix}{self.count}'

    def items(self, children: list[_Element], after: int) -> tuple[list[Item], int]:
        """The items of ``children`` and the index after the last one."""
        out: list[Item] = []
        for child in children:
            item = self.item(child)
            item.gap = self.text(after, child.start)
            out.append(item)
            after = child.end
        return out, after

    def item(self, element: _Element) -> Item:
        if element.tag == 'group':
            return self.group(element)
        if element.tag in ('node', 'node_container'):
            return self.node(element, 'node' if element.tag == 'node' else 'container')
        return Kept(self.text(element.start, element.end), f'<{element.tag}>', element.line,
                    column=element.column)

    def group(self, element: _Element) -> Group:
        group = Group(self.next_id('g'), None, line=element.line, indent=self.column_of(element))
        group.original = self.text(element.start, element.end)
        group.conditional = element.attr('if') is not None or element.attr('unless') is not None
        if element.start_end == element.end:  # <group/>: nothing in it
            group.open_text = group.original
            return group
        group.open_text = self.text(element.start, element.start_end)
        group.items, last = self.items(element.children, element.start_end)
        close_at = self.raw.rfind(b'</', 0, element.end)
        group.close_gap = self.text(last, close_at)
        group.close_text = self.text(close_at, element.end)
        for child in element.children:
            if child.tag in _PUSH:
                namespace = child.attr('namespace')
                if namespace is not None and _literal(namespace):
                    group.namespace = namespace
                else:
                    group.namespace_unknown = True
        return group

    def node(self, element: _Element, kind: str) -> ComposedNode:
        names = _NODE_ATTRS if kind != 'composable' else _COMPOSABLE_ATTRS
        node = ComposedNode(self.next_id('n'), kind, element.attr('pkg') or '',
                            element.attr('exec') if kind != 'composable' else None,
                            plugin=element.attr('plugin') if kind == 'composable' else None,
                            name=element.attr('name'), namespace=element.attr('namespace'),
                            line=element.line, indent=self.column_of(element))
        node.original = self.text(element.start, element.end)
        node.style['tag'] = element.tag
        reasons = []
        if element.attr('if') is not None or element.attr('unless') is not None:
            reasons.append('a condition decides whether it is launched')
        if not all(_literal(element.attr(a)) for a in names):
            reasons.append('its package, name or namespace is a substitution')
        if not element.attr('pkg') or not (element.attr('exec') or element.attr('plugin')):
            reasons.append('it gives no package or executable')
        if reasons:
            node.editable, node.read_only_reason = False, '; '.join(reasons)
        node.style['attrs'] = [(k, v) for k, v in element.attrs if k not in names]
        after = element.start_end
        for child in element.children:
            gap = self.text(after, child.start)
            after = child.end
            text = self.text(child.start, child.end)
            name, value, kind_ = child.attr('name'), child.attr('value'), child.attr('type')
            if child.tag == 'param' and name and value is not None and not child.children \
                    and _literal(name) and _literal(value) and child.attr('value-sep') is None \
                    and child.attr('from') is None:
                try:
                    typed = get_typed_value(value, type_from_identifier(kind_) if kind_ else None)
                except Exception:  # noqa: BLE001 - launch reports it; the composer keeps it
                    node.params.append(Kept(text, 'a parameter launch cannot type', child.line,
                                            gap, child.column))
                    continue
                node.params.append(Param(name, typed, text, gap))
            elif child.tag == 'param':
                what = 'a parameter file' if child.attr('from') is not None else \
                    'a parameter written with substitutions or nested values'
                node.params.append(Kept(text, what, child.line, gap, child.column))
            elif child.tag == 'remap':
                source, target = child.attr('from'), child.attr('to')
                if source and target and _literal(source) and _literal(target):
                    node.remaps.append(Remap(source, target, text, gap))
                else:
                    node.remaps.append(Kept(text, 'a remapping rule with substitutions',
                                            child.line, gap, child.column))
            elif child.tag == 'composable_node' and kind == 'container':
                composable = self.node(child, 'composable')
                composable.gap = gap
                node.children.append(composable)
            else:
                node.extra.append(Kept(text, f'<{child.tag}>', child.line, gap, child.column))
        node.style['close_gap'] = self.text(after, self.raw.rfind(b'</', 0, element.end)) \
            if element.start_end != element.end else ''
        return node


def read_xml(text: str) -> Document:
    """The items of a launch XML file (ReadError when it is not well-formed or not ``<launch>``)."""
    raw = text.encode('utf-8')
    root = _parse(raw)
    if root.tag != 'launch':
        raise ReadError(f"the root is <{root.tag}>; a launch file's root is <launch>",
                        root.line, root.column + 1)
    reader = _Reader(raw)
    if root.start_end == root.end:  # <launch/>
        doc = Document('xml', reader.text(0, root.start) + '<launch>', [], '\n',
                       '</launch>' + reader.text(root.end, len(raw)))
        return doc
    items, last = reader.items(root.children, root.start_end)
    close_at = raw.rfind(b'</', 0, root.end)
    doc = Document('xml', reader.text(0, root.start_end), items, reader.text(last, close_at),
                   reader.text(close_at, len(raw)))
    first = next((i for i in items), None)
    if first is not None and not isinstance(first, Kept):
        doc.indent = first.indent
    elif first is not None:
        doc.indent = ' ' * first.column
    doc.style['next_id'] = reader.count
    return doc


def new_xml() -> Document:
    """An empty launch XML document."""
    return Document('xml', '<?xml version="1.0"?>\n<launch>', [], '\n', '</launch>\n')


def _child_line(item: Param | Remap | Kept, indent: str, text: str) -> str:
    gap = item.gap if item.original is not None and '<!--' in item.gap else None
    if gap is not None:
        return gap + text
    return '\n' + indent + text


def param_xml(param: Param) -> str:
    """A ``<param>`` element."""
    value, type_ = xml_value(param.value)
    typed = f' type="{type_}"' if type_ else ''
    return f'<param name="{escape(param.name)}" value="{escape(value)}"{typed}/>'


def node_xml(node: ComposedNode, indent: str) -> str:
    """A node (or container, or composable node) element, written anew from the model; its
    kept pieces as read."""
    inner = indent + '  '
    if node.kind == 'composable':
        tag, attrs = 'composable_node', [('pkg', node.package), ('plugin', node.plugin)]
    else:
        tag = 'node' if node.kind == 'node' else 'node_container'
        attrs = [('pkg', node.package), ('exec', node.executable)]
    attrs += [('name', node.name), ('namespace', node.namespace)]
    attrs += node.style.get('attrs', [])
    head = f'<{tag}' + ''.join(f' {k}="{escape(v)}"' for k, v in attrs if v is not None)
    body: list[str] = []
    for param in node.params:
        if isinstance(param, Kept):
            body.append(_child_line(param, inner, reindent(param.text, param.column, inner)))
        elif param.original is not None:
            body.append(_child_line(param, inner, param.original))
        else:
            body.append(_child_line(param, inner, param_xml(param)))
    for remap in node.remaps:
        if isinstance(remap, Kept):
            body.append(_child_line(remap, inner, reindent(remap.text, remap.column, inner)))
        else:
            body.append(_child_line(remap, inner, remap.original or
                                    f'<remap from="{escape(remap.source)}" '
                                    f'to="{escape(remap.target)}"/>'))
    for kept in node.extra:
        body.append(_child_line(kept, inner, reindent(kept.text, kept.column, inner)))
    lines_before = ''.join(body).count('\n')
    for child in node.children:
        if child.dirty or child.original is None:
            child_text = node_xml(child, inner)
        else:
            child_text = reindent(child.original, len(child.indent), inner)
        child.style['written_at'] = lines_before + 1
        child.style['written_lines'] = child_text.count('\n')
        body.append('\n' + inner + child_text)
        lines_before += 1 + child_text.count('\n')
    if not body:
        return head + '/>'
    return head + '>' + ''.join(body) + '\n' + indent + f'</{tag}>'


def group_xml(group: Group, indent: str) -> tuple[str, str]:
    """A new group's opening (with its ``push-ros-namespace``) and closing text."""
    if group.original is not None:
        return group.open_text, group.close_text
    return '<group>', '</group>'


def push_xml(namespace: str) -> str:
    """A ``push-ros-namespace`` element."""
    return f'<push-ros-namespace namespace="{escape(namespace)}"/>'
