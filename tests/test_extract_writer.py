"""nodl.extract.writer: drafts with a location comment per entity, gaps commented out, valid."""

from __future__ import annotations

from nodl.extract.model import ExtractedEntity, ExtractedNode, Gap
from nodl.extract.writer import check_entities, draft_data, draft_text
from nodl.loading import load_node
from nodl.location import Location
from nodl.model.qos import QoSProfile

QOS = QoSProfile('KEEP_LAST', 'RELIABLE', 10, 'VOLATILE')


def _node() -> ExtractedNode:
    node = ExtractedNode('Talker', Location('/src/pkg/talker.py', 5, 1), 'python', base='lifecycle_node',
                         package='pkg', executable='talker', sources=['/src/pkg/talker.py'])
    node.entities += [
        ExtractedEntity('publishers', 'chatter', 'std_msgs/msg/String', Location('/src/pkg/talker.py', 9, 9), qos=QOS),
        ExtractedEntity('publishers', 'chatter', 'std_msgs/msg/String', Location('/src/pkg/talker.py', 10, 9), qos=QOS),
        ExtractedEntity('publishers', None, 'std_msgs/msg/String', Location('/src/pkg/talker.py', 11, 9), qos=QOS,
               gaps=[Gap('name', 'topic name is computed at run time', Location('/src/pkg/talker.py', 11, 40),
                         'NODL901')]),
        ExtractedEntity('parameters', 'rate', 'double', Location('/src/pkg/talker.py', 12, 9), default_value=1.0,
               has_default=True, read_only=True, validation={'bounds<>': [0.0, 10.0]}),
        ExtractedEntity('parameters', 'bad name', 'double', Location('/src/pkg/talker.py', 13, 9), default_value=1.0,
               has_default=True),
    ]
    return node


def test_draft_locations_gaps_and_validity() -> None:
    node = _node()
    check_entities(node)
    assert [g.code for g in node.gaps] == ['NODL901', 'NODL914']  # the invalid name becomes a gap
    text = draft_text(node, relative_to='/src/pkg')
    lines = text.splitlines()
    assert lines[0] == '# Extracted from talker.py by nodl extract (pkg talker, python).'
    assert '    # talker.py:9:9' in lines and '    # also at talker.py:10:9' in lines
    assert any(line.startswith('    # GAP talker.py:11:40: topic name is computed at run time') for line in lines)
    assert '    # - type: std_msgs/msg/String' in lines  # written, commented out: nothing invented
    assert '    # bad name:' in lines
    loaded = load_node(text)
    assert loaded.base is not None and loaded.base.value == 'lifecycle_node'
    assert [p.name for p in loaded.main.publishers or []] == ['chatter']
    assert list(loaded.main.parameters or {}) == ['rate']
    assert draft_data(node)['main']['parameters']['rate']['validation'] == {'bounds<>': [0.0, 10.0]}


def test_a_node_with_only_gaps_is_still_a_valid_definition() -> None:
    node = ExtractedNode('n', Location('n.py', 1, 1), 'python')
    node.entities.append(ExtractedEntity('service_clients', None, None, Location('n.py', 3, 1), gaps=[
        Gap('entity', 'arguments not written out', Location('n.py', 3, 1), 'NODL910')]))
    text = draft_text(node)
    assert '  # service_clients:' in text.splitlines()
    assert load_node(text).main.service_clients is None


def test_comment_text_cannot_break_out_of_its_line() -> None:
    node = ExtractedNode('n', Location('n.py', 1, 1), 'python')
    node.entities.append(ExtractedEntity('publishers', None, None, Location('n.py\nmain: evil', 3, 1), gaps=[
        Gap('name', 'why\nnodl_version: 3', Location('n.py', 3, 1), 'NODL901')]))
    text = draft_text(node)
    assert load_node(text).nodl_version == 2
    assert all(line.startswith(('#', ' ', 'nodl_version', 'main')) for line in text.splitlines())
