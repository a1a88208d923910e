"""Merging layers (nodl_schema.composition.merge.merge_layers)."""

from __future__ import annotations

from nodl_schema import load_interface
from nodl_schema.composition import Layer
from nodl_schema.composition.merge import merge_layers
from nodl_schema.diagnostics import Severity
from nodl_schema.loading import check_source
from nodl_schema.model import Interface

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


def test_overrides_are_info_diagnostics_at_the_winning_entity() -> None:
    _, notes = merge_layers([layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml'),
                             layer('c', C, 'c.yaml')])
    assert all(n.severity is Severity.INFO for n in notes)
    assert [str(n) for n in notes] == [
        "b.yaml:3:3: info: parameter 'shared' from b overrides the one from a [parameters.shared]",
        "b.yaml:9:5: info: publisher 'chatter' from b overrides the one from a [publishers[1]]",
        "b.yaml:14:5: info: action client '~/go' from b overrides the one from a "
        '[action_clients[0]]',
        "c.yaml:4:3: info: parameter 'shared' from c overrides the one from b [parameters.shared]",
    ]
    assert notes[0].anchor == 'key'


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
        '[main.parameters.p]']


def test_a_layer_without_placement_gives_unplaced_notes() -> None:
    one = load_interface('nodl_version: 2\nparameters: {p: {type: int, default_value: 1, description: x}}\n')
    two = load_interface('nodl_version: 2\nparameters: {p: {type: int, default_value: 2, description: y}}\n')
    merged, [note] = merge_layers([Layer('one', one), Layer('two', two)])
    assert (note.file, note.line, note.column, note.path) == ('<string>', 0, 0, ('parameters', 'p'))
    assert merged.parameters['p'].default_value == 2


def test_merged_result_round_trips_as_an_interface_definition() -> None:
    from nodl_schema import dump_nodl

    merged, _ = merge_layers([layer('a', A, 'a.yaml'), layer('b', B, 'b.yaml'),
                              layer('c', C, 'c.yaml')])
    again = load_interface(dump_nodl(merged))
    assert again == merged
