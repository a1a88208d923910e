"""nodl.composer.convert: the declarative part of a composition in another launch format.

Nodes, containers, names, namespaces (groups pushing literal ones), parameter values and
remapping rules are written anew; kept pieces and read-only nodes (their conditions and
substitutions are the source format's) are left out, and listed in a comment.  Outputs are
compared with expected files, and read back by the composer as the same nodes.
"""

from __future__ import annotations

import pytest

from composer_helpers import EXAMPLE, FIXTURES, LAUNCH
from nodl.composer.convert import convert_document, left_out
from nodl.composer.formats import read_document, render
from nodl.composer.model import ComposedNode, Remap

EXPECTED = FIXTURES / 'expected'
CASES = [('demo.launch.xml', 'xml', 'yaml'), ('demo.launch.py', 'python', 'xml'),
         ('rules.launch.xml', 'xml', 'python')]


def _summary(node: ComposedNode) -> tuple[object, ...]:
    # (a Python container is written namespace='', as ComposableNodeContainer requires one)
    return (node.kind, node.package, node.executable, node.plugin, node.name, node.namespace or None,
            node.param_values(), [(r.source, r.target) for r in node.remaps
                                  if isinstance(r, Remap)])


@pytest.mark.parametrize(('source', 'kind', 'target'), CASES)
def test_converted_text_is_the_expected_one(source: str, kind: str, target: str) -> None:
    doc = read_document((LAUNCH / source).read_text(encoding='utf-8'), kind)
    text = render(convert_document(doc, target)).text
    suffix = {'xml': 'xml', 'yaml': 'yaml', 'python': 'py'}[target]
    expected = EXPECTED / f'{source.split(".")[0]}.converted.launch.{suffix}'
    assert text == expected.read_text(encoding='utf-8')
    # read back: the same editable nodes, read-only ones and kept pieces left out
    again = read_document(text, target)
    assert [_summary(n) for n in again.nodes()] == \
        [_summary(n) for n in doc.nodes() if n.editable]
    assert all(n.editable for n in again.nodes())


def test_the_source_document_is_not_touched() -> None:
    text = (LAUNCH / 'demo.launch.xml').read_text(encoding='utf-8')
    doc = read_document(text, 'xml')
    convert_document(doc, 'python')
    assert render(doc).text == text


def test_what_is_left_out_is_listed() -> None:
    doc = read_document((EXAMPLE / 'launch' / 'rover.launch.xml').read_text(encoding='utf-8'), 'xml')
    missing = left_out(doc)
    assert missing[:4] == ['line 6: <arg>', 'line 7: <arg>', 'line 8: <arg>', 'line 9: <set_parameter>']
    assert 'line 10: a namespace only the running launch knows (its nodes are written without it)' \
        in missing
    assert 'line 31: the condition of a group (its nodes are written unconditionally)' in missing
    assert "line 39: args='--port 9090' of rover_tools web_bridge" in missing
    assert not any('push' in line for line in missing)   # the groups' namespaces are carried over
    xml = render(convert_document(doc, 'xml')).text
    assert "args='- -port 9090' of rover_tools web_bridge" in xml   # nothing ends the comment
    assert read_document(xml, 'xml').nodes()[0].label == 'rover_base motor_controller'
    rules = read_document((LAUNCH / 'rules.launch.xml').read_text(encoding='utf-8'), 'xml')
    assert left_out(rules) == ['line 4: <arg>', 'line 6: a remapping rule with substitutions of '
                               'demo_pkg listener']


def test_a_read_only_composable_node_is_left_out_as_listed() -> None:
    doc = read_document((LAUNCH / 'rules.launch.xml').read_text(encoding='utf-8'), 'xml')
    camera = doc.nodes()[3]
    camera.editable, camera.read_only_reason = False, 'a condition decides whether it is loaded'
    assert left_out(doc)[-1] == ('line 13: demo_pkg demo_pkg::Camera (read-only: a condition '
                                 'decides whether it is loaded)')
    converted = convert_document(doc, 'yaml')
    assert [n.name for n in converted.nodes()] == ['listener', 'talker', 'box']
