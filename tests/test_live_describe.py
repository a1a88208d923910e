"""describe: a node definition written from an observation.

describe_observed is tested on synthetic observations (with golden files);
describe_node on real node processes, whose descriptions must validate.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from conftest import FIXTURES, NodeProcess
from nodl import ValidationError, load_node, validate_node
from nodl.composition.bases import base_layer
from nodl.live.describe import Description, deduce_base, describe_node, describe_observed, render_description
from nodl.live.observe import ObservedEndpoint, ObservedNode, ObservedParameter
from nodl.live.session import ros_session
from nodl.naming import expand

EXPECTED = FIXTURES / 'live' / 'expected'
SECTIONS = ('publishers', 'subscriptions', 'service_servers', 'service_clients', 'action_servers',
            'action_clients')


def _base_entities(base: str, name: str, namespace: str) -> dict[str, list[ObservedEndpoint]]:
    """What the built-in base says a node of that name exposes, as observed endpoints."""
    iface = base_layer(base).interface
    out: dict[str, list[ObservedEndpoint]] = {}
    for section in SECTIONS:
        out[section] = []
        for entity in iface.endpoints(section):
            qos = None
            if section in ('publishers', 'subscriptions'):
                qos = {k: v for k, v in entity.qos.to_dict().items() if k not in ('history', 'depth')}
            out[section].append(ObservedEndpoint(expand(entity.name, name, namespace), entity.type,
                                                 qos, ['history', 'depth'] if qos else []))
    return out


def synthetic_lifecycle_camera() -> ObservedNode:
    """A lifecycle camera driver /robot/camera as Fast DDS would report it."""
    node = ObservedNode('camera', '/robot')
    for section, endpoints in _base_entities('lifecycle_node', 'camera', '/robot').items():
        setattr(node, section, list(endpoints))
    unobserved = ['history', 'depth']
    node.publishers += [
        ObservedEndpoint('/robot/camera/image_raw', 'sensor_msgs/msg/Image',
                         {'reliability': 'BEST_EFFORT', 'durability': 'VOLATILE',
                          'liveliness': 'AUTOMATIC'}, list(unobserved)),
        ObservedEndpoint('/robot/camera_info', 'sensor_msgs/msg/CameraInfo',
                         {'reliability': 'RELIABLE', 'durability': 'TRANSIENT_LOCAL',
                          'liveliness': 'AUTOMATIC', 'deadline_ns': 100_000_000}, list(unobserved)),
        ObservedEndpoint('/diagnostics', 'diagnostic_msgs/msg/DiagnosticArray', None, ['qos']),
    ]
    node.subscriptions += [
        ObservedEndpoint('/robot/trigger', 'std_msgs/msg/Empty',
                         {'history': 'KEEP_LAST', 'depth': 3, 'reliability': 'RELIABLE',
                          'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC',
                          'liveliness_lease_duration_ns': 1_500_000_000}, []),
    ]
    node.service_servers += [ObservedEndpoint('/robot/camera/set_exposure',
                                              'std_srvs/srv/SetBool')]
    node.service_clients += [ObservedEndpoint('/lights/switch', 'std_srvs/srv/Trigger')]
    node.action_servers = [ObservedEndpoint('/robot/camera/calibrate',
                                            'example_interfaces/action/Fibonacci')]
    node.action_clients = [ObservedEndpoint('/robot/arm/move', 'example_interfaces/action/Fibonacci')]
    node.parameters = {p.name: p for p in [
        ObservedParameter('use_sim_time', 'bool', False),
        ObservedParameter('start_type_description_service', 'bool', True, read_only=True),
        ObservedParameter('qos_overrides./robot/camera/image_raw.publisher.depth', 'int', 5,
                          read_only=True),
        ObservedParameter('fps', 'int', 30, 'Frames per second.', range=(1, 120)),
        ObservedParameter('exposure', 'double', 0.01, 'Exposure in seconds.', range=(0.0, 0.5)),
        ObservedParameter('device', 'string', '/dev/video0', 'Video device.', read_only=True),
        ObservedParameter('roi', 'int_array', [0, 0, 640, 480], 'Region of interest.'),
        ObservedParameter('undeclared_type', 'none', None),
    ]}
    return node


# -- synthetic -------------------------------------------------------------------------------


def test_deduce_base() -> None:
    camera = synthetic_lifecycle_camera()
    assert deduce_base(camera) == 'lifecycle_node'
    camera.service_servers = [e for e in camera.service_servers
                              if not e.name.endswith('/get_transition_graph')]
    assert deduce_base(camera) == 'node'
    assert deduce_base(ObservedNode('x', '/')) == 'node'


def test_base_entities_are_left_out_and_names_relativized() -> None:
    description = describe_observed(synthetic_lifecycle_camera())
    assert isinstance(description, Description)
    assert description.fqn == '/robot/camera'
    definition = description.definition
    assert definition['base'] == 'lifecycle_node' and definition['nodl_version'] == 2
    main = definition['main']
    names = {section: sorted(e['name'] for e in main.get(section, [])) for section in SECTIONS}
    assert names == {
        'publishers': ['/diagnostics', 'camera_info', '~/image_raw'],
        'subscriptions': ['trigger'],
        'service_servers': ['~/set_exposure'],
        'service_clients': ['/lights/switch'],
        'action_servers': ['~/calibrate'],
        'action_clients': ['arm/move'],
    }
    # base parameters and qos_overrides.* are left out too
    assert list(main['parameters']) == ['device', 'exposure', 'fps', 'roi', 'undeclared_type']


def test_entity_of_a_base_name_with_another_type_is_kept() -> None:
    camera = synthetic_lifecycle_camera()
    rosout = next(e for e in camera.publishers if e.name == '/rosout')
    rosout.type = 'std_msgs/msg/String'
    main = describe_observed(camera).definition['main']
    assert {'name': '/rosout', 'type': 'std_msgs/msg/String'}.items() <= \
        next(e for e in main['publishers'] if e['name'] == '/rosout').items()


def test_parameters_ranges_become_bounds() -> None:
    params = describe_observed(synthetic_lifecycle_camera()).definition['main']['parameters']
    assert params['fps'] == {'type': 'int', 'default_value': 30, 'description': 'Frames per second.',
                             'validation': {'bounds<>': [1, 120]}}
    assert params['exposure']['validation'] == {'bounds<>': [0.0, 0.5]}
    assert params['device'] == {'type': 'string', 'default_value': '/dev/video0',
                                'description': 'Video device.', 'read_only': True}
    assert params['roi'] == {'type': 'int_array', 'default_value': [0, 0, 640, 480],
                             'description': 'Region of interest.'}
    assert params['undeclared_type'] == {'type': 'none'}


def test_qos_as_observed_and_notes_for_what_is_not() -> None:
    description = describe_observed(synthetic_lifecycle_camera())
    publishers = {e['name']: e['qos'] for e in description.definition['main']['publishers']}
    # history and depth unobserved: SYSTEM_DEFAULT (claims nothing), no depth
    assert publishers['~/image_raw'] == {'history': 'SYSTEM_DEFAULT', 'reliability': 'BEST_EFFORT',
                                        'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}
    assert publishers['camera_info']['deadline_ns'] == 100_000_000
    # QoS not read at all: nothing but the two fields the schema requires
    assert publishers['/diagnostics'] == {'history': 'SYSTEM_DEFAULT',
                                          'reliability': 'SYSTEM_DEFAULT'}
    trigger = description.definition['main']['subscriptions'][0]['qos']
    assert trigger == {'history': 'KEEP_LAST', 'depth': 3, 'reliability': 'RELIABLE',
                       'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC',
                       'liveliness_lease_duration_ns': 1_500_000_000}
    # services carry no QoS
    assert 'qos' not in description.definition['main']['service_servers'][0]
    notes = description.notes
    assert any('history and depth are not reported' in n for n in notes)
    assert any('service QoS cannot be observed' in n for n in notes)
    assert any('could not be read' in n for n in notes)


def test_no_notes_when_everything_was_observed() -> None:
    node = ObservedNode('talker', '/')
    node.publishers = [ObservedEndpoint('/chatter', 'std_msgs/msg/String',
                                        {'history': 'KEEP_LAST', 'depth': 10,
                                         'reliability': 'RELIABLE'}, [])]
    description = describe_observed(node)
    assert description.notes == []
    assert description.definition == {
        'nodl_version': 2, 'base': 'node',
        'main': {'nodl_version': 2, 'publishers': [
            {'name': '/chatter', 'type': 'std_msgs/msg/String',
             'qos': {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE'}}]}}
    text = render_description(description)
    assert text.startswith('# Described from the running node /talker by `nodl describe`.\n')
    assert 'Not observable' not in text


def test_unobserved_policy_and_observation_notes_are_kept() -> None:
    node = ObservedNode('talker', '/')
    node.publishers = [ObservedEndpoint('/chatter', 'std_msgs/msg/String',
                                        {'history': 'KEEP_LAST', 'depth': 1}, ['reliability'])]
    node.notes = ['parameters could not be read (the node serves no parameter services, or they '
                  'did not answer in time)']
    description = describe_observed(node)
    assert description.notes[0].startswith('parameters could not be read')
    assert 'topic reliability was not reported by the middleware for some endpoints' in \
        description.notes
    assert description.definition['main']['publishers'][0]['qos']['reliability'] == 'SYSTEM_DEFAULT'
    assert 'parameters' not in description.definition['main']


def test_synthetic_description_validates_and_matches_golden(golden) -> None:
    description = describe_observed(synthetic_lifecycle_camera())
    for warning in validate_node(description.definition):
        assert 'has no description' in warning.message  # nothing else to complain about
    text = render_description(description)
    golden.check(text, EXPECTED / 'lifecycle_camera.nodl.yaml')
    # the rendering is a loadable node definition equal to the dict
    assert load_node(text).to_dict() == load_node(render_description(description, 'json')).to_dict()
    golden.check(render_description(description, 'json'), EXPECTED / 'lifecycle_camera.nodl.json')


def test_header_lists_every_note() -> None:
    description = describe_observed(synthetic_lifecycle_camera())
    header = [line for line in render_description(description).splitlines() if line.startswith('#')]
    assert header[0] == '# Described from the running node /robot/camera by `nodl describe`.'
    assert header[1] == ('# Left out: what the base gives an rclpy node (the node does not '
                         'subscribe to /parameter_events, as rclcpp nodes do).')
    assert header[2] == '# Not observable, so not stated here:'
    assert header[3:-1] == [f'#   - {note}' for note in description.notes]
    # The last line silences 'has no description' (describe cannot know them), even with strict.
    assert header[-1].startswith('# nodl: ignore=NODL216 ')
    assert load_node(render_description(description), strict=True)
    assert not render_description(description, 'json').startswith('#')


def test_a_shared_name_is_a_warning_line_not_an_unobservable_note() -> None:
    node = ObservedNode('twin', '/ux', instances=2)
    node.warnings = ['2 nodes in the graph are named /ux/twin: what was observed is all of '
                     'them together (give each node a unique name)']
    node.publishers = [ObservedEndpoint('/chatter', 'std_msgs/msg/String',
                                        {'history': 'KEEP_LAST', 'depth': 10,
                                         'reliability': 'RELIABLE'}, [])]
    description = describe_observed(node)
    assert description.warnings == node.warnings
    assert description.notes == []
    header = [line for line in render_description(description).splitlines() if line.startswith('#')]
    assert header[2] == ('# Warning: 2 nodes in the graph are named /ux/twin: what was observed '
                         'is all of them together (give each node a unique name).')
    assert not any('Not observable' in line for line in header)
    node.notes = ['parameters could not be read (the node serves no parameter services, or they '
                  'did not answer in time)']
    text = render_description(describe_observed(node))
    listed = text.split('# Not observable, so not stated here:\n', 1)[1].split('# nodl:', 1)[0]
    assert 'named /ux/twin' not in listed and 'parameters could not be read' in listed
    assert text.index('# Warning: 2 nodes') < text.index('# Not observable')


def test_file_names_of_describe_all() -> None:
    from nodl.live.describe_all import file_name_for

    assert file_name_for('/robot/driver') == 'robot.driver.nodl.yaml'
    assert file_name_for('/talker', 'json') == 'talker.nodl.json'


# -- real nodes ------------------------------------------------------------------------------


@pytest.fixture(scope='module')
def session():
    with ros_session() as node:
        yield node


@pytest.fixture(scope='module')
def nodes() -> Iterator[dict[str, NodeProcess]]:
    started: dict[str, NodeProcess] = {}
    try:
        started['full'] = NodeProcess('full_node.py', 'full', '/desc')
        started['lifecycle'] = NodeProcess('lifecycle_node.py', 'managed', '/desc')
        started['actions'] = NodeProcess('action_nodes.py', 'fib', '/desc')
        yield started
    finally:
        for node in started.values():
            node.stop()


def test_describe_full_node(nodes, session) -> None:
    description = describe_node('/desc/full', timeout=15, session=session)
    definition = description.definition
    warnings = validate_node(definition)
    assert all(w.severity.value == 'warning' for w in warnings)
    assert definition['base'] == 'node'
    main = definition['main']
    assert sorted((e['name'], e['type']) for e in main['publishers']) == [
        ('/global_chatter', 'std_msgs/msg/String'), ('measurement', 'std_msgs/msg/Float64'),
        ('~/status', 'std_msgs/msg/String')]
    assert sorted((e['name'], e['type']) for e in main['subscriptions']) == [
        ('/emergency_stop', 'std_msgs/msg/Bool'), ('commands', 'std_msgs/msg/String')]
    assert main['service_servers'] == [{'name': '~/reset', 'type': 'std_srvs/srv/Trigger'}]
    assert main['service_clients'] == [{'name': '/motor/enable', 'type': 'std_srvs/srv/SetBool'}]
    assert 'action_servers' not in main and 'action_clients' not in main
    assert set(main['parameters']) == {'frame_id', 'gain', 'joints', 'rate', 'verbose'}
    assert main['parameters']['rate']['validation'] == {'bounds<>': [1, 100]}
    assert main['parameters']['gain']['validation'] == {'bounds<>': [0.0, 1.0]}
    assert main['parameters']['frame_id']['read_only'] is True
    status = next(e for e in main['publishers'] if e['name'] == '~/status')['qos']
    assert (status['reliability'], status['durability']) == ('RELIABLE', 'TRANSIENT_LOCAL')
    chatter = next(e for e in main['publishers'] if e['name'] == '/global_chatter')['qos']
    assert (chatter['deadline_ns'], chatter['lifespan_ns'], chatter['liveliness_lease_duration_ns']) \
        == (1_000_000_000, 2_000_000_000, 3_000_000_000)

    text = render_description(description)
    assert text.startswith('# Described from the running node /desc/full by `nodl describe`.\n')
    assert any('service QoS' in n for n in description.notes)
    for note in description.notes:
        assert f'#   - {note}' in text
    assert load_node(text).to_dict() == load_node(render_description(description, 'json')).to_dict()


def test_describe_full_node_without_parameters(nodes, session) -> None:
    description = describe_node('/desc/full', timeout=15, parameters=False, session=session)
    validate_node(description.definition)
    assert 'parameters' not in description.definition['main']
    assert 'publishers' in description.definition['main']


def test_describe_lifecycle_node(nodes, session) -> None:
    description = describe_node('/desc/managed', timeout=15, session=session)
    assert description.definition == {'nodl_version': 2, 'base': 'lifecycle_node',
                                      'main': {'nodl_version': 2}}
    validate_node(description.definition)
    text = render_description(description)
    for service in ('change_state', 'get_state', 'transition_event'):
        assert service not in text


def test_describe_action_nodes(nodes, session) -> None:
    server = describe_node('/desc/fib', timeout=15, parameters=False, session=session).definition
    client = describe_node('/desc/fib_client', timeout=15, parameters=False,
                           session=session).definition
    assert server['main'] == {'nodl_version': 2, 'action_servers': [
        {'name': '~/fibonacci', 'type': 'test_msgs/action/Fibonacci'}]}
    assert client['main'] == {'nodl_version': 2, 'action_clients': [
        {'name': 'fib/fibonacci', 'type': 'test_msgs/action/Fibonacci'}]}
    for definition in (server, client):
        validate_node(definition)
        assert '_action' not in str(definition)


def test_described_definition_that_is_broken_would_be_reported() -> None:
    """validate_node is a real check here: a mangled description fails it."""
    definition = describe_observed(synthetic_lifecycle_camera()).definition
    definition['main']['publishers'][0]['qos'] = {'depth': 'ten'}
    with pytest.raises(ValidationError):
        validate_node(definition)


# --- client libraries --------------------------------------------------------------------------

def _rclcpp_like(observed: ObservedNode) -> ObservedNode:
    """``observed`` as an rclcpp node would show it: its time source subscribes /parameter_events."""
    observed.subscriptions.append(ObservedEndpoint(
        '/parameter_events', 'rcl_interfaces/msg/ParameterEvent',
        {'history': 'KEEP_LAST', 'depth': 1000, 'reliability': 'RELIABLE', 'durability': 'VOLATILE'}))
    return observed


def test_the_client_library_is_deduced_and_its_base_left_out() -> None:
    from nodl.live.describe import deduce_client_library

    plain = synthetic_lifecycle_camera()
    assert deduce_client_library(plain).name == 'rclpy'
    cpp = _rclcpp_like(synthetic_lifecycle_camera())
    choice = deduce_client_library(cpp)
    assert choice == ('rclcpp', "the node subscribes to /parameter_events, as rclcpp's time "
                                'source does')
    description = describe_observed(cpp)
    assert description.client_library == choice
    # the subscription is rclcpp's base, not the node's own: left out, as with rclpy
    assert description.node.main.subscriptions == describe_observed(plain).node.main.subscriptions
    assert render_description(description).splitlines()[1] == (
        "# Left out: what the base gives an rclcpp node (the node subscribes to /parameter_events, "
        "as rclcpp's time source does).")


def test_a_requested_client_library_wins() -> None:
    cpp = _rclcpp_like(synthetic_lifecycle_camera())
    description = describe_observed(cpp, 'rclpy')
    assert description.client_library == ('rclpy', 'as requested')
    assert '/parameter_events' in {s.name for s in description.node.main.subscriptions or ()}
    with pytest.raises(ValueError, match='unknown client library'):
        describe_observed(cpp, 'rclc')


def test_the_description_is_built_as_a_typed_node() -> None:
    from nodl.model import Node, TopicEndpoint

    description = describe_observed(synthetic_lifecycle_camera())
    assert isinstance(description.node, Node)
    assert all(isinstance(p, TopicEndpoint) for p in description.node.main.publishers or ())
    assert description.definition == description.node.to_dict()
    assert validate_node(description.definition) is not None


def test_describe_reports_version_skew_next_to_the_entity(tmp_path, monkeypatch) -> None:
    """A node built against another String than the installed one: the skew is a warning
    naming the field, and a comment above the entity in the written definition."""
    from skewed_prefix import STRING_WITH_REVISION, VENV, skewed_prefix

    prefix = skewed_prefix(tmp_path, {'std_msgs/msg/String': STRING_WITH_REVISION})
    node = NodeProcess('typed_node.py', 'typed_d', '/skew_d')
    try:
        monkeypatch.setenv('AMENT_PREFIX_PATH', str(VENV))
        assert describe_node(node.fqn, timeout=15).skew_warnings == []
        monkeypatch.setenv('AMENT_PREFIX_PATH', f'{prefix}:{VENV}')
        description = describe_node(node.fqn, timeout=15)
        without = describe_node(node.fqn, timeout=15, types=False)
    finally:
        node.stop()
    assert without.skew == []
    [warning] = description.skew_warnings
    assert warning.startswith("/skew_d/chatter: the node uses another definition of "
                              "'std_msgs/msg/String' than the installed one")
    assert "field 'revision' (int32) is in the installed definition" in warning
    lines = render_description(description).splitlines()
    at = lines.index('  - name: chatter')
    assert lines[at - 1] == f'  # Version skew: {warning}'
    assert '# Version skew' not in render_description(without)
    # the comment keeps the file a valid definition
    validate_node(load_node('\n'.join(lines)).to_dict())
