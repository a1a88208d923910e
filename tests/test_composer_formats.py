"""nodl.composer.formats: which format a path is; read, write and start each format."""

from __future__ import annotations

import pytest

from nodl.composer.formats import ReadError, format_of, new_document, new_group, read_document, render
from nodl.composer.model import ComposedNode, Group, Kept


def test_the_ending_says_the_format() -> None:
    assert [format_of(p) for p in ('a.launch.xml', 'A.LAUNCH.YAML', 'b.launch.yml', 'c.launch.py',
                                   'd.xml', 'e.yaml', 'f.yml', 'g.py')] == \
        ['xml', 'yaml', 'yaml', 'python', 'xml', 'yaml', 'yaml', 'python']
    assert format_of('notes.txt') is None and format_of('launch') is None


@pytest.mark.parametrize('kind', ['xml', 'yaml', 'python'])
def test_new_documents_with_a_group_and_a_node_read_back(kind: str) -> None:
    doc = new_document(kind)
    assert doc.format == kind and doc.items == []
    empty = render(doc).text
    assert read_document(empty, kind).items == []
    group = new_group(kind, 'g1', 'robot', doc.indent)
    assert isinstance(group.items[0], Kept) and group.items[0].what == 'push-ros-namespace'
    node = ComposedNode('n1', 'node', 'demo_pkg', 'talker', name='talker', dirty=True)
    node.indent = str(group.style['inner'])
    node.gap = '\n' + node.indent
    group.items.append(node)
    group.gap = '\n' + doc.indent
    doc.items.append(group)
    text = render(doc).text
    again = read_document(text, kind)
    read_group = again.items[0]
    assert isinstance(read_group, Group) and read_group.namespace == 'robot'
    assert [(n.package, n.executable, n.name) for n in again.nodes()] == \
        [('demo_pkg', 'talker', 'talker')]
    assert render(again).text == text   # as read: byte for byte
    if kind == 'python':   # the names the new entries use are imported
        assert 'from launch_ros.actions import Node, PushRosNamespace' in text
        assert 'GroupAction' in text


@pytest.mark.parametrize(('kind', 'text'), [('xml', '<launch>'), ('yaml', 'launch: [\n'),
                                            ('python', 'def broken(:\n')])
def test_unreadable_text_is_a_read_error(kind: str, text: str) -> None:
    with pytest.raises(ReadError) as caught:
        read_document(text, kind)
    assert caught.value.message and caught.value.line >= 1
