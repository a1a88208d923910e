"""nodl.composer.python_format: a Python launch file parsed (never run) into items."""

from __future__ import annotations

import ast

import pytest

from composer_helpers import EXAMPLE, LAUNCH
from nodl.composer.formats import new_document, read_document, render
from nodl.composer.model import ComposedNode, Group, Kept, Param, Remap
from nodl.composer.python_format import node_python, read_python
from nodl.composer.xml_format import ReadError


@pytest.mark.parametrize('path', [LAUNCH / 'demo.launch.py',
                                  EXAMPLE / 'launch' / 'navigation.launch.py'])
def test_unchanged_file_is_written_byte_for_byte(path) -> None:  # type: ignore[no-untyped-def]
    text = path.read_text(encoding='utf-8')
    assert render(read_document(text, 'python')).text == text


def test_calls_understood_and_code_kept() -> None:
    doc = read_python((LAUNCH / 'demo.launch.py').read_text(encoding='utf-8'))
    assert [type(i).__name__ for i in doc.items] == ['Kept', 'ComposedNode', 'ComposedNode',
                                                     'ComposedNode', 'Group']
    talker, _, quiet, group = doc.items[1:]
    assert isinstance(talker, ComposedNode) and talker.params == [Param('rate', 5.0)]
    assert [k.text for k in talker.extra] == ["output='screen'"]
    assert isinstance(quiet, ComposedNode) and not quiet.editable
    assert isinstance(group, Group) and group.namespace == 'sub'


def test_a_list_built_by_code_is_kept_whole() -> None:
    text = ('from launch import LaunchDescription\n\n'
            'def generate_launch_description():\n    ld = LaunchDescription()\n    return ld\n')
    doc = read_python(text)
    assert doc.style['opaque'] and doc.items == [] and render(doc).text == text


def test_new_nodes_bring_their_imports_and_the_file_parses() -> None:
    doc = new_document('python')
    node = ComposedNode('n1', 'node', 'demo_pkg', 'talker', name="it's", dirty=True,
                        params=[Param('rate', 2.0), Param('prefix', 'x')],
                        remaps=[Remap('chatter', '/robot/chatter')])
    node.gap, node.indent = '\n' + doc.indent, doc.indent
    doc.items.append(node)
    text = render(doc).text
    ast.parse(text)
    assert 'from launch_ros.actions import Node\n' in text
    assert node_python(node, '') == (
        "Node(\n    package='demo_pkg',\n    executable='talker',\n    name=\"it's\",\n"
        "    parameters=[{'rate': 2.0, 'prefix': 'x'}],\n"
        "    remappings=[('chatter', '/robot/chatter')],\n)")


def test_a_kept_parameter_source_stays_in_its_place() -> None:
    doc = read_python((EXAMPLE / 'launch' / 'navigation.launch.py').read_text(encoding='utf-8'))
    planner = next(n for n in doc.nodes() if n.executable == 'planner')
    assert [type(p).__name__ for p in planner.params] == ['Kept']
    planner.params.append(Param('tolerance', 0.5))
    assert "parameters=[params, {'tolerance': 0.5}])" in node_python(planner, '')  # as compact as read
    assert isinstance(planner.params[0], Kept)


def test_not_a_launch_file() -> None:
    with pytest.raises(ReadError, match='syntax'):
        read_python('def (:\n')
    with pytest.raises(ReadError, match='generate_launch_description'):
        read_python('x = 1\n')


def test_an_empty_list_read_back_indents_its_first_item_one_level_in() -> None:
    # a new file, saved empty and opened again: its first node is indented as new_document's
    empty = render(new_document('python')).text
    doc = read_python(empty)
    assert doc.indent == ' ' * 8, repr(doc.indent)
    assert doc.style['trailing_separator']  # every item followed by a comma, as in a new file


def test_an_edited_call_keeps_its_keywords_order_and_code_in_its_list() -> None:
    text = ('from launch import LaunchDescription\n'
            'from launch_ros.actions import ComposableNodeContainer\n'
            'from launch_ros.descriptions import ComposableNode\n\n\n'
            'def generate_launch_description():\n'
            "    extra = ComposableNode(package='p', plugin='p::A', name='a2')\n"
            '    return LaunchDescription([\n'
            "        ComposableNodeContainer(name='box', namespace='', package='rclcpp_components',\n"
            "            executable='component_container', composable_node_descriptions=[\n"
            "                ComposableNode(package='p', plugin='p::A', name='a1'), extra],\n"
            "            output='screen'),\n"
            '    ])\n')
    doc = read_python(text)
    box = doc.items[0]
    assert isinstance(box, ComposedNode)
    box.name = 'box2'
    written = node_python(box, '        ')
    ast.parse(written)  # the code-built composable node stays inside the list
    assert written.index("name='box2'") < written.index('package=') < \
        written.index('composable_node_descriptions=[') < written.index('extra,') < \
        written.index("output='screen'")


def test_a_call_written_compactly_is_edited_in_place() -> None:
    text = (LAUNCH / 'demo.launch.py').read_text(encoding='utf-8')
    doc = read_python(text)
    talker = doc.items[1]
    assert isinstance(talker, ComposedNode)
    talker.params = [Param('rate', 7.5)]
    talker.dirty = True
    assert render(doc).text == text.replace("parameters=[{'rate': 5.0}]", "parameters=[{'rate': 7.5}]")
