"""nodl.composer.adding: where a new entry goes and what it looks like; removing one."""

from __future__ import annotations

from pathlib import Path

from composer_helpers import FIXTURES, LAUNCH, copy_launch, definitions
from nodl.composer import Composition
from nodl.composer.adding import default_plugin

EXPECTED = FIXTURES / 'expected'


def test_the_plugin_class_of_a_composable_node(tmp_path: Path) -> None:
    composition = Composition.new(str(tmp_path / 'new.launch.xml'), definitions=definitions())
    assert default_plugin(composition, 'demo_pkg', 'camera') == 'demo_pkg::Camera'  # nodes.yaml
    assert default_plugin(composition, 'demo_pkg', 'fancy_thing') == 'demo_pkg::FancyThing'
    assert default_plugin(composition, 'demo_pkg', 'other::Class') == 'other::Class'


def test_composable_nodes_go_into_their_container(tmp_path: Path) -> None:
    rules = Composition.open(str(copy_launch(tmp_path) / 'rules.launch.xml'),
                             definitions=definitions())
    into = rules.add('demo_pkg', 'camera', 'rear', container='box')
    assert into.ok and not into.diagnostics
    made = rules.add('demo_pkg', 'camera', 'side', container='other_box', namespace='cams')
    assert made.ok
    assert rules.render() == (EXPECTED / 'rules.added.launch.xml').read_text(encoding='utf-8')
    box = rules.node('box')
    assert box is not None and [c.name for c in box.children] == ['camera', 'rear']
    assert rules.container_of(rules.node('side')).name == 'other_box'  # type: ignore[arg-type,union-attr]


def test_groups_by_id_and_refusals(tmp_path: Path) -> None:
    demo = Composition.open(str(copy_launch(tmp_path) / 'demo.launch.xml'),
                            definitions=definitions())
    group = demo.to_dict(analyse=False)['groups'][0]['id']
    assert demo.add('demo_pkg', 'listener', 'inside', group=group).ok
    assert demo.fqn(demo.node('inside')) == '/sub/inside'  # type: ignore[arg-type]
    assert [d.code for d in demo.add('demo_pkg', 'listener', 'x', group='g99').diagnostics] == \
        ['NODL970']
    assert [d.code for d in demo.add('demo pkg', 'listener', 'x').diagnostics] == ['NODL982']
    assert [d.code for d in demo.add('demo_pkg', 'listener', 'x', namespace='a b').diagnostics] \
        == ['NODL982']
    opaque = Composition.open(str(LAUNCH / 'opaque.launch.py'), definitions=definitions())
    assert [d.code for d in opaque.add('demo_pkg', 'talker', 'x').diagnostics] == ['NODL983']


def test_removing_keeps_the_neighbours_text(tmp_path: Path) -> None:
    demo = Composition.open(str(copy_launch(tmp_path) / 'demo.launch.xml'),
                            definitions=definitions())
    assert demo.add('demo_pkg', 'listener', 'inside', namespace='sub').ok
    assert demo.remove('counter').ok   # the group's second item; the new one follows it
    rules = Composition.open(str(copy_launch(tmp_path / 'r') / 'rules.launch.xml'),
                             definitions=definitions())
    assert rules.remove('camera').ok and rules.remove('listener').ok
    assert demo.render().endswith(
        '  <group>\n    <push-ros-namespace namespace="sub"/>\n'
        '    <node pkg="demo_pkg" exec="listener" name="inside"/>\n  </group>\n</launch>\n')
    assert rules.render().endswith(
        '  <arg name="topic" default="chat"/>\n'
        '  <node pkg="demo_pkg" exec="talker" name="talker"/>\n'
        '  <node_container pkg="rclcpp_components" exec="component_container" name="box"/>\n'
        '</launch>\n')
