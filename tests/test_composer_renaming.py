"""nodl.composer.renaming: a node's name and namespace, and its own remapping rules.

Every refusal changes nothing; the text written is compared with expected files.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from composer_helpers import FIXTURES, LAUNCH, copy_launch, definitions
from nodl.composer import Change, Composition, Remap
from nodl.composer.renaming import rule_pairs

EXPECTED = FIXTURES / 'expected'


@pytest.fixture
def rules(tmp_path: Path) -> Composition:
    return Composition.open(str(copy_launch(tmp_path) / 'rules.launch.xml'),
                            definitions=definitions())


def _codes(change: Change) -> list[str | None]:
    return [d.code for d in change.diagnostics]


def test_rename_writes_the_entry_and_only_it(rules: Composition) -> None:
    camera = rules.node('camera')
    assert camera is not None
    assert rules.rename(camera, 'front_camera', 'cams').ok
    assert rules.rename('talker', 'speaker', '/robot').ok
    assert rules.fqn(camera) == '/cams/front_camera'
    assert rules.fqn(rules.node('speaker')) == '/robot/speaker'  # type: ignore[arg-type]
    assert rules.dirty
    assert rules.render() == (EXPECTED / 'rules.renamed.launch.xml').read_text(encoding='utf-8')
    # empty or None: no attribute, the program names its node
    assert rules.rename('speaker', '', None).ok
    assert '<node pkg="demo_pkg" exec="talker"/>' in rules.render()


def test_rename_refusals_change_nothing(tmp_path: Path, rules: Composition) -> None:
    bad = rules.rename('talker', 'two words', 'a//b')
    assert _codes(bad) == ['NODL982', 'NODL982'] and not bad.ok
    assert "'two words' is not a node name" in bad.diagnostics[0].message
    assert "'a//b' is not a namespace" in bad.diagnostics[1].message
    assert (bad.diagnostics[0].line, bad.diagnostics[0].column) == (11, 3)
    taken = rules.rename('talker', 'listener', None)
    assert _codes(taken) == ['NODL982'] and 'is called /listener already' in \
        taken.diagnostics[0].message
    assert _codes(rules.rename('nobody', 'x', None)) == ['NODL970']
    same = rules.rename('talker', 'talker', None)
    assert same.ok and not same.diagnostics
    assert not rules.dirty
    demo = Composition.open(str(copy_launch(tmp_path / 'demo') / 'demo.launch.xml'),
                            definitions=definitions())
    assert _codes(demo.rename('quiet', 'loud', None)) == ['NODL983']  # a condition: read-only


def test_rename_checks_names_the_analysis_gives() -> None:
    """A namespace given by a launch argument: only the analysis knows /rover."""
    composition = Composition.open(str(LAUNCH / 'argument_namespace.launch.xml'),
                                   definitions=definitions())
    clash = composition.rename('listener', 'talker', None)
    assert _codes(clash) == ['NODL982']
    assert 'is called /rover/talker already' in clash.diagnostics[0].message
    assert composition.rename('listener', 'talker', 'left').ok   # /rover/left/talker
    assert composition.fqn(composition.nodes[1]) == '/?/left/talker'  # until analysed again
    composition.analyse()
    assert composition.fqn(composition.nodes[1]) == '/rover/left/talker'


def test_set_remaps_keeps_kept_rules_in_place(rules: Composition) -> None:
    change = rules.set_remaps('listener', ['messages:=/robot/chatter', ('extra', 'more')])
    assert change.ok and not change.diagnostics
    assert change.remaps == [{'node': 'n1', 'from': 'messages', 'to': '/robot/chatter'},
                             {'node': 'n1', 'from': 'extra', 'to': 'more'}]
    assert change.removed == [{'node': 'n1', 'from': 'messages', 'to': '/chatter'},
                              {'node': 'n1', 'from': 'other', 'to': 'elsewhere'}]
    assert rules.render() == (EXPECTED / 'rules.remapped.launch.xml').read_text(encoding='utf-8')
    # the same rules again: nothing changes; none: only the kept rule is left
    assert rules.set_remaps('listener', [('messages', '/robot/chatter'), 'extra:=more']).ok
    assert rules.set_remaps('listener', []).removed
    listener = rules.node('listener')
    assert listener is not None and not any(isinstance(r, Remap) for r in listener.remaps)
    assert len(listener.remaps) == 1   # the rule with a substitution, kept as written
    # a node without rules gets them after its kept ones (none here)
    assert rules.set_remaps('talker', ['chatter:=/chat']).ok
    assert '<node pkg="demo_pkg" exec="talker" name="talker">\n' \
           '    <remap from="chatter" to="/chat"/>\n  </node>' in rules.render()


def test_unchanged_rules_are_not_a_change(rules: Composition) -> None:
    same = rules.set_remaps('listener', ['messages:=/chatter', 'other:=elsewhere'])
    assert same.ok and not same.remaps and not same.removed and not rules.dirty


def test_set_remaps_refuses_what_rcl_refuses(rules: Composition) -> None:
    refused = rules.set_remaps('listener', ['messages', ('cmd vel', 'x'), 'a:=b', 'a:=:=b'])
    assert _codes(refused) == ['NODL988', 'NODL988', 'NODL988']   # each bad rule, at once
    assert "rule 1 'messages' is not FROM:=TO" in refused.diagnostics[0].message
    assert "rule 2 'cmd vel:=x'" in refused.diagnostics[1].message
    assert "rule 4 'a:=:=b'" in refused.diagnostics[2].message
    assert not rules.dirty
    hidden = rules.set_remaps('listener', ['a:=b', 'a:=c'])
    assert hidden.ok and _codes(hidden) == ['NODL989']
    assert 'a:=c never applies' in hidden.diagnostics[0].message
    assert rules.set_remaps('listener', ['node_only:x:=y', '__ns:=/x']).ok  # rcl's forms


def test_set_remaps_refuses_read_only_rules(tmp_path: Path) -> None:
    computed = Composition.open(str(LAUNCH / 'computed.launch.py'), definitions=definitions())
    change = computed.set_remaps('listener', ['a:=b'])
    assert _codes(change) == ['NODL976'] and 'computed by code' in change.diagnostics[0].message
    demo = Composition.open(str(copy_launch(tmp_path) / 'demo.launch.xml'),
                            definitions=definitions())
    assert _codes(demo.set_remaps('quiet', ['a:=b'])) == ['NODL983']
    assert _codes(demo.set_remaps('nobody', ['a:=b'])) == ['NODL970']


def test_rule_pairs() -> None:
    assert rule_pairs(['a:=b', ('c', 'd'), 'n:e:=f']) == (
        [('a', 'b'), ('c', 'd'), ('n:e', 'f')], [])
    pairs, problems = rule_pairs(['x', ('', 'y')])
    assert pairs == [] and problems[0] == "rule 1 'x' is not FROM:=TO"
    assert problems[1].startswith("rule 2 ':=y': ")
