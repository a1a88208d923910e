"""nodl.composer.xml_format: launch XML read into items that keep their text, written anew."""

from __future__ import annotations

import pytest

from composer_helpers import EXAMPLE, LAUNCH
from nodl.composer.formats import read_document, render
from nodl.composer.model import ComposedNode, Group, Kept, Param, Remap
from nodl.composer.xml_format import ReadError, node_xml, read_xml


@pytest.mark.parametrize('path', [LAUNCH / 'demo.launch.xml', EXAMPLE / 'launch' / 'rover.launch.xml',
                                  LAUNCH / 'other.launch.xml'])
def test_unchanged_file_is_written_byte_for_byte(path) -> None:  # type: ignore[no-untyped-def]
    text = path.read_text(encoding='utf-8')
    assert render(read_document(text, 'xml')).text == text


def test_items_editable_and_kept() -> None:
    doc = read_xml((LAUNCH / 'demo.launch.xml').read_text(encoding='utf-8'))
    kinds = [(type(i).__name__, getattr(i, 'what', getattr(i, 'name', None))) for i in doc.items]
    assert kinds == [('Kept', '<arg>'), ('Kept', '<include>'), ('ComposedNode', 'talker'),
                     ('ComposedNode', 'listener'), ('ComposedNode', 'quiet'), ('Group', None)]
    talker, _, quiet, group = doc.items[2:]
    assert isinstance(talker, ComposedNode) and talker.editable
    assert talker.params == [Param('rate', 5.0, '<param name="rate" value="5.0"/>', '\n    ')]
    assert talker.style['attrs'] == [('output', 'screen')]
    assert isinstance(quiet, ComposedNode) and not quiet.editable
    assert 'condition' in quiet.read_only_reason
    assert isinstance(group, Group) and group.namespace == 'sub'
    counter = group.items[1]
    assert isinstance(counter, ComposedNode)
    assert isinstance(counter.params[0], Kept) and counter.params[0].what == 'a parameter file'


def test_substitution_namespace_is_unknown_not_guessed() -> None:
    doc = read_xml((EXAMPLE / 'launch' / 'rover.launch.xml').read_text(encoding='utf-8'))
    group = next(i for i in doc.items if isinstance(i, Group))
    assert group.namespace is None and group.namespace_unknown


def test_node_written_anew_escapes_and_keeps_its_kept_children() -> None:
    doc = read_xml((LAUNCH / 'demo.launch.xml').read_text(encoding='utf-8'))
    counter = doc.items[5].items[1]  # type: ignore[union-attr]
    counter.name = 'a"b<c>&'
    counter.params.append(Param('label', '3'))
    counter.remaps.append(Remap('count', '/total'))
    text = node_xml(counter, '    ')
    assert text == (
        '<node pkg="demo_pkg" exec="counter" name="a&quot;b&lt;c&gt;&amp;">\n'
        '      <param from="$(dirname)/counter.yaml"/>\n'
        '      <param name="label" value="3" type="str"/>\n'
        '      <remap from="count" to="/total"/>\n'
        '    </node>')


def test_not_a_launch_file() -> None:
    with pytest.raises(ReadError, match='root is <robot>'):
        read_xml('<robot/>')
    with pytest.raises(ReadError, match='not well-formed') as caught:
        read_xml('<launch>\n  <node>\n</launch>')
    assert caught.value.line == 3
