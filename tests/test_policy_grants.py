"""A node instance's grants: its declared endpoints under final names, plus its base as the
client library creates it on the chosen distribution."""

from pathlib import Path

import pytest

from nodl.policy.grants import profile_for_instance, use_sim_time_can_be_true
from nodl.system import NodeInstance, resolve_node

POLICY = Path(__file__).parent / 'fixtures' / 'policy'


def _profile(file, name='node', namespace='/', remaps=None, params=None, library=None, distro='kilted'):
    resolved = resolve_node(POLICY / file, client_library=library)
    profile, problems = profile_for_instance(NodeInstance(resolved, name, namespace, remaps, params),
                                             distro=distro)
    assert problems == []
    return {(g.communication, g.access, g.name) for g in profile.grants.values()}


def test_declared_endpoints_under_final_names_with_remaps():
    got = _profile('relay.nodl.yaml', 'relay', '/robot', ['input:=/sensors/raw'])
    assert ('topic', 'subscribe', '/sensors/raw') in got
    assert ('topic', 'publish', '/robot/output') in got
    assert ('topic', 'publish', '/robot/relay/status') in got  # {node} expanded
    assert ('topic', 'publish', '/global/heartbeat') in got


def test_base_of_rclpy_on_kilted():
    got = _profile('talker.nodl.yaml', 'talker')
    assert got == {('topic', 'publish', '/chatter'), ('topic', 'publish', '/rosout'),
                   ('topic', 'publish', '/parameter_events')} | {
        ('service', 'reply', f'/talker/{s}') for s in (
            'describe_parameters', 'get_parameter_types', 'get_parameters', 'list_parameters',
            'set_parameters', 'set_parameters_atomically', 'get_type_description')}


def test_type_description_service_depends_on_distro_and_parameter():
    name = ('service', 'reply', '/talker/get_type_description')
    assert name not in _profile('talker.nodl.yaml', 'talker', distro='humble')
    assert name in _profile('talker.nodl.yaml', 'talker', distro='iron')
    assert name not in _profile('talker.nodl.yaml', 'talker',
                                params={'start_type_description_service': False})


def test_rclcpp_subscribes_to_parameter_events():
    assert ('topic', 'subscribe', '/parameter_events') in _profile('talker.nodl.yaml', library='rclcpp')
    assert ('topic', 'subscribe', '/parameter_events') not in _profile('talker.nodl.yaml')


def test_clock_only_when_use_sim_time_can_be_true():
    clock = ('topic', 'subscribe', '/clock')
    assert clock not in _profile('talker.nodl.yaml')
    assert clock in _profile('talker.nodl.yaml', params={'use_sim_time': True})
    assert clock not in _profile('talker.nodl.yaml', params={'use_sim_time': False})
    # the definition's default counts, and a launched value overrides it
    assert clock in _profile('sim_default.nodl.yaml')
    assert clock not in _profile('sim_default.nodl.yaml', params={'use_sim_time': False})
    assert [use_sim_time_can_be_true(v) for v in (True, False, None, 'false', '$(var sim)')] == \
        [True, False, False, False, True]


def test_lifecycle_services_and_transition_event():
    got = _profile('camera.nodl.yaml', 'camera', '/robot')
    for service in ('change_state', 'get_state', 'get_available_states',
                    'get_available_transitions', 'get_transition_graph'):
        assert ('service', 'reply', f'/robot/camera/{service}') in got
    assert ('topic', 'publish', '/robot/camera/transition_event') in got


def test_a_name_that_cannot_be_granted_is_a_diagnostic():
    resolved = resolve_node(POLICY / 'talker.nodl.yaml')
    instance = NodeInstance(resolved, 'talker')
    bound = next(e for e in instance.entities if e.name == '/chatter')
    instance.entities = tuple(e._replace(name='/chat*') if e == bound else e for e in instance.entities)
    profile, problems = profile_for_instance(instance)
    assert [d.code for d in problems] == ['NODL602']
    assert problems[0].file.endswith('talker.nodl.yaml') and problems[0].line == 7
    assert ('topic', 'publish', '/chat*') not in profile.grants
    with pytest.raises(ValueError):
        profile_for_instance(instance, distro='foxy')
