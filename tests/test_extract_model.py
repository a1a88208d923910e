"""nodl.extract.model: locations, gaps as located diagnostics, nodes and extractions."""

from __future__ import annotations

from nodl.diagnostics import Severity
from nodl.extract.model import ENTITY_SECTIONS, ExtractedEntity, ExtractedNode, Extraction, Gap
from nodl.location import Location


def test_location_and_gap_diagnostic() -> None:
    where = Location('foo.py', 42, 31)
    assert str(where) == 'foo.py:42:31' and str(Location('foo.py')) == 'foo.py'
    diagnostic = Gap('name', 'topic name is computed at run time', where, 'NODL901').diagnostic()
    assert str(diagnostic) == 'foo.py:42:31: warning: topic name is computed at run time [NODL901]'
    assert diagnostic.severity is Severity.WARNING


def test_node_diagnostics_in_source_order_and_output_name() -> None:
    node = ExtractedNode('Talker', Location('t.py', 5, 1), 'python')
    node.entities += [
        ExtractedEntity('publishers', None, 'std_msgs/msg/String', Location('t.py', 9, 1),
               gaps=[Gap('name', 'late', Location('t.py', 9, 30), 'NODL901')]),
        ExtractedEntity('parameters', 'rate', 'int', Location('t.py', 7, 1), default_value=1, has_default=True,
               gaps=[Gap('default_value', 'early', Location('t.py', 7, 20), 'NODL905')]),
    ]
    assert [d.line for d in node.diagnostics] == [7, 9]
    assert [e.complete for e in node.entities] == [False, False]
    assert node.output_name == 'Talker'
    node.executable = 'talker'
    assert node.output_name == 'talker'
    assert node.section('parameters')[0].key() == ('parameters', 'rate')
    assert ENTITY_SECTIONS[0] == 'parameters' and 'action_clients' in ENTITY_SECTIONS


def test_extraction_extend_keeps_files_once() -> None:
    first = Extraction(files=['a.py'])
    first.extend(Extraction(nodes=[ExtractedNode('N', Location('a.py'), 'python')], files=['a.py', 'b.py']))
    assert first.files == ['a.py', 'b.py'] and len(first.nodes) == 1
    assert first.all_diagnostics == []
