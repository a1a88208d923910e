"""compare(), parse_remaps() and conforms() on synthetic observations.

The declared side is a real composed definition loaded from a fixture file
(tests/fixtures/live/drive_node.nodl.yaml: base ``node``, the referenced
mixin ``drive_health.nodl.yaml``, an in-place mixin and ``main``); the
observed side is an ObservedNode written by hand, so every difference can be
provoked on purpose.
"""

from __future__ import annotations

import copy
from typing import Any

import pytest

from conftest import FIXTURES
from nodl.live.check import load_definition
from nodl.live.conformance import DRIFT_KINDS, LiveDiagnostic, compare, conforms, parse_remaps
from nodl.live.observe import ObservedEndpoint, ObservedNode, ObservedParameter

LIVE = FIXTURES / 'live'
NAME, NAMESPACE = 'drive', '/base'

_PARAM_SERVICES = ['describe_parameters', 'get_parameter_types', 'get_parameters', 'list_parameters',
                   'set_parameters', 'set_parameters_atomically']


@pytest.fixture(scope='module')
def composed():
    return load_definition(LIVE / 'drive_node.nodl.yaml')


def _ep(name: str, type_: str, qos: dict[str, Any] | None = None) -> ObservedEndpoint:
    return ObservedEndpoint(name, type_, qos)


def conforming() -> ObservedNode:
    """What /base/drive would expose if it did exactly what drive_node.nodl.yaml says."""
    node = ObservedNode(NAME, NAMESPACE)
    node.publishers = [
        _ep('/rosout', 'rcl_interfaces/msg/Log',
            {'history': 'KEEP_LAST', 'depth': 1000, 'reliability': 'RELIABLE',
             'durability': 'TRANSIENT_LOCAL', 'lifespan_ns': 10_000_000_000,
             'liveliness': 'AUTOMATIC'}),
        _ep('/parameter_events', 'rcl_interfaces/msg/ParameterEvent',
            {'history': 'KEEP_LAST', 'depth': 1000, 'reliability': 'RELIABLE',
             'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}),
        _ep('/diagnostics', 'diagnostic_msgs/msg/DiagnosticArray',
            {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE',
             'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}),
        _ep('/base/drive/odom', 'nav_msgs/msg/Odometry',
            {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE',
             'durability': 'VOLATILE', 'deadline_ns': 100_000_000, 'liveliness': 'AUTOMATIC'}),
        _ep('/base/status', 'std_msgs/msg/String',
            {'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'RELIABLE',
             'durability': 'TRANSIENT_LOCAL', 'liveliness': 'AUTOMATIC'}),
        _ep('/drive/heartbeat', 'std_msgs/msg/Empty',
            {'history': 'KEEP_LAST', 'depth': 7, 'reliability': 'BEST_EFFORT',
             'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}),
    ]
    node.subscriptions = [
        _ep('/base/cmd_vel', 'geometry_msgs/msg/Twist',
            {'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'BEST_EFFORT',
             'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC',
             'liveliness_lease_duration_ns': 2_000_000_000}),
    ]
    node.service_servers = (
        [_ep(f'/base/drive/{s}', f'rcl_interfaces/srv/{"".join(w.title() for w in s.split("_"))}')
         for s in _PARAM_SERVICES]
        + [_ep('/base/drive/get_type_description',
               'type_description_interfaces/srv/GetTypeDescription'),
           _ep('/base/drive/reset_odometry', 'std_srvs/srv/Trigger'),
           _ep('/base/drive/enable', 'std_srvs/srv/SetBool')])
    node.service_clients = [_ep('/power/switch', 'std_srvs/srv/SetBool')]
    node.action_servers = [_ep('/base/drive/dock', 'example_interfaces/action/Fibonacci')]
    node.action_clients = [_ep('/planner/plan', 'example_interfaces/action/Fibonacci')]
    node.parameters = {p.name: p for p in [
        ObservedParameter('use_sim_time', 'bool', False),
        ObservedParameter('start_type_description_service', 'bool', True, read_only=True),
        ObservedParameter('health.period', 'double', 1.0),
        ObservedParameter('wheel_radius', 'double', 0.1, range=(0.01, 1.0)),
        ObservedParameter('max_speed', 'int', 5, range=(0, 10)),
        ObservedParameter('port', 'string', '/dev/ttyACM0', read_only=True),
        ObservedParameter('wheel_names', 'string_array', ['left', 'right']),
    ]}
    return node


def _endpoint(observed: ObservedNode, section: str, name: str) -> ObservedEndpoint:
    return next(e for e in getattr(observed, section) if e.name == name)


def _drift(differences: list[LiveDiagnostic]) -> list[LiveDiagnostic]:
    return [d for d in differences if d.kind in DRIFT_KINDS]


def _only(differences: list[LiveDiagnostic], kind: str) -> LiveDiagnostic:
    found = [d for d in differences if d.kind == kind]
    assert len(found) == 1, differences
    return found[0]


# -- the conforming observation --------------------------------------------------------------


def test_synthetic_observation_matches_the_fixture_definition(composed) -> None:
    assert [layer.label for layer in composed.layers] == \
        ['base:node', 'drive_health.nodl.yaml', 'mixins[1]', 'main']
    differences = compare(composed, conforming())
    assert _drift(differences) == []
    assert conforms(differences)
    assert {d.kind for d in differences} == {'unverifiable'}
    assert all(d.severity == 'info' for d in differences)


def test_every_difference_is_a_diagnostic_placed_in_the_definitions_files(composed) -> None:
    from nodl.diagnostics import Diagnostic

    observed = conforming()
    observed.publishers.append(_ep('/base/debug', 'std_msgs/msg/String', {}))
    differences = compare(composed, observed)
    assert differences and all(isinstance(d, Diagnostic) for d in differences)
    files = {str(LIVE / 'drive_node.nodl.yaml'), str(LIVE / 'drive_health.nodl.yaml')}
    for d in differences:
        assert d.code and d.line > 0 and d.column > 0, d
        assert d.file in files or d.file.endswith('.nodl.yaml'), d  # the base's file, in the package
    extra = _only(differences, 'extra')
    assert extra.location is None and extra.file == str(LIVE / 'drive_node.nodl.yaml')  # main's section


# -- missing and extra -----------------------------------------------------------------------


@pytest.mark.parametrize('section, name, layer, type_', [
    ('publishers', '/base/drive/odom', 'main', 'nav_msgs/msg/Odometry'),
    ('publishers', '/drive/heartbeat', 'main', 'std_msgs/msg/Empty'),  # /{node}/heartbeat
    ('publishers', '/diagnostics', 'drive_health.nodl.yaml', 'diagnostic_msgs/msg/DiagnosticArray'),
    ('publishers', '/rosout', 'base:node', 'rcl_interfaces/msg/Log'),
    ('subscriptions', '/base/cmd_vel', 'main', 'geometry_msgs/msg/Twist'),
    ('service_servers', '/base/drive/reset_odometry', 'mixins[1]', 'std_srvs/srv/Trigger'),
    ('service_servers', '/base/drive/list_parameters', 'base:node',
     'rcl_interfaces/srv/ListParameters'),
    ('service_clients', '/power/switch', 'main', 'std_srvs/srv/SetBool'),
    ('action_servers', '/base/drive/dock', 'main', 'example_interfaces/action/Fibonacci'),
    ('action_clients', '/planner/plan', 'main', 'example_interfaces/action/Fibonacci'),
])
def test_missing_endpoint_names_its_layer(composed, section: str, name: str, layer: str,
                                          type_: str) -> None:
    observed = conforming()
    setattr(observed, section, [e for e in getattr(observed, section) if e.name != name])
    differences = compare(composed, observed)
    drift = _drift(differences)
    assert len(drift) == 1, drift
    d = drift[0]
    assert (d.kind, d.section, d.name, d.layer, d.declared) == ('missing', section, name, layer, type_)
    assert d.severity == 'error'
    assert name in d.message and type_ in d.message
    assert not conforms(differences)


@pytest.mark.parametrize('section', ['publishers', 'subscriptions', 'service_servers',
                                     'service_clients', 'action_servers', 'action_clients'])
def test_undeclared_endpoint_is_extra(composed, section: str) -> None:
    observed = conforming()
    getattr(observed, section).append(_ep('/base/debug', 'std_msgs/msg/String', {}))
    d = _only(compare(composed, observed), 'extra')
    assert (d.section, d.name, d.observed, d.layer) == (section, '/base/debug', 'std_msgs/msg/String',
                                                        None)
    assert d.severity == 'error'


def test_same_name_in_another_section_is_missing_plus_extra(composed) -> None:
    observed = conforming()
    odom = _endpoint(observed, 'publishers', '/base/drive/odom')
    observed.publishers.remove(odom)
    observed.subscriptions.append(odom)
    drift = _drift(compare(composed, observed))
    assert sorted((d.kind, d.section) for d in drift) == \
        [('extra', 'subscriptions'), ('missing', 'publishers')]


# -- types -----------------------------------------------------------------------------------


@pytest.mark.parametrize('section, name, layer', [
    ('subscriptions', '/base/cmd_vel', 'main'),
    ('publishers', '/diagnostics', 'drive_health.nodl.yaml'),
    ('service_servers', '/base/drive/reset_odometry', 'mixins[1]'),
    ('action_clients', '/planner/plan', 'main'),
])
def test_type_difference(composed, section: str, name: str, layer: str) -> None:
    observed = conforming()
    endpoint = _endpoint(observed, section, name)
    declared = endpoint.type
    endpoint.type = 'std_msgs/msg/Int32'
    differences = compare(composed, observed)
    d = _only(differences, 'type')
    assert (d.section, d.name, d.declared, d.observed, d.layer) == \
        (section, name, declared, 'std_msgs/msg/Int32', layer)
    # with the wrong type, the QoS of that endpoint is not compared
    assert not [x for x in differences if x.name == name and x.kind == 'qos']
    assert len(_drift(differences)) == 1


# -- QoS, per policy -------------------------------------------------------------------------


@pytest.mark.parametrize('name, policy, observed_value, declared', [
    ('/base/drive/odom', 'reliability', 'BEST_EFFORT', 'RELIABLE'),
    ('/base/drive/odom', 'durability', 'TRANSIENT_LOCAL', 'VOLATILE'),
    ('/base/drive/odom', 'depth', 5, 10),
    ('/base/drive/odom', 'deadline_ns', 200_000_000, 100_000_000),
    ('/base/drive/odom', 'deadline_ns', None, 100_000_000),  # not reported: infinite (0)
    ('/base/status', 'durability', 'VOLATILE', 'TRANSIENT_LOCAL'),
    ('/base/cmd_vel', 'liveliness', 'MANUAL_BY_TOPIC', 'AUTOMATIC'),
    ('/base/cmd_vel', 'liveliness_lease_duration_ns', 1_000_000_000, 2_000_000_000),
    ('/diagnostics', 'reliability', 'BEST_EFFORT', 'RELIABLE'),
])
def test_one_qos_difference_per_policy(composed, name: str, policy: str, observed_value: Any,
                                       declared: Any) -> None:
    observed = conforming()
    section = 'subscriptions' if name == '/base/cmd_vel' else 'publishers'
    endpoint = _endpoint(observed, section, name)
    assert endpoint.qos is not None
    if observed_value is None:
        del endpoint.qos[policy]
    else:
        endpoint.qos[policy] = observed_value
    differences = compare(composed, observed)
    d = _only(differences, 'qos')
    expected_observed = 0 if observed_value is None else observed_value
    assert (d.section, d.name, d.declared, d.observed) == (section, name, declared, expected_observed)
    assert policy in d.message
    assert f'declared {declared}, observed {expected_observed}' in d.message
    assert d.layer == ('drive_health.nodl.yaml' if name == '/diagnostics' else 'main')
    assert not conforms(differences)


def test_policies_the_definition_leaves_open_are_not_compared(composed) -> None:
    observed = conforming()
    # ~/odom states no lifespan and no liveliness; /diagnostics no durability
    _endpoint(observed, 'publishers', '/base/drive/odom').qos.update(
        lifespan_ns=5, liveliness='MANUAL_BY_TOPIC')
    _endpoint(observed, 'publishers', '/diagnostics').qos['durability'] = 'TRANSIENT_LOCAL'
    assert conforms(compare(composed, observed))


def test_keep_all_observed_for_keep_last_is_a_history_difference(composed) -> None:
    observed = conforming()
    qos = _endpoint(observed, 'publishers', '/base/drive/odom').qos
    qos['history'] = 'KEEP_ALL'
    del qos['depth']
    drift = _drift(compare(composed, observed))
    assert sorted(d.message.split(' ')[2] for d in drift) == ['depth:', 'history:']
    assert {d.kind for d in drift} == {'qos'}


# -- unverifiable ----------------------------------------------------------------------------


def test_unobserved_history_and_depth_are_unverifiable_not_drift(composed) -> None:
    observed = conforming()
    for endpoint in observed.publishers + observed.subscriptions:
        assert endpoint.qos is not None
        endpoint.qos.pop('history')
        endpoint.qos.pop('depth')
        endpoint.unobserved = ['history', 'depth']
    differences = compare(composed, observed)
    assert conforms(differences)
    odom = [d for d in differences if d.name == '/base/drive/odom']
    assert sorted(d.message.split(' ')[2] for d in odom) == ['depth:', 'history:']
    assert all(d.kind == 'unverifiable' and d.severity == 'info' and d.layer == 'main' for d in odom)
    assert all('does not report' in d.message for d in odom)
    rosout = [d for d in differences if d.name == '/rosout']
    assert {d.layer for d in rosout} == {'base:node'}


def test_other_unobserved_policies_are_unverifiable(composed) -> None:
    observed = conforming()
    endpoint = _endpoint(observed, 'publishers', '/base/drive/odom')
    del endpoint.qos['reliability']
    endpoint.unobserved = ['reliability']
    differences = compare(composed, observed)
    assert conforms(differences)
    d = [x for x in differences if x.name == '/base/drive/odom']
    assert len(d) == 1 and d[0].kind == 'unverifiable' and 'reliability' in d[0].message


def test_unreadable_topic_qos_is_one_unverifiable_difference(composed) -> None:
    observed = conforming()
    endpoint = _endpoint(observed, 'subscriptions', '/base/cmd_vel')
    endpoint.qos = None
    endpoint.unobserved = ['qos']
    differences = compare(composed, observed)
    assert conforms(differences)
    d = [x for x in differences if x.name == '/base/cmd_vel']
    assert len(d) == 1
    assert d[0].kind == 'unverifiable' and 'could not be read' in d[0].message
    assert d[0].declared == {'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'BEST_EFFORT',
                             'liveliness': 'AUTOMATIC', 'liveliness_lease_duration_ns': 2_000_000_000}


def test_service_qos_is_unverifiable(composed) -> None:
    differences = compare(composed, conforming())
    enable = [d for d in differences if d.name == '/base/drive/enable']
    assert len(enable) == 1
    assert (enable[0].kind, enable[0].section, enable[0].layer) == \
        ('unverifiable', 'service_servers', 'main')
    assert 'service QoS' in enable[0].message
    assert enable[0].declared == {'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'RELIABLE'}
    # declared without QoS: nothing to verify, nothing listed
    assert not [d for d in differences if d.name in ('/base/drive/reset_odometry', '/power/switch')]
    # the base's services declare QoS too
    base = [d for d in differences if d.name == '/base/drive/get_parameters']
    assert [(d.kind, d.layer) for d in base] == [('unverifiable', 'base:node')]


def test_system_default_and_best_available_are_unverifiable(composed) -> None:
    differences = compare(composed, conforming())
    heartbeat = {d.message.split(' ')[2]: d for d in differences if d.name == '/drive/heartbeat'}
    # history SYSTEM_DEFAULT, reliability SYSTEM_DEFAULT, durability BEST_AVAILABLE: whatever the
    # middleware resolved (depth 7, BEST_EFFORT, VOLATILE) cannot contradict them.
    assert set(heartbeat) == {'history:', 'reliability:', 'durability:'}
    assert all(d.kind == 'unverifiable' for d in heartbeat.values())
    assert 'resolved by the middleware' in heartbeat['durability:'].message


# -- parameters ------------------------------------------------------------------------------


def test_parameter_type(composed) -> None:
    observed = conforming()
    observed.parameters['max_speed'] = ObservedParameter('max_speed', 'double', 5.0)
    d = _only(compare(composed, observed), 'parameter_type')
    assert (d.section, d.name, d.declared, d.observed, d.layer) == \
        ('parameters', 'max_speed', 'int', 'double', 'main')
    assert d.severity == 'error'


def test_fixed_size_array_matches_its_base_type(composed) -> None:
    observed = conforming()
    assert observed.parameters['wheel_names'].type == 'string_array'
    assert not [d for d in compare(composed, observed) if d.name == 'wheel_names']
    observed.parameters['wheel_names'] = ObservedParameter('wheel_names', 'string', 'left')
    d = _only(compare(composed, observed), 'parameter_type')
    assert d.declared == 'string_array_fixed_2'


@pytest.mark.parametrize('name, observed_read_only, layer', [
    ('port', False, 'main'),
    ('wheel_radius', True, 'main'),
    ('start_type_description_service', False, 'base:node'),
    ('health.period', True, 'drive_health.nodl.yaml'),
])
def test_read_only(composed, name: str, observed_read_only: bool, layer: str) -> None:
    observed = conforming()
    observed.parameters[name].read_only = observed_read_only
    d = _only(compare(composed, observed), 'read_only')
    assert (d.name, d.declared, d.observed, d.layer) == (name, not observed_read_only,
                                                        observed_read_only, layer)


@pytest.mark.parametrize('name, value, layer, validator', [
    ('wheel_radius', 2.0, 'main', 'bounds<>'),
    ('max_speed', 11, 'main', 'bounds<>'),
    ('health.period', -1.0, 'drive_health.nodl.yaml', 'gt<>'),
])
def test_value_breaking_a_validator_is_a_warning_not_drift(composed, name: str, value: Any,
                                                           layer: str, validator: str) -> None:
    observed = conforming()
    observed.parameters[name].value = value
    differences = compare(composed, observed)
    d = _only(differences, 'value')
    assert d.severity == 'warning'
    assert 'value' not in DRIFT_KINDS
    assert (d.section, d.name, d.observed, d.layer) == ('parameters', name, value, layer)
    assert validator in d.message and 'current value' in d.message
    assert 'default_value' not in d.message
    assert conforms(differences)
    assert d.brief().startswith('warning: value: ')


def test_values_within_the_validators_give_no_warning(composed) -> None:
    observed = conforming()
    observed.parameters['wheel_radius'].value = 1.0
    observed.parameters['max_speed'].value = 0
    assert not [d for d in compare(composed, observed) if d.kind == 'value']


def test_missing_and_extra_parameters(composed) -> None:
    observed = conforming()
    del observed.parameters['port']
    observed.parameters['debug'] = ObservedParameter('debug', 'bool', False)
    observed.parameters['qos_overrides./base/status.publisher.depth'] = \
        ObservedParameter('qos_overrides./base/status.publisher.depth', 'int', 1, read_only=True)
    drift = sorted(_drift(compare(composed, observed)), key=lambda d: d.kind)
    assert [(d.kind, d.section, d.name, d.layer) for d in drift] == \
        [('extra', 'parameters', 'debug', None), ('missing', 'parameters', 'port', 'main')]
    assert drift[0].observed == 'bool' and drift[1].declared == 'string'


def test_unread_parameters_are_one_unverifiable_difference(composed) -> None:
    observed = conforming()
    observed.parameters = None
    differences = compare(composed, observed)
    params = [d for d in differences if d.section == 'parameters']
    assert [(d.kind, d.name) for d in params] == [('unverifiable', '*')]
    assert conforms(differences)


# -- remaps ----------------------------------------------------------------------------------


def test_parse_remaps_relative_private_and_absolute() -> None:
    rules = parse_remaps(['cmd_vel:=cmd_in', '~/odom:=odometry', '/power/switch:=~/power',
                          'status:=/global/status'], NAME, NAMESPACE)
    assert rules == {'/base/cmd_vel': '/base/cmd_in',
                     '/base/drive/odom': '/base/odometry',
                     '/power/switch': '/base/drive/power',
                     '/base/status': '/global/status'}


def test_parse_remaps_first_rule_wins_and_node_specific_rules() -> None:
    rules = parse_remaps(['cmd_vel:=first', 'cmd_vel:=second', 'drive:status:=mine',
                          'other:~/odom:=theirs', 'drive:~/odom:=odometry'], NAME, NAMESPACE)
    assert rules == {'/base/cmd_vel': '/base/first', '/base/status': '/base/mine',
                     '/base/drive/odom': '/base/odometry'}


@pytest.mark.parametrize('rule', ['cmd_vel', 'cmd_vel:=', ':=x', 'cmd_vel=x', 'drive::=x'])
def test_parse_remaps_rejects_malformed_rules(rule: str) -> None:
    with pytest.raises(ValueError, match='invalid remapping'):
        parse_remaps([rule], NAME, NAMESPACE)


_RULE_SETS = [
    ['cmd_vel:=cmd_in'],
    ['~/odom:=odometry', '/power/switch:=~/power'],
    ['cmd_vel:=first', 'cmd_vel:=second'],
    ['drive:status:=mine', 'other:cmd_vel:=theirs'],
    ['/base/cmd_vel:=/cmd', 'status:=/global/status'],
]


@pytest.mark.parametrize('rules', _RULE_SETS)
def test_parse_remaps_agrees_with_rcl(rules: list[str]) -> None:
    """rcl (a real rclpy node started with the same --ros-args) is the reference."""
    import rclpy

    from nodl.naming import expand

    args = ['--ros-args', '--disable-rosout-logs']
    for rule in rules:
        args += ['-r', rule]
    context = rclpy.Context()
    rclpy.init(context=context, args=args)
    try:
        node = rclpy.create_node(NAME, namespace=NAMESPACE, context=context,
                                 start_parameter_services=False, enable_rosout=False)
        try:
            names = ['cmd_vel', '~/odom', 'status', '/power/switch', '/base/cmd_vel', 'other']
            by_rcl = {n: node.resolve_topic_name(n) for n in names}
        finally:
            node.destroy_node()
    finally:
        rclpy.shutdown(context=context)
    mapped = parse_remaps(rules, NAME, NAMESPACE)
    for name, resolved in by_rcl.items():
        full = expand(name, NAME, NAMESPACE)
        assert mapped.get(full, full) == resolved, name


def test_remapped_node_conforms_only_with_its_remaps(composed) -> None:
    observed = conforming()
    _endpoint(observed, 'subscriptions', '/base/cmd_vel').name = '/base/cmd_in'
    _endpoint(observed, 'publishers', '/base/drive/odom').name = '/base/odometry'
    _endpoint(observed, 'action_clients', '/planner/plan').name = '/base/drive/plan'
    drift = _drift(compare(composed, observed))
    assert sorted((d.kind, d.name) for d in drift) == [
        ('extra', '/base/cmd_in'), ('extra', '/base/drive/plan'), ('extra', '/base/odometry'),
        ('missing', '/base/cmd_vel'), ('missing', '/base/drive/odom'), ('missing', '/planner/plan')]
    rules = parse_remaps(['cmd_vel:=cmd_in', '~/odom:=odometry', '/planner/plan:=~/plan'],
                         NAME, NAMESPACE)
    differences = compare(composed, observed, rules)
    assert conforms(differences)
    # the QoS is still compared, under the remapped name
    _endpoint(observed, 'publishers', '/base/odometry').qos['reliability'] = 'BEST_EFFORT'
    d = _only(compare(composed, observed, rules), 'qos')
    assert d.name == '/base/odometry' and d.layer == 'main'


# -- LiveDiagnostic and conforms -----------------------------------------------------------------


def test_a_difference_is_a_coded_diagnostic_with_its_values() -> None:
    import pickle

    from nodl.diagnostics import Diagnostic, Severity
    from nodl.live import conformance
    from nodl.location import Location

    d = LiveDiagnostic('qos', 'publishers', '/base/status', "publisher '/base/status' durability: "
                       'declared TRANSIENT_LOCAL, observed VOLATILE', declared='TRANSIENT_LOCAL',
                       observed='VOLATILE', layer='main', location=Location('robot.nodl.yaml', 7, 5))
    assert isinstance(d, Diagnostic)
    assert not hasattr(conformance, 'Difference')  # the former name is gone (issue 16)
    assert (d.severity, d.code, d.path, d.file, d.line, d.column) == (
        Severity.ERROR, 'NODL404', ('publishers', '/base/status'), 'robot.nodl.yaml', 7, 5)
    assert d.brief() == ("error: qos: publisher '/base/status' durability: declared TRANSIENT_LOCAL, "
                         'observed VOLATILE (declared in main) [NODL404]')
    assert str(d) == ("robot.nodl.yaml:7:5: error: publisher '/base/status' durability: declared "
                      'TRANSIENT_LOCAL, observed VOLATILE [publishers["/base/status"]] [NODL404]')
    assert d.to_dict() == {'kind': 'qos', 'code': 'NODL404', 'severity': 'error', 'section': 'publishers',
                           'name': '/base/status', 'declared': 'TRANSIENT_LOCAL',
                           'observed': 'VOLATILE', 'layer': 'main', 'message': d.message,
                           'file': 'robot.nodl.yaml', 'line': 7, 'column': 5, 'related': []}
    extra = LiveDiagnostic('extra', 'publishers', '/x', "publisher '/x' is observed but not declared")
    assert extra.brief() == "error: extra: publisher '/x' is observed but not declared [NODL402]"
    assert (extra.location, extra.file, extra.line) == (None, '<definition>', 0)  # not placed yet
    # immutable values: replace keeps what it is; pickled (a child process) and hashed whole
    unverifiable = LiveDiagnostic('unverifiable', 's', 'n', 'm', declared={'depth': 1})
    promoted = unverifiable.replace(severity='error')
    assert isinstance(promoted, LiveDiagnostic) and promoted.promoted and not unverifiable.promoted
    assert (promoted.kind, promoted.declared, promoted.code) == ('unverifiable', {'depth': 1}, 'NODL408')
    assert pickle.loads(pickle.dumps(promoted)) == promoted
    assert hash(promoted) == hash(promoted.replace())
    with pytest.raises(AttributeError):
        d.kind = 'missing'  # type: ignore[misc]


@pytest.mark.parametrize('kinds, expected', [
    ([], True),
    (['unverifiable', 'value'], True),
    (['unverifiable', 'missing'], False),
    *[([kind], False) for kind in DRIFT_KINDS],
])
def test_conforms(kinds: list[str], expected: bool) -> None:
    assert conforms(LiveDiagnostic(k, 'publishers', '/x', 'm') for k in kinds) is expected


def test_severities() -> None:
    assert {k: LiveDiagnostic(k, 's', 'n', 'm').severity for k in (*DRIFT_KINDS, 'value', 'unverifiable')} \
        == {**{k: 'error' for k in DRIFT_KINDS}, 'value': 'warning', 'unverifiable': 'info'}


def test_compare_does_not_modify_its_inputs(composed) -> None:
    observed = conforming()
    before = copy.deepcopy(observed)
    compare(composed, observed, parse_remaps(['cmd_vel:=x'], NAME, NAMESPACE))
    assert observed == before


# -- JUnit report: each difference on the declaration it is about ----------------------------


def _junit(result: Any) -> str:
    """The check's JUnit report, as ``nodl check --format junit`` writes it."""
    from nodl.live.report import check_report
    from nodl.reporting.reporters import JUnitReporter

    return JUnitReporter().report(check_report(result))


def _json(result: Any) -> str:
    """The check's JSON report, as ``nodl check --format json`` writes it."""
    from nodl.live.report import check_report
    from nodl.reporting.reporters import JsonReporter

    return JsonReporter().report(check_report(result))



def test_junit_attributes_differences_to_declared_entities(composed) -> None:
    import xml.etree.ElementTree as ET

    from nodl.live.check import CheckResult

    observed = conforming()
    # '/{node}/heartbeat' goes missing; cmd_vel is remapped to cmd_in and has the wrong type
    observed.publishers = [e for e in observed.publishers if e.name != '/drive/heartbeat']
    cmd = _endpoint(observed, 'subscriptions', '/base/cmd_vel')
    cmd.name, cmd.type = '/base/cmd_in', 'std_msgs/msg/String'
    observed.parameters['port'].read_only = False
    rules = parse_remaps(['cmd_vel:=cmd_in'], NAME, NAMESPACE)
    result = CheckResult('/base/drive', str(LIVE / 'drive_node.nodl.yaml'),
                         compare(composed, observed, rules), composed, observed, rules)
    suite = ET.fromstring(_junit(result))
    cases = {(c.get('classname'), c.get('name')): c for c in suite.iter('testcase')}
    failures = {k: [f.get('type') for f in c.iter('failure')] for k, c in cases.items()}
    assert failures[('publishers', '/{node}/heartbeat')] == ['missing']
    assert failures[('subscriptions', 'cmd_vel')] == ['type']
    assert failures[('parameters', 'port')] == ['read_only']
    assert ('publishers', '/drive/heartbeat') not in cases
    assert ('subscriptions', '/base/cmd_in') not in cases
    assert suite.get('failures') == '3'
    # one test case per declared entity, nothing else (no extras here)
    declared = sum(len(composed.interface.endpoints(s)) for s in
                   ('publishers', 'subscriptions', 'service_servers', 'service_clients',
                    'action_servers', 'action_clients')) + len(composed.interface.parameters)
    assert suite.get('tests') == str(declared) == str(len(cases))
    # unverifiable fields are reported as output of their test case, not as failures
    enable = cases[('service_servers', '~/enable')]
    assert [e.tag for e in enable] == ['system-out']
    # as the JUnit schema wants: failures first, at most one system-out per test case
    for case in cases.values():
        tags = [e.tag for e in case]
        assert tags == sorted(tags, key=lambda t: t != 'failure') and tags.count('system-out') <= 1


def test_junit_failure_comes_before_the_notes_of_the_same_entity(composed) -> None:
    import xml.etree.ElementTree as ET

    from nodl.live.check import CheckResult

    observed = conforming()
    odom = _endpoint(observed, 'publishers', '/base/drive/odom')
    del odom.qos['history']
    odom.unobserved = ['history']  # unverifiable (info) ...
    odom.qos['reliability'] = 'BEST_EFFORT'  # ... and drift, on one entity
    result = CheckResult('/base/drive', 'drive_node.nodl.yaml', compare(composed, observed),
                         composed, observed)
    suite = ET.fromstring(_junit(result))
    case = next(c for c in suite.iter('testcase') if c.get('name') == '~/odom')
    assert [e.tag for e in case] == ['failure', 'system-out']
    assert 'history' in case.find('system-out').text


def test_reports_of_a_synthetic_check_match_golden(composed, golden) -> None:
    from nodl.live.check import CheckResult
    from nodl.live.report import format_check_text

    observed = conforming()
    observed.publishers = [e for e in observed.publishers if e.name != '/base/status']
    observed.publishers.append(_ep('/base/debug', 'std_msgs/msg/String', {}))
    _endpoint(observed, 'publishers', '/base/drive/odom').qos['durability'] = 'TRANSIENT_LOCAL'
    _endpoint(observed, 'action_servers', '/base/drive/dock').type = 'example_interfaces/action/Other'
    for endpoint in observed.subscriptions:
        endpoint.qos.pop('history')
        endpoint.qos.pop('depth')
        endpoint.unobserved = ['history', 'depth']
    observed.parameters['max_speed'].value = 12
    observed.parameters['port'].read_only = False
    result = CheckResult('/base/drive', 'tests/fixtures/live/drive_node.nodl.yaml',
                         compare(composed, observed), composed, observed)
    expected = LIVE / 'expected'
    golden.check(format_check_text(result), expected / 'drive_check.txt')
    golden.check(format_check_text(result, verbose=True), expected / 'drive_check_verbose.txt')
    # differences point at their declarations: the base's file in the package, mixins by path
    import os

    import nodl

    package = os.path.dirname(nodl.__file__) + os.sep
    here = str(LIVE) + os.sep
    golden.check(_json(result).replace(package, '<nodl>/').replace(
        here, '<live>/'), expected / 'drive_check.json')
    golden.check(_junit(result), expected / 'drive_check.junit.xml')


# -- remaps through the naming module (rcl's rules) ------------------------------------------


def test_parse_remaps_node_rules_are_not_topic_remaps() -> None:
    """The issue's example: __ns and __node change the node's own name."""
    assert parse_remaps(['__ns:=/robot', '__node:=foo'], 'driver', '/ns') == {}
    # the other rules then apply to the renamed node, in its new namespace
    assert parse_remaps(['__ns:=/robot', '__node:=foo', 'foo:~/x:=y', 'driver:a:=b'],
                        'driver', '/ns') == {'/robot/foo/x': '/robot/y'}


def test_compare_with_node_names_keeps_topic_and_service_rules_apart(composed) -> None:
    from nodl.naming import NodeNames, parse_remap_rules

    observed = conforming()
    _endpoint(observed, 'service_servers', '/base/drive/reset_odometry').name = '/base/reset'
    _endpoint(observed, 'action_servers', '/base/drive/dock').name = '/base/docking'
    rules = tuple(parse_remap_rules(['rostopic://~/reset_odometry:=not_for_services',
                                     'rosservice://~/reset_odometry:=reset', '~/dock:=docking']))
    assert conforms(compare(composed, observed, NodeNames(NAME, NAMESPACE, rules)))
    # the same rules as a plain mapping cannot tell services from topics
    assert not conforms(compare(composed, observed, parse_remaps([str(r) for r in rules],
                                                                 NAME, NAMESPACE)))
