"""nodl studio's HTTP API (nodl.studio.app over nodl.studio.session), through starlette's
TestClient: the example system as the page gets it, and the edits the page sends (add,
connect, compatible ports, parameters, names, remapping rules, save, positions, exports).

The example system (examples/system) is copied into a temporary folder (the studio writes
next to its launch file); its definitions come from a definitions folder
(tests/fixtures/studio/example_definitions), so no colcon build is needed.
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import pytest
from starlette.testclient import TestClient

from conftest import FIXTURES, REPO
from nodl.composer import Composition
from nodl.studio.app import create_app
from nodl.studio.session import Session
from nodl.targets.resolve import gather_definitions

DEFINITIONS = FIXTURES / 'studio' / 'example_definitions'
TOKEN = 'test-token'
PORT = 8999


def make_client(launch: Path, *, execute: bool = True) -> tuple[TestClient, Session]:
    definitions = gather_definitions([str(DEFINITIONS)], use_config=False)
    session = Session(str(launch), definitions=definitions, roots=[str(DEFINITIONS)],
                      execute=execute, definition_folders=[str(DEFINITIONS)])
    client = TestClient(create_app(session, TOKEN, PORT), base_url=f'http://127.0.0.1:{PORT}')
    client.headers['x-nodl-token'] = TOKEN
    return client, session


@pytest.fixture
def example(tmp_path: Path) -> Path:
    """A copy of the example system; its top launch file."""
    shutil.copytree(REPO / 'examples' / 'system', tmp_path / 'system')
    return tmp_path / 'system' / 'launch' / 'rover.launch.xml'


def post(client: TestClient, path: str, **data: Any) -> dict[str, Any]:
    response = client.post(f'/api/{path}', json=data)
    answer: dict[str, Any] = response.json()
    answer['status'] = response.status_code
    return answer


def node_named(state: dict[str, Any], fqn: str) -> dict[str, Any]:
    return next(n for n in state['nodes'] if n['fqn'] == fqn)


def test_the_example_system_as_the_page_gets_it(example: Path) -> None:
    client, _ = make_client(example)
    state = post(client, 'state')['state']
    nodes = {n['fqn']: n for n in state['nodes']}
    # the file's own nodes are editable; the included YAML file's are drawn, read-only
    assert nodes['/rover/motor_controller']['editable']
    assert not nodes['/rover/lidar']['editable'] and nodes['/rover/lidar']['included']
    assert 'sensors.launch.yaml' in nodes['/rover/lidar']['read_only_reason']
    # the Python launch file is not run until asked: its nodes are missing, and it says so
    assert '/rover/localizer' not in nodes
    assert state['code'] == {'allowed': True, 'ran': False, 'needed': True,
                             'message': state['code']['message']}
    # ports: the definitions' endpoints with final names, the client library's left out
    ports = {p['name']: p for p in nodes['/rover/safety_controller']['ports']}
    assert set(ports) == {'cmd_vel', 'scan', 'cmd_vel_in', '~/reset'}
    assert ports['cmd_vel_in']['final'] == '/rover/cmd_vel_nav'
    # edges: the analysis's connections between drawn ports
    edges = {(e['source'], e['target']) for e in state['edges']}
    lidar, safety = nodes['/rover/lidar']['id'], nodes['/rover/safety_controller']['id']
    assert (f'{lidar}|publisher|scan', f'{safety}|subscription|scan') in edges
    # findings: nodl analyse's, with its codes, naming the nodes they concern
    codes = {f['code'] for f in state['findings']}
    assert {'NODL525', 'NODL553', 'NODL559', 'NODL561', 'NODL562', 'NODL564'} <= codes
    # not run because nobody asked yet (the studio was not given --no-exec): it says how to ask
    not_run = next(f for f in state['findings'] if f['code'] == 'NODL525')
    assert 'click Run launch Python' in not_run['message'] and '--no-exec' not in not_run['message']
    qos = next(f for f in state['findings'] if f['code'] == 'NODL553')
    assert qos['nodes'] == ['/rover/lidar', '/rover/safety_controller']
    assert state['counts']['error'] == sum(f['severity'] == 'error' for f in state['findings'])
    # parameters: type, default, constraints in words
    capacity = next(p for p in nodes['/rover/battery_monitor']['parameters']
                    if p['name'] == 'capacity_ah')
    assert capacity['given'] and capacity['text'] == '24.0'
    assert capacity['default_text'] == '20.0' and capacity['constraints'] == 'must be greater than 0.0'
    # what is kept as written is listed read-only
    assert any('include' in k['what'] for k in state['readonly'])
    # a group's push of a namespace it reads is the group (drawn), not a piece it leaves alone;
    # one it cannot read ($(var robot)) is read-only
    assert [k['what'] for k in state['readonly']].count('<push-ros-namespace>') == 1


def test_the_palette_lists_every_definition_with_its_ports(example: Path) -> None:
    from nodl.studio.palette import matches

    client, _ = make_client(example)
    palette = post(client, 'palette')['palette']
    assert len(palette) == 15
    lidar = next(e for e in palette if e['executable'] == 'lidar_driver')
    assert lidar['node_name'] == 'lidar' and lidar['origin'].startswith('overlay')
    assert {'kind': 'publisher', 'name': 'scan', 'type': 'sensor_msgs/msg/LaserScan'} in lidar['ports']
    # searched by package, executable and interface type
    assert [e['executable'] for e in palette if matches(e, 'LaserScan')] == \
        ['safety_controller', 'lidar_driver']
    assert [e['executable'] for e in palette if matches(e, 'rover_tools dash')] == ['dashboard']


def test_add_connect_set_and_save_write_the_launch_file(example: Path) -> None:
    client, session = make_client(example)
    added = post(client, 'add', package='rover_tools', executable='dashboard',
                 name='dashboard', namespace='/ops')
    assert added['ok'], added
    state = added['state']
    dashboard = node_named(state, '/ops/dashboard')
    battery = node_named(state, '/rover/battery_monitor')
    source = f"{battery['id']}|publisher|battery"
    target = f"{dashboard['id']}|subscription|battery"
    # while dragging: the compatible ports, by the composer's verdict
    verdicts = post(client, 'compatible', port=source)['ports']
    assert verdicts[target]['ok']
    assert not verdicts[f"{node_named(state, '/rover/safety_controller')['id']}|subscription|scan"]['ok']
    assert 'types differ' in verdicts[f"{node_named(state, '/rover/safety_controller')['id']}"
                                      '|subscription|scan']['reason']
    connected = post(client, 'connect', a=source, b=target)
    assert connected['ok'], connected
    assert connected['remaps'] == [{'node': dashboard['id'], 'from': 'battery',
                                    'to': '/rover/battery'}]
    assert (source, target) in {(e['source'], e['target']) for e in connected['state']['edges']}
    # a value that breaks a validator: refused, with the error, nothing changed
    broken = post(client, 'parameter', node=battery['id'], name='capacity_ah', value='-5.0')
    assert not broken['ok'] and broken['diagnostics'][0]['code'] == 'NODL977'
    assert 'greater than 0' in broken['error']
    fine = post(client, 'parameter', node=battery['id'], name='capacity_ah', value='30.0')
    assert fine['ok'], fine
    saved = post(client, 'save')
    assert saved['ok'], saved
    text = example.read_text(encoding='utf-8')
    assert '<param name="capacity_ah" value="30.0"/>' in text
    assert '<push-ros-namespace namespace="/ops"/>' in text or 'namespace="ops"' in text
    assert '<remap from="battery" to="/rover/battery"/>' in text
    # the composer reads back what the studio showed
    reread = Composition.open(str(example), definitions=session.definitions)
    again = {n['fqn']: n for n in reread.to_dict()['nodes']}
    assert again['/ops/dashboard']['remaps'] == [['battery', '/rover/battery']]
    assert again['/rover/battery_monitor']['parameters'] == {'capacity_ah': 30.0}


def test_names_namespaces_and_remapping_rules(example: Path) -> None:
    client, _ = make_client(example)
    state = post(client, 'state')['state']
    teleop = node_named(state, '/rover/teleop')
    # refused by the composer, nothing changed: its errors, and the state as it was
    refused = post(client, 'rename', node=teleop['id'], name='tele op', namespace='')
    assert not refused['ok'] and refused['diagnostics'][0]['code'] == 'NODL982'
    assert "'tele op' is not a node name" in refused['error']
    assert node_named(refused['state'], '/rover/teleop')['name_given'] == 'teleop'
    taken = post(client, 'rename', node=teleop['id'], name='battery_monitor', namespace='')
    assert not taken['ok'] and taken['diagnostics'][0]['code'] == 'NODL982'
    renamed = post(client, 'rename', node=teleop['id'], name='joystick', namespace='')
    assert renamed['ok'], renamed
    assert node_named(renamed['state'], '/rover/joystick')['name_given'] == 'joystick'
    # the rules of the entry, edited as a whole (teleop into the safety controller's input)
    ruled = post(client, 'remaps', node=teleop['id'], remaps=[['cmd_vel', 'cmd_vel_nav']])
    assert ruled['ok'], ruled
    ports = node_named(ruled['state'], '/rover/joystick')['ports']
    assert ports == [{'kind': 'publisher', 'name': 'cmd_vel', 'final': '/rover/cmd_vel_nav',
                      'type': 'geometry_msgs/msg/Twist'}]
    assert 'NODL551' not in {f['code'] for f in ruled['state']['findings']}  # one publisher left
    bad = post(client, 'remaps', node=teleop['id'], remaps=[['cmd vel', 'x']])
    assert not bad['ok'] and bad['diagnostics'][0]['code'] == 'NODL988'
    assert node_named(bad['state'], '/rover/joystick')['remaps'] == [
        {'from': 'cmd_vel', 'to': 'cmd_vel_nav', 'kept': False}]
    assert post(client, 'remaps', node=teleop['id'], remaps='cmd_vel:=x')['status'] == 400
    # a read-only node (from the included file) cannot be renamed
    lidar = node_named(state, '/rover/lidar')
    assert post(client, 'rename', node=lidar['id'], name='x')['status'] == 400


def test_positions_are_kept_next_to_the_launch_file(example: Path) -> None:
    client, _ = make_client(example)
    state = post(client, 'state')['state']
    teleop = node_named(state, '/rover/teleop')
    kept = post(client, 'positions', positions={teleop['id']: {'x': 10.5, 'y': -20},
                                                'nonsense': {'x': 1, 'y': 2}})
    side = example.parent / 'rover.launch.xml.studio.json'
    assert kept['ok'] and kept['file'] == str(side)
    assert '"/rover/teleop": {\n   "x": 10.5,\n   "y": -20.0\n  }' in side.read_text()
    client2, _ = make_client(example)
    assert post(client2, 'state')['state']['positions'] == {teleop['id']: {'x': 10.5, 'y': -20.0}}


def test_an_empty_file_is_composed_and_created_on_save(tmp_path: Path) -> None:
    launch = tmp_path / 'new.launch.yaml'
    client, _ = make_client(launch)
    state = post(client, 'state')['state']
    assert state['nodes'] == [] and state['dirty'] and not launch.exists()
    assert post(client, 'add', package='rover_tools', executable='teleop', name='teleop')['ok']
    assert post(client, 'save')['ok']
    assert 'package: rover_tools' in launch.read_text() or 'pkg: rover_tools' in launch.read_text()


def test_exports_write_next_to_the_launch_file(tmp_path: Path) -> None:
    launch = tmp_path / 'small.launch.xml'
    launch.write_text('<launch>\n  <node pkg="rover_tools" exec="teleop" name="teleop"/>\n'
                      '  <node pkg="rover_base" exec="motor_controller" name="motor"/>\n</launch>\n')
    client, _ = make_client(launch, execute=False)
    assert post(client, 'add', package='rover_tools', executable='dashboard', name='dash')['ok']
    assert 'save the launch file first' in post(client, 'export', what='policy')['error']
    assert post(client, 'save')['ok']
    # (doc runs the same way: nodl doc LAUNCH -o small-docs; left out for time)
    for what, name in (('policy', 'small.policy.xml'), ('graph', 'small.graph.svg')):
        answer = post(client, 'export', what=what)
        assert answer['ok'] and answer['written'] == [str(tmp_path / name)], answer
    assert '<profile ns="/" node="dash">' in (tmp_path / 'small.policy.xml').read_text()
    assert (tmp_path / 'small.graph.svg').read_text().lstrip().startswith('<')
    # a file of the user's at the export's path is not replaced
    (tmp_path / 'mine.xml').write_text('my own policy\n')
    refused = post(client, 'export', what='policy', output='mine.xml')
    assert not refused['ok'] and (tmp_path / 'mine.xml').read_text() == 'my own policy\n', refused
    assert post(client, 'export', what='nothing')['status'] == 400


def test_the_page_puts_text_from_definitions_as_text_only() -> None:
    """Names, descriptions and messages reach the page only through textContent, attributes
    and canvas labels: the page's script never parses text as HTML."""
    import re

    from nodl.studio.app import STATIC

    script = (STATIC / 'studio.js').read_text(encoding='utf-8')
    code = re.sub(r'/\*.*?\*/|//[^\n]*', '', script, flags=re.S)  # (comments may name them)
    assert not re.search(r'innerHTML|outerHTML|insertAdjacentHTML|document\.write|\beval\(|'
                         r'new Function|setTimeout\(\s*[\'"]', code)
    assert code.count('.textContent =') >= 5
    page = (STATIC / 'index.html').read_text(encoding='utf-8')
    assert '<script>' not in page  # no inline script (the policy allows none either)
    assert not re.search(r'\son[a-z]+\s*=', page)  # no onclick= and the like
