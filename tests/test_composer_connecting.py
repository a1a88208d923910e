"""nodl.composer.connecting: the rule that makes two final names meet, written and taken away.

(The refusals for kinds, types and QoS are in test_composer_composition.py.)
"""

from __future__ import annotations

from pathlib import Path

from composer_helpers import FIXTURES, copy_launch, definitions
from nodl.composer import Composition
from nodl.composer.connecting import resolve_ports

EXPECTED = FIXTURES / 'expected'


def test_the_rule_goes_first_relative_and_replaces_one_with_the_same_from(tmp_path: Path) -> None:
    path = tmp_path / 'robot.launch.yaml'
    composition = Composition.new(str(path), definitions=definitions())
    for name, executable, namespace in (('talker', 'talker', 'robot'),
                                        ('listener', 'listener', 'robot'),
                                        ('far', 'listener', None)):
        assert composition.add('demo_pkg', executable, name, namespace=namespace).ok
    assert composition.set_remaps('/robot/listener', ['messages:=old', 'x:=y']).ok
    near = composition.connect('/robot/talker:chatter', '/robot/listener:messages')
    listener = composition.node('/robot/listener')
    assert near.ok and near.remaps == [{'node': listener.id, 'from': 'messages',  # type: ignore[union-attr]
                                        'to': 'chatter'}]   # relative: the same namespace
    far = composition.connect('/robot/talker:chatter', 'far:messages')
    assert far.remaps[0]['to'] == '/robot/chatter'
    assert composition.render() == (EXPECTED / 'connected.launch.yaml').read_text(encoding='utf-8')
    parted = composition.disconnect('far:messages', '/robot/talker:chatter')
    assert parted.ok and parted.removed == [{'node': far.node, 'from': 'messages',
                                             'to': '/robot/chatter'}]


def test_names_that_meet_through_kept_rules(tmp_path: Path) -> None:
    rules = Composition.open(str(copy_launch(tmp_path) / 'rules.launch.xml'),
                             definitions=definitions())
    (_, _), problem = resolve_ports(rules, 'talker', 'listener:messages')
    assert problem is not None and problem.code == 'NODL971' and 'NODE:ENDPOINT' in problem.message
    (_, _), problem = resolve_ports(rules, 'talker:chatter', 'nobody:messages')
    assert problem is not None and problem.code == 'NODL970'
    (talker, listener), problem = resolve_ports(rules, 'talker:chatter', 'listener:messages')
    assert problem is None and talker.final_name == listener.final_name == '/chatter'
    joined = rules.connect('talker:chatter', 'listener:messages')
    assert [d.code for d in joined.diagnostics] == ['NODL986'] and not rules.dirty
    # the listener's rules hold one kept as written: its own rules cannot be recomputed
    parted = rules.disconnect('talker:chatter', 'listener:messages')
    assert [d.code for d in parted.diagnostics] == ['NODL987'] and not rules.dirty
