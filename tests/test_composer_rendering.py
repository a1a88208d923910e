"""nodl.composer.rendering: a document's text, item by item, and where each node is in it."""

from __future__ import annotations

from composer_helpers import LAUNCH
from nodl.composer.formats import read_document, render
from nodl.composer.model import ComposedNode, Document, Group, Kept
from nodl.composer.rendering import Output, reindent, render_document


def test_reindent_moves_following_lines_by_the_difference() -> None:
    text = 'a\n    b\n\n  c'
    assert reindent(text, 4, '      ') == 'a\n      b\n\n    c'   # blank lines stay blank
    assert reindent(text, 4, '') == 'a\nb\n\nc'   # never more than a line's own indent
    assert reindent(text, 2, '  ') == text and reindent('one line', 0, '    ') == 'one line'


def test_output_counts_lines() -> None:
    out = Output()
    out.write('a\nb')
    out.write('\n')
    assert out.line == 3 and out.text() == 'a\nb\n'


def test_spans_lead_back_to_nodes_as_read_and_written() -> None:
    text = (LAUNCH / 'rules.launch.xml').read_text(encoding='utf-8')
    doc = read_document(text, 'xml')
    listener, talker, box, camera = doc.nodes()
    read = render(doc)
    assert read.text == text
    assert read.spans == {listener.id: (5, 10), talker.id: (11, 11), box.id: (12, 14),
                          camera.id: (13, 13)}
    box.dirty = True   # the container written anew: its composable node found in it again
    talker.dirty = True
    written = render(doc)
    lines = written.text.split('\n')
    assert written.spans[camera.id][0] == written.spans[box.id][0] + 1
    assert 'name="camera"' in lines[written.spans[camera.id][0] - 1]
    assert 'name="talker"' in lines[written.spans[talker.id][0] - 1]


def test_items_gaps_and_separators() -> None:
    """The walk every format shares: gaps as read, new items by the writers, separators."""
    node = ComposedNode('n1', 'node', 'pkg', 'exe', gap='\n  ')
    group = Group('g1', 'ns', [Kept('PUSH', 'push', gap='\n    ')], open_text='OPEN(',
                  close_text=')', original='', gap='\n  ')
    doc = Document('python', 'HEAD[', [node, group, Kept('CODE', 'code', gap='\n  ')],
                   close_gap='\n', trailer=']\n')

    def node_text(item: ComposedNode, indent: str) -> str:
        return f'NODE({item.package})'

    def group_text(item: Group, indent: str) -> tuple[str, str]:
        return 'NEWGROUP(', ')'

    rendered = render_document(doc, node_text, group_text, ',')
    assert rendered.text == 'HEAD[\n  NODE(pkg),\n  OPEN(\n    PUSH),\n  CODE\n]\n'
    assert rendered.spans == {'n1': (2, 2)}
    group.dirty = True
    doc.style['trailing_separator'] = True
    assert render_document(doc, node_text, group_text, ',').text == \
        'HEAD[\n  NODE(pkg),\n  NEWGROUP(\n    PUSH),\n  CODE,\n]\n'
