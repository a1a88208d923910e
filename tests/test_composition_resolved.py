"""The resolved node (nodl.composition.resolved): entities, providers, layers, locations."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl import ValidationError, compose
from nodl.composition.bases import base_file
from nodl.system import (
    EntityKind,
    InterfaceType,
    Location,
    Provider,
    ResolvedNode,
    resolve_node,
    resolve_registered,
)

SYSTEM = FIXTURES / 'system'
TALKER = SYSTEM / 'talker.nodl.yaml'


@pytest.fixture(scope='module')
def talker() -> ResolvedNode:
    return resolve_node(TALKER)


def line_of(path: Path, text: str) -> int:
    return path.read_text().splitlines().index(text) + 1


def test_what_the_node_is(talker: ResolvedNode) -> None:
    assert talker.file == str(TALKER)
    assert talker.base is not None and talker.base.value == 'node'
    assert (talker.client_library, talker.client_library_reason) == (
        'rclpy', 'the default; choose with --client-library')
    assert [layer.label for layer in talker.layers] == ['base:node', 'diagnostics.nodl.yaml', 'main']
    assert talker.interface.description == 'Talks on ~/chatter and serves a reset.'
    assert len(talker) == len(talker.entities) == len(list(talker))


def test_every_entity_has_its_kind_provider_and_layer(talker: ResolvedNode) -> None:
    table = {(e.kind.value, e.name): (e.provider.value, e.layer, e.declared_in) for e in talker}
    assert table[('parameter', 'use_sim_time')] == ('client_library', 'main', ('base:node', 'main'))
    assert table[('parameter', 'rate')] == ('implementation', 'main', ('main',))
    assert table[('parameter', 'diagnostics_period')] == (
        'other_code', 'diagnostics.nodl.yaml', ('diagnostics.nodl.yaml',))
    assert table[('publisher', '/diagnostics')] == (
        'other_code', 'main', ('diagnostics.nodl.yaml', 'main'))
    assert table[('publisher', '/rosout')] == ('client_library', 'base:node', ('base:node',))
    assert table[('service_server', '~/reset')] == ('implementation', 'main', ('main',))
    assert table[('action_client', '/navigate')] == ('implementation', 'main', ('main',))


def test_implementation_entities_are_main_only_never_the_base(talker: ResolvedNode) -> None:
    implemented = talker.implementation_entities()
    assert [(e.kind.value, e.name) for e in implemented] == [
        ('parameter', 'rate'), ('publisher', '~/chatter'), ('service_server', '~/reset'),
        ('action_client', '/navigate')]
    # as an interface definition (what a generator would be given)
    iface = talker.interface_of(implemented)
    assert list(iface.parameters or {}) == ['rate']
    assert [p.name for p in iface.publishers or ()] == ['~/chatter']
    assert iface.subscriptions is None
    assert {e.provider for e in talker.provided_by('client_library', 'other_code')} == {
        Provider.CLIENT_LIBRARY, Provider.OTHER_CODE}


def test_types_qos_and_definitions_are_typed(talker: ResolvedNode) -> None:
    chatter = talker.entity(EntityKind.PUBLISHER, '~/chatter')
    assert chatter.type == InterfaceType('std_msgs', 'msg', 'String')
    assert chatter.type_name == 'std_msgs/msg/String'
    assert chatter.qos is not None and (chatter.qos.depth, chatter.qos.reliability) == (10, 'RELIABLE')
    assert chatter.description == 'What the talker says.'
    assert chatter.definition.origin == 'main'
    assert talker.entity('action_client', '/navigate').qos is None
    rate = talker.entity('parameter', 'rate')
    assert (rate.type.name, rate.default_value, rate.read_only) == ('double', 2.0, False)
    assert talker.entity('parameter', 'start_type_description_service').read_only is True


def test_locations_point_at_the_winning_declaration(talker: ResolvedNode) -> None:
    chatter = talker.entity('publisher', '~/chatter')
    assert chatter.location == Location(str(TALKER), line_of(TALKER, '    - name: ~/chatter'), 7)
    rate = talker.entity('parameter', 'rate')  # a parameter is placed at its key
    assert rate.location == Location(str(TALKER), line_of(TALKER, '    rate:'), 5)
    period = talker.entity('parameter', 'diagnostics_period')
    assert Path(period.location.file) == (SYSTEM / 'diagnostics.nodl.yaml').resolve()
    assert period.location.line == line_of(SYSTEM / 'diagnostics.nodl.yaml', '  diagnostics_period:')
    rosout = talker.entity('publisher', '/rosout')
    assert rosout.location.file == base_file('node')
    assert rosout.location.line == line_of(Path(base_file('node')), '  - name: /rosout')


def test_locations_are_placed_on_first_use_only(tmp_path: Path) -> None:
    # Placing a declaration is not free: resolving does not place (an analysis of a thousand
    # nodes prints few locations); the first use does, and keeps the result.
    file = tmp_path / 'n.nodl.yaml'
    file.write_text('nodl_version: 2\nbase: node\nmain:\n  nodl_version: 2\n  description: N.\n'
                    '  publishers:\n    - {name: out, type: std_msgs/msg/String, description: O., qos:'
                    ' {history: KEEP_LAST, depth: 1, reliability: RELIABLE, durability: VOLATILE,'
                    ' liveliness: AUTOMATIC}}\n')
    fresh = resolve_node(file)
    out = fresh.entity('publisher', 'out')
    assert all(not isinstance(e._where, Location) for e in fresh.entities)  # type: ignore[attr-defined]
    first = out.location
    assert isinstance(out._where, Location) and out.location is first  # type: ignore[attr-defined]
    assert fresh.diagnostics == [] and first == Location(str(file), 7, 7)


def test_lookups(talker: ResolvedNode) -> None:
    assert talker.get('publisher', 'nope') is None
    with pytest.raises(KeyError, match="no subscription 'nope'"):
        talker.entity(EntityKind.SUBSCRIPTION, 'nope')
    with pytest.raises(ValueError):
        talker.of_kind('publishers')  # a section, not a kind
    assert [e.name for e in talker.of_kind('service_server')][-1] == '~/reset'
    assert {e.kind for e in talker.endpoints} == set(EntityKind) - {EntityKind.PARAMETER,
                                                                     EntityKind.SUBSCRIPTION,
                                                                     EntityKind.SERVICE_CLIENT,
                                                                     EntityKind.ACTION_SERVER}
    assert [e.name for e in talker.parameters] == [
        'use_sim_time', 'start_type_description_service', 'diagnostics_period', 'rate']


def test_rclcpp_base_and_an_unknown_library() -> None:
    cpp = resolve_node(TALKER, client_library='rclcpp')
    assert (cpp.client_library, cpp.client_library_reason) == ('rclcpp', 'as requested')
    sub = cpp.entity('subscription', '/parameter_events')
    assert (sub.provider, sub.layer) == (Provider.CLIENT_LIBRARY, 'base:node')
    assert sub.location.file.endswith('rclcpp/node.nodl.yaml')
    with pytest.raises(ValueError, match='unknown client library'):
        resolve_node(TALKER, client_library='rclc')


def test_a_composition_can_be_resolved_and_errors_raise() -> None:
    resolved = resolve_node(compose(TALKER))
    assert resolved.client_library == 'rclpy'
    assert resolved.entity('publisher', '~/chatter').layer == 'main'
    with pytest.raises(ValidationError) as exc:
        resolve_node(FIXTURES / 'composition' / 'overrides' / 'base_redefined.nodl.yaml')
    assert {d.code for d in exc.value.errors} == {'NODL307'}


def test_registered_nodes_take_their_package_build_type(monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = SYSTEM / 'prefix'
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    cpp, _, source = resolve_registered('cpp_pkg', 'driver')
    assert cpp is not None and Path(source) == prefix / 'share/cpp_pkg/nodl/driver.nodl.yaml'
    assert (cpp.client_library, cpp.client_library_reason) == (
        'rclcpp', "package 'cpp_pkg' is built with ament_cmake")
    py, _, _ = resolve_registered('py_pkg', 'driver')
    assert py is not None and py.client_library == 'rclpy'
    asked, _, _ = resolve_registered('cpp_pkg', 'driver', client_library='rclpy')
    assert asked is not None and asked.client_library_reason == 'as requested'
    missing, diagnostics, _ = resolve_registered('cpp_pkg', 'nope')
    assert missing is None and diagnostics[0].code == 'NODL306'


def test_nodes_resolved_in_one_run_share_their_base(tmp_path: Path) -> None:
    # Inside an index snapshot (one analysis) every node of a base shares its layer and the
    # entities only the base declares; what a node declares or refines stays its own, and
    # outside a snapshot nothing is shared.
    from nodl import ament_index

    files = []
    for i, refine in enumerate(('', '  parameters:\n    use_sim_time: {type: bool, default_value: false,'
                                    ' description: Refined.}\n')):
        file = tmp_path / f'n{i}.nodl.yaml'
        file.write_text('nodl_version: 2\nbase: node\nmain:\n  nodl_version: 2\n  description: N.\n'
                        + refine)
        files.append(file)
    with ament_index.snapshot():
        one, two = (resolve_node(f) for f in files)
        assert one.layers[0] is two.layers[0]
        assert one.entity('publisher', '/rosout') is two.entity('publisher', '/rosout')
        assert one.entity('parameter', 'use_sim_time') is not two.entity('parameter', 'use_sim_time')
        assert two.entity('parameter', 'use_sim_time').description == 'Refined.'
        assert one.entity('parameter', 'use_sim_time').description != 'Refined.'
    three = resolve_node(files[0])
    assert three.layers[0] is not one.layers[0] and three.layers[0].shared is None
    assert three.entity('publisher', '/rosout') is not one.entity('publisher', '/rosout')
    assert [(e.key, e.location, e.provider, e.declared_in) for e in three.entities] == \
        [(e.key, e.location, e.provider, e.declared_in) for e in one.entities]
