"""nodl.composer.analysed, and the round trip: compose -> save in each format -> nodl analyse.

The composition is analysed by the real analysis (nodl.system.run.analyse_launch, what
``nodl analyse`` runs); what is saved, analysed again from the file, is the same system
(final names, remapping rules, parameters, connections) in the three formats.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

from composer_helpers import definitions, example_copy, example_definitions
from nodl.composer import Composition
from nodl.system.run import analyse_launch


def _system(nodes: list[Any]) -> dict[str, Any]:
    """What must be the same: per final name, what runs, rules, parameters, endpoints."""
    out = {}
    for node in nodes:
        endpoints = sorted((e.entity.kind.value, e.name) for e in node.instance.endpoints) \
            if node.instance is not None else []
        out[node.fqn] = {'runs': (node.package, node.entry.executable or node.entry.plugin),
                         'rules': [str(r) for r in node.rules],
                         'parameters': node.parameter_values(), 'endpoints': endpoints}
    return out


def _compose(path: Path) -> Composition:
    c = Composition.new(str(path), definitions=definitions())
    for args, options in ((('demo_pkg', 'talker', 'talker'), {'namespace': 'robot'}),
                          (('demo_pkg', 'listener', 'listener'), {'namespace': 'robot'}),
                          (('demo_pkg', 'listener', 'logger'), {}),
                          (('demo_pkg', 'camera', 'camera'), {'container': 'cameras'})):
        change = c.add(*args, **options)
        assert change.ok and not change.diagnostics, change
    assert c.connect('/robot/talker:chatter', '/robot/listener:messages').ok
    assert c.connect('/robot/talker:chatter', 'logger:messages').ok
    assert c.set_parameter('/robot/talker', 'rate', '2.5').ok
    assert c.set_parameter('talker', 'prefix', '3').ok   # a string that looks like a number
    assert c.set_parameter('camera', 'fps', '15.0').ok
    return c


@pytest.fixture(scope='module')
def composed(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple[Composition, Any, Any]]:
    folder = tmp_path_factory.mktemp('composed')
    out = {}
    for suffix in ('xml', 'yaml', 'py'):
        path = folder / f'demo.launch.{suffix}'
        c = _compose(path)
        before = c.analyse().analysis   # unsaved: analysed through a hidden copy
        assert c.save() == []
        after = analyse_launch(str(path), definitions=definitions())
        out[suffix] = (c, before, after)
    assert sorted(os.listdir(folder)) == ['demo.launch.py', 'demo.launch.xml', 'demo.launch.yaml']
    return out


def test_saved_file_analyses_to_the_composed_system(composed) -> None:  # type: ignore[no-untyped-def]
    for suffix, (_, before, after) in composed.items():
        assert _system(after.nodes) == _system(before.nodes), suffix
        system = _system(after.nodes)
        assert system['/robot/listener']['rules'] == ['messages:=chatter']
        assert system['/logger']['rules'] == ['messages:=/robot/chatter']
        assert system['/robot/talker']['parameters'] == {'rate': 2.5, 'prefix': '3'}
        assert system['/camera']['parameters'] == {'fps': 15.0}
        assert system['/cameras']['runs'] == ('rclcpp_components', 'component_container')


def test_the_three_formats_resolve_the_same(composed) -> None:  # type: ignore[no-untyped-def]
    systems = {suffix: _system(after.nodes) for suffix, (_, _, after) in composed.items()}
    assert systems['xml'] == systems['yaml'] == systems['py']


def test_connections_and_only_the_expected_findings(composed) -> None:  # type: ignore[no-untyped-def]
    for suffix, (c, _, after) in composed.items():
        joined = {(j['from']['final_name'], c.fqn(c.node(j['to']['node'])))
                  for j in c.connections() if j['from']['provider'] != 'client_library'}
        assert ('/robot/chatter', '/robot/listener') in joined and \
            ('/robot/chatter', '/logger') in joined, suffix
        # what is left: the camera's images and the talker's reset service have no user
        codes = sorted({f.code for f in after.findings})
        assert codes == ['NODL558'], (suffix, [str(f.diagnostic) for f in after.findings])


def test_findings_name_the_launch_file_not_the_hidden_copy(tmp_path: Path) -> None:
    path = tmp_path / 'one.launch.xml'
    c = Composition.new(str(path), definitions=definitions())
    c.add('demo_pkg', 'listener', 'listener')
    findings = c.analyse().findings
    assert findings and {f.diagnostic.file for f in findings} == {str(path)}
    assert os.listdir(tmp_path) == []   # the hidden copy is gone, nothing saved yet
    assert c.analyse().node(c.nodes[0].id).fqn == '/listener'


def test_example_system_opens_edits_and_saves_cleanly(tmp_path: Path) -> None:
    folders = definitions(example_definitions(tmp_path))
    system = example_copy(tmp_path)
    path = system / 'launch' / 'rover.launch.xml'
    original = path.read_text(encoding='utf-8')
    reference = analyse_launch(str(path), definitions=folders)
    c = Composition.open(str(path), definitions=folders)
    assert _system(c.analyse().analysis.nodes) == _system(reference.nodes)
    # the planted multiple-publishers: teleop publishes into the safety controller instead
    change = c.connect('/rover/teleop:cmd_vel', '/rover/safety_controller:cmd_vel_in')
    assert change.ok and change.remaps == [{'node': 'n4', 'from': 'cmd_vel_in', 'to': 'cmd_vel'}]
    assert c.set_parameter('/rover/battery_monitor', 'capacity_ah', '30.0').ok
    # into the group whose namespace is a launch argument's value
    assert c.add('rover_tools', 'dashboard', 'dashboard2', group='g1').ok
    assert c.save() == []
    text = path.read_text(encoding='utf-8')
    # only the two edited entries changed; everything else is as written
    changed = [line for line in text.splitlines() if line not in original.splitlines()]
    assert changed == ['      <param name="capacity_ah" value="30.0"/>',
                       '      <remap from="cmd_vel_in" to="cmd_vel"/>',
                       '    <node pkg="rover_tools" exec="dashboard" name="dashboard2"/>']
    after = analyse_launch(str(path), definitions=folders)
    nodes = _system(after.nodes)
    assert nodes['/rover/safety_controller']['rules'] == ['cmd_vel_in:=cmd_vel']
    assert nodes['/rover/battery_monitor']['parameters']['capacity_ah'] == 30.0
    assert nodes['/rover/dashboard2']['runs'] == ('rover_tools', 'dashboard')
    kinds = {f.kind for f in after.findings}
    assert {f.kind for f in reference.findings} - kinds <= {'unused-remap'}
