"""nodl.composer.model: the items of a launch file, in file order."""

from __future__ import annotations

from composer_helpers import LAUNCH
from nodl.composer.formats import read_document
from nodl.composer.model import NODE_KINDS, ComposedNode, Group, Kept, Param, Remap


def test_walk_nodes_and_kept_in_file_order() -> None:
    doc = read_document((LAUNCH / 'demo.launch.xml').read_text(encoding='utf-8'), 'xml')
    walked = [(type(item).__name__, parent.id if parent is not None else None)
              for item, parent in doc.walk()]
    group = next(item for item in doc.items if isinstance(item, Group))
    assert walked == [('Kept', None), ('Kept', None), ('ComposedNode', None),
                      ('ComposedNode', None), ('ComposedNode', None), ('Group', None),
                      ('Kept', group.id), ('ComposedNode', group.id)]
    assert [n.name for n in doc.nodes()] == ['talker', 'listener', 'quiet', 'counter']
    assert [k.what for k in doc.kept()] == ['<arg>', '<include>']  # the push: the group's namespace
    rules = read_document((LAUNCH / 'rules.launch.xml').read_text(encoding='utf-8'), 'xml')
    assert [(n.kind, n.name) for n in rules.nodes()] == [
        ('node', 'listener'), ('node', 'talker'), ('container', 'box'), ('composable', 'camera')]
    assert {n.kind for n in rules.nodes()} == set(NODE_KINDS)


def test_a_node_and_its_pieces() -> None:
    camera = ComposedNode('n2', 'composable', 'demo_pkg', None, plugin='demo_pkg::Camera')
    box = ComposedNode('n1', 'container', 'rclcpp_components', 'component_container',
                       children=[camera])
    assert list(box.walk()) == [box, camera]
    assert (box.label, camera.label) == ('rclcpp_components component_container',
                                         'demo_pkg demo_pkg::Camera')
    node = ComposedNode('n3', 'node', 'p', 'e', params=[
        Param('a', 1), Kept('<param from="f.yaml"/>', 'a parameter file', 4), Param('a', 2.5)],
        remaps=[Remap('x', 'y')])
    assert node.param_values() == {'a': 2.5}   # a later value wins
    kept = node.params[1]
    assert isinstance(kept, Kept) and kept.original == kept.text
    assert kept.to_dict() == {'type': 'kept', 'what': 'a parameter file', 'line': 4,
                              'text': '<param from="f.yaml"/>'}
    assert ComposedNode('n4', 'node', 'p', 'e') != ComposedNode('n4', 'node', 'p', 'e')  # by identity
