"""Node instances (nodl.composition.instance): final names, remaps, parameters.

The final names are compared with what a real rclpy node, started with the
same name, namespace and remapping rules, shows in the ROS graph.
"""

from __future__ import annotations

import pytest

from conftest import FIXTURES
from nodl.live.observe import observe_node
from nodl.naming import InvalidRemapRuleError
from nodl.system import EntityKind, NodeInstance, resolve_node

SYSTEM = FIXTURES / 'system'


@pytest.fixture(scope='module')
def talker():  # type: ignore[no-untyped-def]
    return resolve_node(SYSTEM / 'talker.nodl.yaml')


def test_final_names_expand_against_name_and_namespace(talker) -> None:  # type: ignore[no-untyped-def]
    instance = NodeInstance(talker, 'talker', '/robot')
    assert (instance.name, instance.namespace, instance.fqn) == ('talker', '/robot', '/robot/talker')
    names = {(b.kind.value, b.entity.name): b.name for b in instance.entities}
    assert names[('publisher', '~/chatter')] == '/robot/talker/chatter'
    assert names[('publisher', '/diagnostics')] == '/diagnostics'
    assert names[('service_server', '~/reset')] == '/robot/talker/reset'
    assert names[('service_server', '~/get_parameters')] == '/robot/talker/get_parameters'
    assert names[('parameter', 'rate')] == 'rate'
    assert instance.final_name(('publisher', '~/chatter')) == '/robot/talker/chatter'
    assert instance.find(EntityKind.SERVICE_SERVER, '/robot/talker/reset') is not None
    assert instance.find('publisher', '/nope') is None


def test_remap_rules_and_node_renames(talker) -> None:  # type: ignore[no-untyped-def]
    instance = NodeInstance(talker, 'talker', '/robot',
                            ['~/chatter:=/chat', '__node:=speaker', '__ns:=/team',
                             'rosservice://~/reset:=/reset_all', 'other:/diagnostics:=/elsewhere'])
    assert instance.fqn == '/team/speaker'
    assert (instance.created_name, instance.created_namespace) == ('talker', '/robot')
    assert instance.final_name(('publisher', '~/chatter')) == '/chat'
    assert instance.final_name(('service_server', '~/reset')) == '/reset_all'
    assert instance.final_name(('publisher', '/diagnostics')) == '/diagnostics'  # other node's rule
    assert instance.final_name(('service_server', '~/list_parameters')) == \
        '/team/speaker/list_parameters'
    # a whole command line works too
    line = NodeInstance(talker, 'talker', '/', ['--ros-args', '-r', '~/chatter:=out', '-p', 'x:=1'])
    assert line.final_name(('publisher', '~/chatter')) == '/out'
    with pytest.raises(InvalidRemapRuleError):
        NodeInstance(talker, 'talker', '/', ['no rule'])
    with pytest.raises(ValueError):
        NodeInstance(talker, 'bad name!', '/')


def test_an_instance_given_its_names_resolves_as_one_that_makes_them(talker) -> None:  # type: ignore[no-untyped-def]
    from nodl.naming import NodeNames, parse_remap_rules

    rules = parse_remap_rules(['~/chatter:=/chat', '__ns:=/team', 'reset:=/r'])
    made = NodeInstance(talker, 'talker', '/robot', rules)
    names = NodeNames.create('talker', '/robot', rules)
    given = NodeInstance(talker, 'talker', '/robot', rules, names=names)
    assert given.names is names and given.fqn == made.fqn == '/team/talker'
    assert [(b.entity, b.name) for b in given.entities] == [(b.entity, b.name) for b in made.entities]


def test_parameter_values_are_defaults_overridden(talker) -> None:  # type: ignore[no-untyped-def]
    instance = NodeInstance(talker, 'talker', '/', parameter_overrides={'rate': 5.0, 'nope': 1})
    values = instance.parameter_values()
    assert values['rate'] == 5.0
    assert values['diagnostics_period'] == 1.0
    assert values['use_sim_time'] is False
    assert instance.undeclared_overrides() == ['nope']


def test_final_names_agree_with_a_real_rclpy_node(ros_node) -> None:  # type: ignore[no-untyped-def]
    rules = ['commands:=cmd_in', '~/status:=/health', 'rosservice://~/reset:=/reset_all',
             '__ns:=/moved']
    ros_node('full_node.py', 'inst', '/sys', '--ros-args', *[x for r in rules for x in ('-r', r)])
    resolved = resolve_node(FIXTURES / 'live' / 'full_node.nodl.yaml')
    instance = NodeInstance(resolved, 'inst', '/sys', rules)
    observed = observe_node(instance.fqn, timeout=15, parameters=False)
    assert observed.fully_qualified_name == instance.fqn == '/moved/inst'
    for kind in EntityKind:
        if kind is EntityKind.PARAMETER:
            continue
        declared = {b.name for b in instance.of_kind(kind)}
        seen = {e.name for e in getattr(observed, kind.section)}
        assert declared == seen, kind


def test_an_instance_and_its_entities_form_no_reference_cycle(talker) -> None:  # type: ignore[no-untyped-def]
    # A large analysis hangs off its instances: with a cycle it would be freed only by the
    # garbage collector.  With the collector off, letting go must free the instance at once.
    import gc
    import weakref

    was_enabled = gc.isenabled()
    gc.disable()
    try:
        instance = NodeInstance(talker, 'talker', '/robot')
        entities = instance.entities
        assert entities == instance.entities and hash(entities) == hash(instance.entities)
        assert instance.endpoints == [e for e in entities if not e.entity.is_parameter]
        alive = weakref.ref(instance)
        del instance
        assert alive() is entities[0].instance  # an entity keeps its instance alive
        del entities
        assert alive() is None
    finally:
        if was_enabled:
            gc.enable()


def test_entities_can_be_replaced(talker) -> None:  # type: ignore[no-untyped-def]
    instance = NodeInstance(talker, 'talker', '/robot')
    chatter = instance.find('publisher', '/robot/talker/chatter')
    assert chatter is not None
    instance.entities = tuple(e._replace(name='/renamed') if e == chatter else e
                              for e in instance.entities)
    assert instance.find('publisher', '/renamed') is not None
    assert instance.final_name(chatter.entity) == '/renamed'
    assert '/renamed' in [e.name for e in instance.endpoints]
