"""The three launch formats behind one interface: which format a path is, read, write, new.

``.launch.xml`` (and ``.xml``), ``.launch.yaml`` (``.launch.yml``, ``.yaml``) and
``.launch.py`` (``.py``).
"""

from __future__ import annotations

from nodl.composer import python_format, xml_format, yaml_format
from nodl.composer.model import ComposedNode, Document, Group, Item, Kept
from nodl.composer.rendering import Rendered, render_document
from nodl.composer.xml_format import ReadError

__all__ = [
    'FORMATS',
    'ReadError',
    'format_of',
    'new_document',
    'new_group',
    'read_document',
    'render',
]

#: The formats, by the suffix that names them.
FORMATS = {'.launch.xml': 'xml', '.launch.yaml': 'yaml', '.launch.yml': 'yaml',
           '.launch.py': 'python', '.xml': 'xml', '.yaml': 'yaml', '.yml': 'yaml', '.py': 'python'}


def format_of(path: str) -> str | None:
    """``xml``, ``yaml`` or ``python`` by the file name's ending; None for another."""
    lower = path.lower()
    return next((kind for suffix, kind in FORMATS.items() if lower.endswith(suffix)), None)


def read_document(text: str, kind: str) -> Document:
    """The items of a launch file's text (ReadError when it cannot be read as one)."""
    if kind == 'xml':
        return xml_format.read_xml(text)
    if kind == 'yaml':
        return yaml_format.read_yaml(text)
    return python_format.read_python(text)


def new_document(kind: str) -> Document:
    """An empty launch file of ``kind``."""
    if kind == 'xml':
        return xml_format.new_xml()
    if kind == 'yaml':
        return yaml_format.new_yaml()
    return python_format.new_python()


def new_group(kind: str, group_id: str, namespace: str, indent: str) -> Group:
    """A new group pushing ``namespace`` (its first item the push)."""
    group = Group(group_id, namespace, indent=indent, dirty=True)
    inner = indent + ('    ' if kind == 'yaml' else '  ' if kind == 'xml' else '    ')
    if kind == 'xml':
        push = xml_format.push_xml(namespace)
    elif kind == 'yaml':
        push = yaml_format.push_yaml(namespace)
        inner = indent + '      '
    else:
        push = python_format.push_python(namespace)
    group.items.append(Kept(push, 'push-ros-namespace', 0, '\n' + inner if kind != 'yaml'
                            else inner, column=len(inner)))
    group.style['inner'] = inner
    group.close_gap = '' if kind == 'yaml' else '\n' + indent
    group.style['trailing_separator'] = kind == 'python'
    return group


def _used_names(items: list[Item]) -> set[str]:
    used: set[str] = set()
    for item in items:
        if isinstance(item, Group):
            if item.original is None:
                used |= {'GroupAction', 'PushRosNamespace'}
            used |= _used_names(item.items)
        elif isinstance(item, ComposedNode) and (item.dirty or item.original is None):
            if item.original is None or 'call' not in item.style:
                used.add('Node' if item.kind == 'node' else 'ComposableNodeContainer')
            for child in item.children:
                if child.original is None:
                    used.add('ComposableNode')
    return used


def render(doc: Document) -> Rendered:
    """The text of ``doc`` and where each node is in it."""
    if doc.format == 'xml':
        return render_document(doc, xml_format.node_xml, xml_format.group_xml)
    if doc.format == 'yaml':
        return render_document(doc, yaml_format.node_yaml, yaml_format.group_yaml)
    header = doc.header
    imports = python_format.imports_needed(doc, _used_names(doc.items))
    if doc.style.get('fresh'):
        header = header.replace('{imports}\n', imports)
    elif imports:
        at = doc.style.get('import_at')
        header = imports + header if at is None else \
            header[:at] + '\n' + imports.rstrip('\n') + header[at:]
    shifted = Document(doc.format, header, doc.items, doc.close_gap, doc.trailer, doc.indent,
                       doc.style)
    return render_document(shifted, python_format.node_python, python_format.group_python, ',')
