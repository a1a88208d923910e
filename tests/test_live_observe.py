"""observe_node against real node processes (tests/nodes/).

The nodes of this module are started once (module fixtures, always
stopped) and observed through one shared observer session, so discovery is
paid once; the tests of a node that is not there, or goes away, use a
session of their own as `nodl describe` and `nodl check` do.
"""

from __future__ import annotations

import time
from collections.abc import Iterator

import pytest

from conftest import NodeProcess
from nodl.live.observe import ACTION_INFIX, DISCOVERY_WINDOW, ObservedNode, list_nodes, observe_node, wait_for_node
from nodl.live.session import LiveError, NodeNotFound, ros_session

SECTIONS = ('publishers', 'subscriptions', 'service_servers', 'service_clients', 'action_servers',
            'action_clients')
#: What a default rclpy node exposes under its own name.
PARAMETER_SERVICES = {
    'describe_parameters': 'rcl_interfaces/srv/DescribeParameters',
    'get_parameter_types': 'rcl_interfaces/srv/GetParameterTypes',
    'get_parameters': 'rcl_interfaces/srv/GetParameters',
    'list_parameters': 'rcl_interfaces/srv/ListParameters',
    'set_parameters': 'rcl_interfaces/srv/SetParameters',
    'set_parameters_atomically': 'rcl_interfaces/srv/SetParametersAtomically',
    'get_type_description': 'type_description_interfaces/srv/GetTypeDescription',
}


@pytest.fixture(scope='module')
def full() -> Iterator[NodeProcess]:
    node = NodeProcess('full_node.py', 'full', '/obs')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def actions() -> Iterator[NodeProcess]:
    node = NodeProcess('action_nodes.py', 'fib', '/obs_act')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def session():
    with ros_session() as node:
        yield node


@pytest.fixture(scope='module')
def observed_full(full: NodeProcess, session) -> ObservedNode:
    return observe_node(full.fqn, timeout=15, session=session)


def _names(observed: ObservedNode, section: str) -> dict[str, str]:
    return {e.name: e.type for e in getattr(observed, section)}


def test_full_node_identity(observed_full: ObservedNode) -> None:
    assert (observed_full.name, observed_full.namespace) == ('full', '/obs')
    assert observed_full.fully_qualified_name == '/obs/full'
    assert observed_full.notes == []


def test_full_node_endpoints_and_types(observed_full: ObservedNode) -> None:
    assert _names(observed_full, 'publishers') == {
        '/obs/full/status': 'std_msgs/msg/String',
        '/obs/measurement': 'std_msgs/msg/Float64',
        '/global_chatter': 'std_msgs/msg/String',
        '/rosout': 'rcl_interfaces/msg/Log',
        '/parameter_events': 'rcl_interfaces/msg/ParameterEvent',
    }
    assert _names(observed_full, 'subscriptions') == {
        '/emergency_stop': 'std_msgs/msg/Bool',
        '/obs/commands': 'std_msgs/msg/String',
    }
    assert _names(observed_full, 'service_servers') == {
        '/obs/full/reset': 'std_srvs/srv/Trigger',
        **{f'/obs/full/{s}': t for s, t in PARAMETER_SERVICES.items()},
    }
    assert _names(observed_full, 'service_clients') == {'/motor/enable': 'std_srvs/srv/SetBool'}
    assert observed_full.action_servers == [] and observed_full.action_clients == []


def _qos(observed: ObservedNode, section: str, name: str) -> dict:
    endpoint = next(e for e in getattr(observed, section) if e.name == name)
    assert endpoint.qos is not None, f'no QoS read for {name}'
    assert 'qos' not in endpoint.unobserved
    history = endpoint.qos.get('history')
    if history is None:  # Fast DDS reports neither history nor depth
        assert set(endpoint.unobserved) >= {'history', 'depth'}
        assert 'depth' not in endpoint.qos
    return endpoint.qos


def test_full_node_topic_qos_as_set_in_the_node(observed_full: ObservedNode) -> None:
    status = _qos(observed_full, 'publishers', '/obs/full/status')
    assert (status['reliability'], status['durability']) == ('RELIABLE', 'TRANSIENT_LOCAL')
    assert status.get('depth', 1) == 1

    measurement = _qos(observed_full, 'publishers', '/obs/measurement')
    assert (measurement['reliability'], measurement['durability']) == ('BEST_EFFORT', 'VOLATILE')
    assert measurement.get('depth', 5) == 5

    chatter = _qos(observed_full, 'publishers', '/global_chatter')
    assert chatter['reliability'] == 'RELIABLE'
    assert chatter['deadline_ns'] == 1_000_000_000
    assert chatter['lifespan_ns'] == 2_000_000_000
    assert chatter['liveliness'] == 'AUTOMATIC'
    assert chatter['liveliness_lease_duration_ns'] == 3_000_000_000

    # infinite durations are left out, not reported as huge numbers
    for qos in (status, measurement):
        assert not {'deadline_ns', 'lifespan_ns', 'liveliness_lease_duration_ns'} & set(qos)

    commands = _qos(observed_full, 'subscriptions', '/obs/commands')
    assert (commands['reliability'], commands['durability']) == ('BEST_EFFORT', 'VOLATILE')
    stop = _qos(observed_full, 'subscriptions', '/emergency_stop')
    assert stop['reliability'] == 'RELIABLE'


def test_services_and_actions_carry_no_qos(observed_full: ObservedNode) -> None:
    for section in ('service_servers', 'service_clients'):
        for endpoint in getattr(observed_full, section):
            assert endpoint.qos is None and endpoint.unobserved == []


def test_full_node_parameters_with_ranges(observed_full: ObservedNode) -> None:
    params = observed_full.parameters
    assert params is not None
    assert set(params) == {'rate', 'gain', 'frame_id', 'joints', 'verbose', 'use_sim_time',
                           'start_type_description_service'}
    rate = params['rate']
    assert (rate.type, rate.value, rate.range, rate.read_only) == ('int', 10, (1, 100), False)
    assert rate.description == 'Publishing rate in Hz.'
    assert isinstance(rate.range[0], int)
    gain = params['gain']
    assert (gain.type, gain.value, gain.range) == ('double', 0.5, (0.0, 1.0))
    assert isinstance(gain.range[0], float)
    frame = params['frame_id']
    assert (frame.type, frame.value, frame.read_only, frame.range) == \
        ('string', 'base_link', True, None)
    assert (params['joints'].type, params['joints'].value) == ('string_array', ['left', 'right'])
    assert (params['verbose'].type, params['verbose'].value, params['verbose'].description) == \
        ('bool', False, '')
    assert (params['use_sim_time'].type, params['use_sim_time'].value) == ('bool', False)
    assert params['start_type_description_service'].read_only is True


def test_without_parameters(full: NodeProcess, session) -> None:
    observed = observe_node(full.fqn, timeout=15, parameters=False, session=session)
    assert observed.parameters is None
    assert observed.notes == []
    assert '/obs/full/status' in _names(observed, 'publishers')


def test_action_server_and_client_are_folded(actions: NodeProcess, session) -> None:
    server = observe_node('/obs_act/fib', timeout=15, parameters=False, session=session)
    client = observe_node('/obs_act/fib_client', timeout=15, parameters=False, session=session)
    assert [(e.name, e.type) for e in server.action_servers] == \
        [('/obs_act/fib/fibonacci', 'test_msgs/action/Fibonacci')]
    assert server.action_clients == []
    assert [(e.name, e.type) for e in client.action_clients] == \
        [('/obs_act/fib/fibonacci', 'test_msgs/action/Fibonacci')]
    assert client.action_servers == []
    for observed in (server, client):
        for section in ('publishers', 'subscriptions', 'service_servers', 'service_clients'):
            hidden = [e.name for e in getattr(observed, section) if ACTION_INFIX in e.name]
            assert hidden == [], f'{observed.fully_qualified_name} {section}: {hidden}'
    # what is left is the plain node's own
    assert set(_names(server, 'publishers')) == {'/rosout', '/parameter_events'}
    assert set(_names(client, 'service_clients')) == set()


def test_the_graph_really_has_the_hidden_action_endpoints(actions: NodeProcess, session) -> None:
    """The folding above is not vacuous: rclpy lists /_action/ services for the server."""
    observe_node('/obs_act/fib', timeout=15, parameters=False, session=session)  # discovered
    raw = session.get_service_names_and_types_by_node('fib', '/obs_act')
    assert '/obs_act/fib/fibonacci/_action/send_goal' in {n for n, _ in raw}


def test_list_nodes(full: NodeProcess, actions: NodeProcess, session) -> None:
    observe_node(actions.fqn + '_client', timeout=15, parameters=False, session=session)
    observe_node(full.fqn, timeout=15, parameters=False, session=session)
    names = list_nodes(session)
    assert {'/obs/full', '/obs_act/fib', '/obs_act/fib_client'} <= set(names)
    assert session.get_fully_qualified_name() not in names
    assert names == sorted(set(names))
    assert all(n.startswith('/') for n in names)


def test_node_that_never_appears_is_not_found_within_the_timeout() -> None:
    timeout = 1.0
    start = time.monotonic()
    with pytest.raises(NodeNotFound) as caught:
        observe_node('/obs/never_there', timeout=timeout)
    elapsed = time.monotonic() - start
    assert timeout <= elapsed < timeout + 3
    message = str(caught.value)
    assert "'/obs/never_there'" in message and 'not found within 1 s' in message
    assert 'ROS_DOMAIN_ID' in message
    assert isinstance(caught.value, LiveError)


def test_node_name_without_leading_slash_is_in_the_root_namespace() -> None:
    with pytest.raises(NodeNotFound, match="'/never_there'"):
        observe_node('never_there', timeout=0.5)


def test_namesakes_are_counted_after_the_discovery_window_of_a_fresh_session(ros_node) -> None:
    """Two nodes of one name: the second participant is often discovered seconds after the
    first (Fast DDS: at its next announcement), so a fresh session counts both only once
    discovery has had DISCOVERY_WINDOW seconds; the name is a warning, not a note."""
    first = ros_node('plain_node.py', 'twin', '/obs_twin')
    ros_node('plain_node.py', 'twin', '/obs_twin')
    for _ in range(2):  # either participant may be the late one: twice from a fresh session
        start = time.monotonic()
        observed = observe_node(first.fqn, timeout=10, parameters=False)
        assert time.monotonic() - start < 10 + 3
        assert observed.instances == 2
        assert observed.warnings == ['2 nodes in the graph are named /obs_twin/twin: what was '
                                     'observed is all of them together (give each node a '
                                     'unique name)']
        assert not any('/obs_twin/twin' in note for note in observed.notes)


def test_the_discovery_window_counts_from_the_session_start_within_the_timeout(ros_node) -> None:
    node = ros_node('plain_node.py', 'alone', '/obs_twin')
    with ros_session() as session:
        wait_for_node(session, node.fqn, 10)
        # a session that has only just started discovering waits out the window ...
        session.nodl_started = time.monotonic()
        start = time.monotonic()
        observed = observe_node(node.fqn, timeout=10, parameters=False, session=session)
        assert DISCOVERY_WINDOW <= time.monotonic() - start < 10 + 3
        assert observed.instances == 1 and observed.warnings == []
        # ... but never beyond the timeout
        session.nodl_started = time.monotonic()
        start = time.monotonic()
        observe_node(node.fqn, timeout=1.0, parameters=False, session=session)
        assert time.monotonic() - start < DISCOVERY_WINDOW
        # and a session that has discovered long enough does not wait again
        session.nodl_started = time.monotonic() - DISCOVERY_WINDOW
        start = time.monotonic()
        observe_node(node.fqn, timeout=10, parameters=False, session=session)
        assert time.monotonic() - start < DISCOVERY_WINDOW


def test_node_that_has_exited_is_a_live_error(ros_node) -> None:
    node = ros_node('dying_node.py', 'short_lived', '/obs', '--lifetime', '0.2')
    node.process.wait(timeout=10)
    start = time.monotonic()
    with pytest.raises(LiveError) as caught:
        observe_node(node.fqn, timeout=1)
    assert time.monotonic() - start < 1 + 3
    assert "'/obs/short_lived'" in str(caught.value)


def test_node_dying_while_observed_again_and_again_gives_a_live_error(ros_node) -> None:
    """Observe a dying node until it is gone: every call returns or fails within its timeout."""
    lifetime, timeout = 1.0, 2.0
    node = ros_node('dying_node.py', 'dying', '/obs', '--lifetime', str(lifetime))
    start = time.monotonic()
    error: LiveError | None = None
    observations = 0
    with ros_session() as session:
        while time.monotonic() - start < lifetime + 15:
            call = time.monotonic()
            try:
                observed = observe_node(node.fqn, timeout=timeout, session=session)
            except LiveError as exc:
                error = exc
                break
            finally:
                assert time.monotonic() - call < timeout + 3, 'an observation overran its timeout'
            observations += 1
            assert '/obs/dying/last_words' in _names(observed, 'publishers')
    assert error is not None, 'the node never went away'
    message = str(error)
    assert "'/obs/dying'" in message
    assert 'not found' in message or 'disappeared' in message
    assert node.process.wait(timeout=10) == 0


_FLAPPING_NODE = '''
import sys

import rclpy
from std_msgs.msg import String

argv = sys.argv[1:]
rclpy.init()
node = rclpy.create_node(argv[argv.index('--name') + 1],
                         namespace=argv[argv.index('--namespace') + 1])
print('ready', flush=True)
i = 0
try:
    while rclpy.ok():
        publisher = node.create_publisher(String, f'flap_{i % 50}', 1)
        rclpy.spin_once(node, timeout_sec=0.002)
        node.destroy_publisher(publisher)
        i += 1
except KeyboardInterrupt:
    pass
'''


def test_node_whose_endpoints_never_settle_is_observed_at_the_deadline(ros_node, tmp_path) -> None:
    """A node creating and destroying a publisher every few ms: no hang, taken as it is."""
    script = tmp_path / 'flapping_node.py'
    script.write_text(_FLAPPING_NODE, encoding='utf-8')
    node = ros_node(str(script), 'flapper', '/obs')
    timeout = 1.0
    with ros_session() as session:
        wait_for_node(session, node.fqn, 15)
        start = time.monotonic()
        observed = observe_node(node.fqn, timeout=timeout, parameters=False, session=session)
        elapsed = time.monotonic() - start
    assert elapsed < timeout + 3
    assert {'/rosout', '/parameter_events'} <= set(_names(observed, 'publishers'))


_SILENT_NODE = '''
import sys
import time

import rclpy
from std_msgs.msg import String

argv = sys.argv[1:]
rclpy.init()
node = rclpy.create_node(argv[argv.index('--name') + 1],
                         namespace=argv[argv.index('--namespace') + 1])
node.create_publisher(String, '~/out', 1)
print('ready', flush=True)
try:
    while True:  # never spins: its parameter services never answer
        time.sleep(0.05)
except KeyboardInterrupt:
    pass
'''


def test_node_that_never_answers_parameter_requests(ros_node, tmp_path) -> None:
    """Parameters unreadable: a note, no parameters, and the timeout is kept."""
    script = tmp_path / 'silent_node.py'
    script.write_text(_SILENT_NODE, encoding='utf-8')
    node = ros_node(str(script), 'silent', '/obs')
    timeout = 1.0
    with ros_session() as session:
        wait_for_node(session, node.fqn, 15)
        start = time.monotonic()
        observed = observe_node(node.fqn, timeout=timeout, session=session)
        elapsed = time.monotonic() - start
    assert elapsed < timeout + 3
    assert observed.parameters is None
    assert observed.notes == ['parameters could not be read (the node serves no parameter services, '
                              'or they did not answer in time)']
    assert '/obs/silent/out' in _names(observed, 'publishers')


@pytest.mark.parametrize('sections, lopsided', [
    ({'publishers': ['/rosout']}, True),
    ({'subscriptions': ['/x']}, True),
    ({'service_servers': ['/n/get_parameters']}, True),
    ({'publishers': ['/rosout'], 'service_servers': ['/n/get_parameters']}, False),
    ({'publishers': ['/rosout'], 'service_clients': ['/c']}, False),
    ({}, False),
])
def test_only_writers_or_only_readers_is_lopsided(sections: dict, lopsided: bool) -> None:
    from nodl.live.observe import _lopsided

    raw = {s: [(n, ['t']) for n in sections.get(s, [])]
           for s in ('publishers', 'subscriptions', 'service_servers', 'service_clients')}
    assert _lopsided(raw) is lopsided
