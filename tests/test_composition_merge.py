"""Merging layers (nodl.composition.merge.merge_layers)."""

from __future__ import annotations

import pytest

from nodl import load_interface
from nodl.composition import Layer
from nodl.composition.merge import merge_layers
from nodl.diagnostics import Severity
from nodl.loading import check_source
from nodl.model import Interface

A = """\
nodl_version: 2
description: Layer A.
parameters:
  shared: {type: int, default_value: 1, description: From A.}
  only_a: {type: int, default_value: 2, description: From A.}
publishers:
  - name: chatter
    type: std_msgs/msg/String
    description: A's chatter.
    qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}
subscriptions:
  - name: chatter
    type: std_msgs/msg/String
    description: A's chatter subscription, in another section.
    qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}
action_clients:
  - {name: ~/go, type: test_msgs/action/Fibonacci, description: A's action client.}
"""

B = """\
nodl_version: 2
parameters:
  shared: {type: double, default_value: 1.5, description: From B.}
publishers:
  - name: other
    type: std_msgs/msg/String
    description: B's other.
    qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}
  - name: chatter
    type: std_msgs/msg/Bool
    description: B's chatter.
    qos: {history: KEEP_LAST, depth: 2, reliability: BEST_EFFORT}
action_clients:
  - {name: ~/go, type: test_msgs/action/Fibonacci, description: B's action client.}
"""

C = """\
nodl_version: 2
description: Layer C.
parameters:
  shared: {type: string, default_value: c, description: From C.}
"""


def layer(label: str, text: str, file: str) -> Layer:
    report = check_source(text, file=file)
    assert not report.has_errors(), report.diagnostics
    return Layer(label, report.model(), report.place)  # type: ignore[arg-type]


def test_later_layers_win_and_origins_name_them() -> None:
    merged, _ = merge_layers([layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml'),
                              layer('c', C, 'c.yaml')])
    assert (merged.parameters['shared'].type, merged.parameters['shared'].origin) == ('string', 'c')
    assert merged.parameters['only_a'].origin == 'a'
    chatter = next(p for p in merged.publishers if p.name == 'chatter')
    assert (chatter.type, chatter.qos.depth, chatter.origin) == ('std_msgs/msg/Bool', 2, 'b')
    assert [(s.name, s.origin) for s in merged.subscriptions] == [('chatter', 'a')]
    assert [(a.description, a.origin) for a in merged.action_clients] == [
        ("B's action client.", 'b')]


def test_entities_keep_the_position_of_their_first_declaration() -> None:
    merged, _ = merge_layers([layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml')])
    assert list(merged.parameters) == ['shared', 'only_a']
    assert [p.name for p in merged.publishers] == ['chatter', 'other']


def test_the_description_is_the_last_layers_even_when_empty() -> None:
    merged, _ = merge_layers([layer('a', A, 'a.yaml'), layer('c', C, 'c.yaml')])
    assert merged.description == 'Layer C.'
    merged, _ = merge_layers([layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml')])
    assert merged.description is None


def test_overrides_are_diagnostics_at_the_winning_entity() -> None:
    _, notes = merge_layers([layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml'),
                             layer('c', C, 'c.yaml')])
    # None of these layers is a base: a type change is a warning, the rest is info.
    assert [str(n) for n in notes] == [
        "b.yaml:3:3: warning: parameter 'shared' from b changes the type of the one from a "
        '(int -> double); the code behind a and this node disagree [parameters.shared] [NODL310]',
        "b.yaml:9:5: warning: publisher 'chatter' from b changes the type of the one from a "
        '(std_msgs/msg/String -> std_msgs/msg/Bool); the code behind a and this node disagree '
        '[publishers[1]] [NODL310]',
        "b.yaml:14:5: info: action client '~/go' from b overrides the one from a "
        '[action_clients[0]] [NODL304]',
        "c.yaml:4:3: warning: parameter 'shared' from c changes the type of the one from b "
        '(double -> string); the code behind b and this node disagree [parameters.shared] [NODL310]',
    ]
    assert notes[0].anchor == 'key'
    # each one relates the declaration it overrides
    assert notes[0].related == (('a.yaml', 4, 3, 'the declaration in a'),)
    assert notes[1].related == (('a.yaml', 7, 5, 'the declaration in a'),)


def base(text: str, file: str = 'base.yaml') -> Layer:
    report = check_source(text, file=file)
    assert not report.has_errors(), report.diagnostics
    return Layer('base:test', report.model(), report.place, role='base')  # type: ignore[arg-type]


BASE = """\
nodl_version: 2
parameters:
  p: {type: int, default_value: 1, read_only: true, description: Base p.}
publishers:
  - name: /out
    type: std_msgs/msg/String
    description: Base out.
    qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}
service_servers:
  - {name: ~/srv, type: std_srvs/srv/Empty, description: Base srv.,
     qos: {history: KEEP_LAST, depth: 5, reliability: RELIABLE}}
"""


def test_refining_a_base_entity_is_info() -> None:
    refined = layer('main', """\
nodl_version: 2
parameters:
  p: {type: int, default_value: 7, read_only: true, description: Refined p.}
publishers:
  - name: /out
    type: std_msgs/msg/String
    description: Refined out.
    qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}
service_servers:
  - {name: ~/srv, type: std_srvs/srv/Empty, description: Refined srv without QoS.}
""", 'main.yaml')
    merged, notes = merge_layers([base(BASE), refined])
    assert [(n.severity, n.code) for n in notes] == [(Severity.INFO, 'NODL304')] * 3
    assert merged.parameters['p'].description == 'Refined p.'


@pytest.mark.parametrize('change, code, words', [
    ('parameters: {p: {type: double, default_value: 1.0, read_only: true, description: x}}',
     'NODL307', "changes the type of the one from base:test (int -> double)"),
    ('parameters: {p: {type: int, default_value: 1, description: x}}',
     'NODL309', 'changes read_only of the one from base:test (True -> False)'),
    ('publishers: [{name: /out, type: std_msgs/msg/Bool, description: x, '
     'qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}}]',
     'NODL307', 'changes the type of the one from base:test'),
    ('publishers: [{name: /out, type: std_msgs/msg/String, description: x, '
     'qos: {history: KEEP_LAST, depth: 2, reliability: RELIABLE}}]',
     'NODL308', 'changes the QoS of the one from base:test'),
    ('service_servers: [{name: ~/srv, type: std_srvs/srv/Empty, description: x, '
     'qos: {history: KEEP_LAST, depth: 9, reliability: RELIABLE}}]',
     'NODL308', 'changes the QoS of the one from base:test'),
])
def test_changing_what_the_base_creates_is_an_error(change: str, code: str, words: str) -> None:
    _, [note] = merge_layers([base(BASE), layer('main', f'nodl_version: 2\n{change}\n', 'main.yaml')])
    assert (note.severity, note.code, note.file) == (Severity.ERROR, code, 'main.yaml')
    assert words in note.message
    assert note.related and note.related[0][0] == 'base.yaml'


def test_a_base_entity_is_judged_against_the_base_even_after_a_mixin() -> None:
    mixin = layer('mixin', 'nodl_version: 2\nparameters: {p: {type: double, default_value: 1.0, '
                  'read_only: true, description: x}}\n', 'mixin.yaml')
    main = layer('main', 'nodl_version: 2\nparameters: {p: {type: double, default_value: 2.0, '
                 'read_only: true, description: y}}\n', 'main.yaml')
    _, notes = merge_layers([base(BASE), mixin, main])
    assert [(n.file, n.code) for n in notes] == [('mixin.yaml', 'NODL307'), ('main.yaml', 'NODL307')]


def test_traced_declarations_list_every_layer_in_order() -> None:
    from nodl.composition.merge import merge_traced

    result = merge_traced([layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml'), layer('c', C, 'c.yaml')])
    trace = result.declarations[('parameters', 'shared')]
    assert [(d.layer.label, d.path) for d in trace] == [
        ('a', ('parameters', 'shared')), ('b', ('parameters', 'shared')),
        ('c', ('parameters', 'shared'))]
    assert [d.layer.label for d in result.declarations[('publishers', 'other')]] == ['b']
    assert result.declarations[('publishers', 'chatter')][1].path == ('publishers', 1)


def test_no_override_no_note() -> None:
    merged, notes = merge_layers([layer('a', A, 'a.yaml')])
    assert notes == []
    assert merged.parameters['shared'].origin == 'a'


def test_the_same_name_in_two_sections_is_not_an_override() -> None:
    _, notes = merge_layers([layer('a', A, 'a.yaml')])
    assert notes == []  # chatter is both a publisher and a subscription of A


def test_layers_are_not_modified() -> None:
    a, b = layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml')
    before = (a.interface.to_dict(), b.interface.to_dict())
    merge_layers([a, b])
    assert (a.interface.to_dict(), b.interface.to_dict()) == before
    assert a.interface.parameters['shared'].origin is None
    assert a.interface.publishers[0].origin is None


def test_no_layers_is_an_empty_interface() -> None:
    merged, notes = merge_layers([])
    assert merged == Interface(nodl_version=2)
    assert merged.parameters is None and merged.publishers is None
    assert notes == []


def test_a_layer_prefix_places_notes_inside_a_node_document() -> None:
    node = ('nodl_version: 2\nmixins:\n  - nodl_version: 2\n    parameters:\n'
            '      p: {type: int, default_value: 1, description: mixin}\n'
            'main:\n  nodl_version: 2\n  parameters:\n'
            '    p: {type: int, default_value: 2, description: main}\n')
    report = check_source(node, file='node.yaml')
    model = report.model()
    _, notes = merge_layers([Layer('mixins[0]', model.mixins[0], report.place, ('mixins', 0)),
                             Layer('main', model.main, report.place, ('main',))])
    assert [str(n) for n in notes] == [
        "node.yaml:9:5: info: parameter 'p' from main overrides the one from mixins[0] "
        '[main.parameters.p] [NODL304]']


def test_a_layer_without_placement_gives_unplaced_notes() -> None:
    one = load_interface('nodl_version: 2\nparameters: {p: {type: int, default_value: 1, description: x}}\n')
    two = load_interface('nodl_version: 2\nparameters: {p: {type: int, default_value: 2, description: y}}\n')
    merged, [note] = merge_layers([Layer('one', one), Layer('two', two)])
    assert (note.file, note.line, note.column, note.path) == ('<string>', 0, 0, ('parameters', 'p'))
    assert merged.parameters['p'].default_value == 2


def test_merged_result_round_trips_as_an_interface_definition() -> None:
    from nodl import dump_nodl

    merged, _ = merge_layers([layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml'),
                              layer('c', C, 'c.yaml')])
    again = load_interface(dump_nodl(merged))
    assert again == merged


def test_merged_entities_are_stamped_copies_of_every_field() -> None:
    # Merging copies each entity field by field (quicker than copy.copy) for the model's
    # classes: every class is copied that way, every field is kept, the layer's is untouched.
    import dataclasses

    from nodl.composition.merge import _SLOTS
    from nodl.model.interface import ActionEndpoint, ServiceEndpoint, TopicEndpoint
    from nodl.model.parameter import ParameterDefinition

    assert set(_SLOTS) == {TopicEndpoint, ServiceEndpoint, ActionEndpoint, ParameterDefinition}
    a = load_interface(A)
    merged, _ = merge_layers([Layer('a', a)])
    originals = list((a.parameters or {}).values()) + a.endpoints('publishers')
    copies = list((merged.parameters or {}).values()) + merged.endpoints('publishers')
    for original, copy in zip(originals, copies, strict=True):
        assert copy is not original and copy.origin == 'a' and original.origin is None
        assert [getattr(copy, f.name) for f in dataclasses.fields(copy) if f.name != 'origin'] == \
            [getattr(original, f.name) for f in dataclasses.fields(original) if f.name != 'origin']


NODE = """\
nodl_version: 2
base: node
main:
  nodl_version: 2
  description: A node.
  parameters:
    rate: {{type: double, default_value: 10.0, description: Rate.}}
{extra}"""


def test_a_run_shares_the_base_and_copies_a_trace_only_when_a_later_layer_adds_to_it() -> None:
    # Within a snapshot (an analysis) every node shares the base layer's merge; a node that
    # refines a base parameter must not change what the others see.
    from nodl import ament_index
    from nodl.composition import compose

    refined = NODE.format(extra='    use_sim_time: {type: bool, default_value: true, '
                                'description: Refined.}\n')
    plain = NODE.format(extra='')
    key = ('parameters', 'use_sim_time')
    with ament_index.snapshot():
        first, other, again = compose(refined), compose(plain), compose(refined)
    assert [d.layer.label for d in first.declarations[key]] == ['base:node', 'main']
    assert [d.layer.label for d in again.declarations[key]] == ['base:node', 'main']
    assert [d.layer.label for d in other.declarations[key]] == ['base:node']
    assert other.declarations[key] is not first.declarations[key]
    assert other.interface.parameters['use_sim_time'].default_value is False
    assert first.interface.parameters['use_sim_time'].default_value is True
    assert other.declarations[('parameters', 'rate')] != first.declarations[('parameters', 'rate')]
