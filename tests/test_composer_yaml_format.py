"""nodl.composer.yaml_format: launch YAML read into items that keep their text, written anew."""

from __future__ import annotations

import pytest
import yaml

from composer_helpers import EXAMPLE, LAUNCH
from nodl.composer.formats import read_document, render
from nodl.composer.model import ComposedNode, Group, Kept, Param
from nodl.composer.xml_format import ReadError
from nodl.composer.yaml_format import node_yaml, read_yaml


@pytest.mark.parametrize('path', [LAUNCH / 'demo.launch.yaml',
                                  EXAMPLE / 'launch' / 'sensors.launch.yaml'])
def test_unchanged_file_is_written_byte_for_byte(path) -> None:  # type: ignore[no-untyped-def]
    text = path.read_text(encoding='utf-8')
    assert render(read_document(text, 'yaml')).text == text


def test_container_and_composable_nodes() -> None:
    doc = read_yaml((EXAMPLE / 'launch' / 'sensors.launch.yaml').read_text(encoding='utf-8'))
    container = doc.items[-1]
    assert isinstance(container, ComposedNode) and container.kind == 'container'
    camera, rectifier = container.children
    assert (camera.plugin, camera.name) == ('rover_sensors::CameraDriver', 'camera')
    # the device is a substitution: kept; fps is a value
    assert [type(p).__name__ for p in camera.params] == ['Kept', 'Param']
    assert camera.params[1] == Param('fps', 90.0, '- {name: fps, value: 90.0}')
    assert rectifier.remaps[0].source == 'image'  # type: ignore[union-attr]


def test_group_with_a_literal_namespace() -> None:
    doc = read_yaml((LAUNCH / 'demo.launch.yaml').read_text(encoding='utf-8'))
    group = doc.items[-1]
    assert isinstance(group, Group) and group.namespace == 'sub'
    assert isinstance(group.items[0], Kept) and isinstance(group.items[1], ComposedNode)


def test_edited_node_keeps_its_kept_keys_reindented() -> None:
    doc = read_yaml((LAUNCH / 'demo.launch.yaml').read_text(encoding='utf-8'))
    talker = doc.items[1]
    assert isinstance(talker, ComposedNode)
    talker.params = [Param('rate', 2.5), Param('prefix', 'true')]
    assert node_yaml(talker, '  ') == (
        '- node:\n'
        '      pkg: demo_pkg\n'
        '      exec: talker\n'
        '      name: talker\n'
        '      output: screen\n'  # in the file's order: an edit moves nothing else
        '      param:\n'
        '        - {name: rate, value: 2.5}\n'
        "        - {name: prefix, value: 'true', type: str}")


def test_not_a_launch_file() -> None:
    with pytest.raises(ReadError, match="key 'launch'"):
        read_yaml('robot: {}\n')
    with pytest.raises(ReadError, match='not YAML'):
        read_yaml('launch: [\n')


def test_an_edited_container_keeps_its_flow_composable_nodes_in_its_list() -> None:
    doc = read_yaml('launch:\n  - node_container:\n      pkg: rclcpp_components\n'
                    '      exec: component_container\n      name: box\n      composable_node:\n'
                    '        - {plugin: p::B, pkg: p, name: b}\n      output: screen\n')
    box = doc.items[0]
    assert isinstance(box, ComposedNode)
    box.name = 'box2'
    written = node_yaml(box, '  ')
    assert written.endswith('      composable_node:\n        - {plugin: p::B, pkg: p, name: b}\n'
                            '      output: screen')
    assert yaml.safe_load('launch:\n  ' + written)['launch'][0]['node_container']['name'] == 'box2'
