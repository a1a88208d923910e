"""nodl.composer.composition (with adding, connecting, parameters): the operations.

Each operation returns a Change: an error means nothing changed.  The file is edited in
place, and not over changes made on disk since it was read.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from composer_helpers import copy_launch, definitions
from nodl.composer import ComposerError, Composition
from nodl.launch.sandbox import LaunchLimits


@pytest.fixture
def demo(tmp_path: Path) -> Composition:
    return Composition.open(str(copy_launch(tmp_path) / 'demo.launch.xml'),
                            definitions=definitions())


def _codes(change) -> list[str]:  # type: ignore[no-untyped-def]
    return [d.code for d in change.diagnostics]


def test_nodes_are_found_by_id_final_name_and_name(demo: Composition) -> None:
    talker = demo.node('talker')
    assert talker is not None and demo.node('/talker') is talker and demo.node(talker.id) is talker
    assert demo.fqn(demo.node('counter')) == '/sub/counter'   # type: ignore[arg-type]
    node, problem = demo.find('nobody')
    assert node is None and problem is not None and problem.code == 'NODL970'
    assert '/sub/counter' in problem.message


def test_read_only_node_is_refused(demo: Composition) -> None:
    change = demo.set_parameter('quiet', 'x', '1')
    assert _codes(change) == ['NODL983'] and 'condition' in change.diagnostics[0].message


def test_set_checks_type_and_validators_at_once(demo: Composition) -> None:
    refused = demo.set_parameter('talker', 'rate', '500.0')
    assert _codes(refused) == ['NODL977'] and '0.1' in refused.diagnostics[0].message
    typed = demo.set_parameter('talker', 'rate', '3')
    assert _codes(typed) == ['NODL977'] and 'write 3.0' in typed.diagnostics[0].message
    unknown = demo.set_parameter('talker', 'rat', '3.0')
    assert _codes(unknown) == ['NODL978'] and "'rate'" in unknown.diagnostics[0].message
    assert not demo.dirty
    assert demo.set_parameter('talker', 'rate', '7.5').ok and demo.dirty
    assert '<param name="rate" value="7.5"/>' in demo.render()


def test_set_after_a_kept_parameter_file_goes_last(demo: Composition) -> None:
    # counter declares no parameters: a value is written, unchecked names are refused
    assert _codes(demo.set_parameter('counter', 'offset', '2')) == ['NODL978']


def test_add_places_nodes_in_namespace_groups(demo: Composition) -> None:
    assert demo.add('demo_pkg', 'listener', 'second', namespace='sub').ok
    assert demo.add('demo_pkg', 'listener', 'third', namespace='other').ok
    text = demo.render()
    assert ('<node pkg="demo_pkg" exec="counter" name="counter">\n'
            '      <param from="$(dirname)/counter.yaml"/>\n'
            '    </node>\n'
            '    <node pkg="demo_pkg" exec="listener" name="second"/>\n'
            '  </group>\n'
            '  <group>\n'
            '    <push-ros-namespace namespace="other"/>\n'
            '    <node pkg="demo_pkg" exec="listener" name="third"/>\n'
            '  </group>\n'
            '</launch>\n') in text
    assert demo.fqn(demo.node('third')) == '/other/third'  # type: ignore[arg-type]
    # a group's push of its literal namespace is the group, not a piece kept as written
    pushes = [k.what for k in demo.document.kept() if 'push' in k.what]
    assert pushes == [], pushes
    assert demo.save() == []
    reopened = Composition.open(demo.path, definitions=definitions())
    assert not [k for k in reopened.document.kept() if 'push' in k.what]
    assert not [d for d in reopened.kept_diagnostics() if 'push' in d.message]
    duplicate = demo.add('demo_pkg', 'listener', 'second', namespace='/sub')
    assert _codes(duplicate) == ['NODL982']
    assert _codes(demo.add('demo_pkg', 'listener', 'bad name')) == ['NODL982']
    unknown = demo.add('demo_pkg', 'nothing', 'x')
    assert unknown.ok and _codes(unknown) == ['NODL985']


def test_remove(demo: Composition) -> None:
    assert demo.remove('listener').ok
    assert 'name="listener"' not in demo.render()
    assert _codes(demo.remove('quiet')) == ['NODL983']


def test_connect_refuses_with_reasons(demo: Composition) -> None:
    demo.add('demo_pkg', 'counter', 'numbers')
    demo.add('demo_pkg', 'fast_listener', 'fast')
    demo.add('demo_pkg', 'strict_listener', 'strict')
    demo.add('demo_pkg', 'resetter', 'resetter')
    kinds = demo.connect('talker:chatter', 'resetter:reset')
    assert _codes(kinds) == ['NODL972']
    types = demo.connect('talker:chatter', 'numbers:count')
    assert _codes(types) == ['NODL973']
    assert 'std_msgs/msg/String' in types.diagnostics[0].message
    assert 'count:=/chatter on /numbers' in types.diagnostics[0].message  # the remap offered
    qos = demo.connect('talker:chatter', 'strict:messages')
    assert _codes(qos) == ['NODL974'] and 'durability' in qos.diagnostics[0].message
    assert demo.can_connect('talker:chatter', 'fast:messages').verdict == 'ok'
    missing = demo.connect('talker:nothing', 'fast:messages')
    assert _codes(missing) == ['NODL971'] and 'chatter' in missing.diagnostics[0].message
    assert not demo.dirty or demo.render().count('<remap') == 0


def test_connect_service_and_disconnect(demo: Composition) -> None:
    demo.add('demo_pkg', 'resetter', 'resetter')
    joined = demo.connect('resetter:reset', 'talker:~/reset')
    assert joined.ok and joined.remaps == [{'node': demo.node('resetter').id,  # type: ignore[union-attr]
                                            'from': 'reset', 'to': '/talker/reset'}]
    assert demo.can_connect('talker:~/reset', 'resetter:reset').connected
    again = demo.connect('talker:~/reset', 'resetter:reset')
    assert _codes(again) == ['NODL986']
    parted = demo.disconnect('talker:~/reset', 'resetter:reset')
    assert parted.ok and parted.removed and '<remap' not in demo.render()
    never = demo.disconnect('talker:chatter', 'listener:messages')
    assert _codes(never) == ['NODL986']


def test_save_refuses_a_file_changed_on_disk(demo: Composition) -> None:
    demo.set_parameter('talker', 'rate', '6.0')
    Path(demo.path).write_text(Path(demo.path).read_text(encoding='utf-8') + '<!-- mine -->\n',
                               encoding='utf-8')
    problems = demo.save()
    assert [d.code for d in problems] == ['NODL980']
    assert '<!-- mine -->' in Path(demo.path).read_text(encoding='utf-8')
    assert demo.save(force=True) == []
    assert 'value="6.0"' in Path(demo.path).read_text(encoding='utf-8')
    ids = [n.id for n in demo.nodes]
    demo.set_parameter('talker', 'rate', '8.0')
    assert demo.save() == [] and [n.id for n in demo.nodes] == ids


def test_new_refuses_an_existing_file(tmp_path: Path) -> None:
    path = tmp_path / 'a.launch.yaml'
    path.write_text('launch: []\n', encoding='utf-8')
    with pytest.raises(ComposerError) as caught:
        Composition.new(str(path))
    assert caught.value.diagnostic.code == 'NODL981'
    with pytest.raises(ComposerError) as caught:
        Composition.new(str(tmp_path / 'a.txt'))
    assert caught.value.diagnostic.code == 'NODL984'
    broken = tmp_path / 'b.launch.xml'
    broken.write_text('<launch>', encoding='utf-8')
    with pytest.raises(ComposerError) as caught:
        Composition.open(str(broken))
    assert caught.value.diagnostic.code == 'NODL984'


def test_to_dict_is_json(demo: Composition) -> None:
    import json

    data = json.loads(json.dumps(demo.to_dict()))
    talker = next(n for n in data['nodes'] if n['name'] == 'talker')
    assert talker['editable'] and talker['parameters'] == {'rate': 5.0}
    assert {'kind': 'publisher', 'name': 'chatter', 'final_name': '/chatter'}.items() <= \
        next(p for p in talker['ports'] if p['name'] == 'chatter').items()
    assert [k['what'] for k in data['kept']] == ['<arg>', '<include>']  # the push is the group's
    assert data['groups'] == [{'id': 'g4', 'namespace': 'sub', 'namespace_unknown': False,
                               'conditional': False, 'parent': None}]
    assert {f['code'] for f in data['findings']} >= {'NODL555'}


def test_other_formats_render_the_declarative_part(demo: Composition) -> None:
    yaml_text = demo.render('yaml')
    assert '  - node:\n      pkg: demo_pkg\n      exec: talker\n' in yaml_text
    body = yaml_text.split('\nlaunch:\n', 1)[1]   # (the comment above says what is left out)
    assert 'output' not in body and "output='screen'" in yaml_text   # kept pieces: XML's
    assert "PushRosNamespace('sub')" in demo.render('python')
    assert 'quiet' not in body   # read-only: its condition is XML's


def test_set_limits_analyses_anew(tmp_path: Path) -> None:
    demo = Composition.open(str(copy_launch(tmp_path) / 'demo.launch.py'),
                            definitions=definitions(), limits=LaunchLimits(execute=False))
    before = demo.analyse()
    assert demo.analyse() is before   # cached until something changes
    assert {f.code for f in before.findings} & {'NODL525', 'NODL526'}   # not run: said so
    allowed = LaunchLimits(execute=True)
    demo.set_limits(allowed)
    assert demo.limits is allowed and not demo.dirty
    after = demo.analyse()
    assert after is not before
    assert not {f.code for f in after.findings} & {'NODL525', 'NODL526'}


def test_a_yaml_edit_changes_only_what_it_edits(tmp_path: Path) -> None:
    path = copy_launch(tmp_path) / 'demo.launch.yaml'
    before = path.read_text(encoding='utf-8')
    c = Composition.open(str(path), definitions=definitions())
    assert c.set_parameter('talker', 'rate', '7.5').ok
    assert c.render() == before.replace('{name: rate, value: 5.0}', '{name: rate, value: 7.5}')
