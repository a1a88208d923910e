"""The analysis checks against the real semantics (nodl.system.checks.names,
connections, orphans): final names as rcl makes them (``__node``/``__ns`` rules, pushed
namespaces, composable nodes), QoS exactly as ``check_qos_compatible`` decides for every
publisher/subscription pair, actions remapped as a whole by their name as rcl remaps them
(a rule for an ``_action/...`` name only splits the action), services by service rules."""

from __future__ import annotations

import itertools
from pathlib import Path
from typing import Any

import yaml

from nodl.analysis import analyse_launch
from nodl.qos_compat import check_qos_compatible


def _prefix(root: Path, nodes: dict[str, dict[str, Any]], info: dict[str, str] | None = None) -> list[str]:
    """An ament prefix with the package ``demo`` registering ``nodes`` (executable -> the
    ``main`` of its definition); ``info``: executable -> its nodl_node_info text."""
    prefix = root / 'prefix'
    index = prefix / 'share' / 'ament_index' / 'resource_index'
    share = prefix / 'share' / 'demo'
    for folder in (index / 'packages', index / 'nodl_nodes', index / 'nodl_node_info', share / 'nodl'):
        folder.mkdir(parents=True, exist_ok=True)
    (index / 'packages' / 'demo').write_text('', encoding='utf-8')
    (share / 'package.xml').write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>demo</name><version>0.1.0</version>'
        '<description>d</description><maintainer email="a@b.c">a</maintainer>'
        '<license>Apache-2.0</license><export><build_type>ament_python</build_type></export>'
        '</package>\n', encoding='utf-8')
    for executable, main in nodes.items():
        document = {'nodl_version': 2, 'base': 'node',
                    'main': {'nodl_version': 2, 'description': f'{executable}.', **main}}
        (share / 'nodl' / f'{executable}.nodl.yaml').write_text(yaml.safe_dump(document), encoding='utf-8')
        (index / 'nodl_nodes' / f'demo__{executable}').write_text(f'nodl/{executable}.nodl.yaml',
                                                                   encoding='utf-8')
    for executable, text in (info or {}).items():
        (index / 'nodl_node_info' / f'demo__{executable}').write_text(text, encoding='utf-8')
    return [str(prefix)]


def _analyse(tmp_path: Path, nodes: dict[str, dict[str, Any]], launch: str,
             info: dict[str, str] | None = None) -> Any:
    prefixes = _prefix(tmp_path, nodes, info)
    path = tmp_path / 'system.launch.xml'
    path.write_text(launch, encoding='utf-8')
    analysis = analyse_launch(path, prefixes=prefixes)
    assert not [f for f in analysis.findings if f.kind in ('launch-file', 'not-analysable', 'broken-check')], \
        [str(f) for f in analysis.findings]
    return analysis


def _kinds(analysis: Any, *kinds: str) -> list[Any]:
    return [f for f in analysis.findings if f.kind in kinds]


# -- duplicate-node ------------------------------------------------------------------------

def test_duplicate_node_sees_final_names(tmp_path: Path) -> None:
    """Same final name by a pushed namespace, a __node rule (node-scoped too), a __ns rule,
    a composable node in a container and a node without definition; different namespaces
    or a __node rule for another node keep names apart."""
    analysis = _analyse(tmp_path, {'talker': {}}, '''<launch>
  <group><push-ros-namespace namespace="ns"/>
    <node pkg="demo" exec="talker" name="x"/>
  </group>
  <node pkg="demo" exec="talker" name="y" namespace="ns">
    <remap from="__node" to="x"/>
  </node>
  <node pkg="demo" exec="talker" name="z" namespace="/ns" ros_args="-r z:__node:=x"/>
  <node pkg="demo" exec="talker" name="x" namespace="/other" args="--ros-args -r __ns:=/ns"/>
  <node_container pkg="rclcpp_components" exec="component_container" name="box" namespace="/">
    <composable_node pkg="demo" plugin="demo::Talker" name="x" namespace="/ns"/>
  </node_container>
  <node pkg="demo" exec="unknown" name="x" namespace="ns"/>
  <node pkg="demo" exec="talker" name="w" namespace="/ns" ros_args="-r q:__node:=x"/>
  <node pkg="demo" exec="talker" name="x" namespace="/elsewhere"/>
  <node pkg="demo" exec="talker" name="box"/>
</launch>
''')
    assert [n.fqn for n in analysis.nodes] == ['/ns/x', '/ns/x', '/ns/x', '/ns/x', '/box', '/ns/x', '/ns/x',
                                               '/ns/w', '/elsewhere/x', '/box']
    found = [(f.diagnostic.line, f.nodes) for f in _kinds(analysis, 'duplicate-node')]
    assert found == [(5, ('/ns/x',)), (8, ('/ns/x',)), (9, ('/ns/x',)), (11, ('/ns/x',)),
                     (13, ('/ns/x',)), (16, ('/box',))]
    first = _kinds(analysis, 'duplicate-node')[0]
    assert [r[1] for r in first.diagnostic.related] == [3]  # where /ns/x is first launched


def test_duplicate_findings_at_one_place_follow_each_name_s_first_launch() -> None:
    """Nodes launched from one place (a loop in a Python launch file) sort alike: their
    duplicate-node findings come in the order of context.by_fqn, that of each name's first
    launch (/a before /b here, though /b is launched again first)."""
    from nodl.launch.model import LaunchedNode
    from nodl.location import Location
    from nodl.system.run import analyse_entries

    here = Location('system.launch.py', 4, 5)
    analysis = analyse_entries([LaunchedNode('node', 'demo', 'talker', name, '/', here)
                                for name in ('a', 'b', 'b', 'a', 'b')], prefixes=[])
    assert analysis.context is not None and list(analysis.context.by_fqn) == ['/a', '/b']
    found = [f.message.split(' ')[0] for f in _kinds(analysis, 'duplicate-node')]
    assert found == ['/a', '/b', '/b']


# -- QoS -----------------------------------------------------------------------------------

#: Publisher and subscription profiles on one topic; some omit durability, liveliness...
PUBLISHERS = {
    'p_reliable': {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE', 'durability': 'VOLATILE'},
    'p_best_effort': {'history': 'KEEP_LAST', 'depth': 5, 'reliability': 'BEST_EFFORT'},
    'p_latched': {'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'RELIABLE',
                  'durability': 'TRANSIENT_LOCAL', 'deadline_ns': 100000000},
    'p_default': {'history': 'SYSTEM_DEFAULT', 'reliability': 'SYSTEM_DEFAULT'},
    'p_manual': {'history': 'KEEP_ALL', 'reliability': 'RELIABLE', 'liveliness': 'MANUAL_BY_TOPIC',
                 'liveliness_lease_duration_ns': 2000000000},
}
SUBSCRIPTIONS = {
    's_latched': {'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'RELIABLE', 'durability': 'TRANSIENT_LOCAL'},
    's_best_effort': {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'BEST_EFFORT'},
    's_deadline': {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE', 'deadline_ns': 50000000},
    's_default': {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'SYSTEM_DEFAULT'},
    's_lease': {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'BEST_AVAILABLE',
                'liveliness': 'MANUAL_BY_TOPIC', 'liveliness_lease_duration_ns': 1000000000},
}


def test_qos_findings_are_exactly_check_qos_compatible_for_every_pair(tmp_path: Path) -> None:
    def endpoint(qos: dict[str, Any]) -> dict[str, Any]:
        return {'name': 'data', 'type': 'std_msgs/msg/String', 'description': 'd.', 'qos': qos}

    nodes: dict[str, dict[str, Any]] = {n: {'publishers': [endpoint(q)]} for n, q in PUBLISHERS.items()}
    nodes.update({n: {'subscriptions': [endpoint(q)]} for n, q in SUBSCRIPTIONS.items()})
    # a node with both ends: its own publisher is paired with its own subscription too
    nodes['relay'] = {'publishers': [endpoint(PUBLISHERS['p_best_effort'])],
                      'subscriptions': [endpoint(SUBSCRIPTIONS['s_latched'])]}
    launch = '<launch>\n' + ''.join(f'  <node pkg="demo" exec="{n}" name="{n}"/>\n' for n in nodes) + '</launch>\n'
    analysis = _analyse(tmp_path, nodes, launch)

    expected = {}
    pubs = {**PUBLISHERS, 'relay': PUBLISHERS['p_best_effort']}
    subs = {**SUBSCRIPTIONS, 'relay': SUBSCRIPTIONS['s_latched']}
    for (pub, pub_qos), (sub, sub_qos) in itertools.product(pubs.items(), subs.items()):
        verdict = check_qos_compatible(pub_qos, sub_qos)
        if verdict.verdict != 'ok':
            kind = 'qos-incompatible' if verdict.verdict == 'error' else 'qos-warning'
            expected[kind, f'/{pub}', f'/{sub}'] = verdict.reason
    assert any(k[0] == 'qos-incompatible' for k in expected) and any(k[0] == 'qos-warning' for k in expected)

    found = {}
    for finding in _kinds(analysis, 'qos-incompatible', 'qos-warning'):
        assert finding.endpoint == '/data'
        pub, sub = finding.nodes if len(finding.nodes) == 2 else finding.nodes * 2
        # both ends are named in the message, and both definitions are related places
        assert f'the publisher of {pub}' in finding.message and f'the subscription of {sub}' in finding.message
        related = [r[0] for r in finding.diagnostic.related]
        assert related[0].endswith(f'{pub[1:]}.nodl.yaml') and related[1].endswith(f'{sub[1:]}.nodl.yaml')
        # the finding is at the subscribing node's launch entry
        assert finding.diagnostic.line == list(nodes).index(sub[1:]) + 2
        key = (finding.kind, pub, sub)
        assert key not in found
        found[key] = finding.message.split(': ', 2)[-1]
    assert found == expected


def test_a_topic_many_nodes_share_is_checked_per_pair_of_profiles(tmp_path: Path) -> None:
    """Every node publishing and subscribing one topic (/tf-like): compatible profiles give no
    finding; one subscriber with a stricter profile gets one finding per publisher, in the
    publishers' order, as when every pair is looked at."""
    qos = {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE', 'durability': 'VOLATILE',
           'liveliness': 'AUTOMATIC'}

    def node(sub_qos: dict[str, Any]) -> dict[str, Any]:
        return {'publishers': [{'name': '/tf', 'type': 'std_msgs/msg/String', 'description': 'd.',
                                'qos': qos}],
                'subscriptions': [{'name': '/tf', 'type': 'std_msgs/msg/String', 'description': 'd.',
                                   'qos': sub_qos}]}

    nodes = {f'n{i}': node(qos) for i in range(6)}
    launch = '<launch>\n' + ''.join(f'  <node pkg="demo" exec="{n}" name="{n}"/>\n' for n in nodes) + '</launch>\n'
    assert not _kinds(_analyse(tmp_path / 'a', nodes, launch), 'qos-incompatible', 'qos-warning')

    nodes['n3'] = node({**qos, 'durability': 'TRANSIENT_LOCAL'})
    found = _kinds(_analyse(tmp_path / 'b', nodes, launch), 'qos-incompatible', 'qos-warning')
    assert [(f.kind, f.nodes) for f in found] == [  # (a node's own pair names it once)
        ('qos-incompatible', tuple(dict.fromkeys((f'/n{i}', '/n3')))) for i in range(6)]


# -- actions and services ------------------------------------------------------------------

def _action(name: str, type_name: str = 'test_msgs/action/Fibonacci') -> dict[str, Any]:
    return {'name': name, 'type': type_name, 'description': 'd.'}


def _service(name: str, type_name: str = 'std_srvs/srv/Empty') -> dict[str, Any]:
    return {'name': name, 'type': type_name, 'description': 'd.'}


def test_actions_and_services_connect_by_final_name(tmp_path: Path) -> None:
    """An action is remapped as a whole by topic rules on its name (rcl resolves the action
    name like a topic); rosservice:// rules do not touch it; a rule for one of its internal
    ``_action/...`` names renames no action.  Services take plain and rosservice:// rules,
    not rostopic:// ones.  A type difference is a type-mismatch, not an orphan."""
    nodes = {
        'server': {'action_servers': [_action('dock'), _action('fib'), _action('goto')],
                   'service_servers': [_service('get_map'), _service('reset', 'std_srvs/srv/Trigger')]},
        'client': {'action_clients': [_action('dock'), _action('undock'),
                                      _action('fib', 'test_msgs/action/NestedMessage'),
                                      _action('go'), _action('go2'), _action('go3'), _action('go4')],
                   'service_clients': [_service('map'), _service('map2'), _service('map3'),
                                       _service('reset'), _service('lost')]},
    }
    analysis = _analyse(tmp_path, nodes, '''<launch>
  <node pkg="demo" exec="server" name="server" namespace="/nav"/>
  <node pkg="demo" exec="client" name="client" namespace="/nav">
    <remap from="go" to="goto"/>
    <remap from="rostopic://go2" to="/nav/goto"/>
    <remap from="rosservice://go3" to="goto"/>
    <remap from="go4/_action/send_goal" to="goto/_action/send_goal"/>
    <remap from="map" to="get_map"/>
    <remap from="rosservice://map2" to="/nav/get_map"/>
    <remap from="rostopic://map3" to="get_map"/>
  </node>
</launch>
''')
    client = next(n for n in analysis.nodes if n.fqn == '/nav/client')
    assert client.instance is not None
    finals = {(e.entity.kind.value, e.entity.name): e.name for e in client.instance.endpoints
              if e.entity.kind.communication != 'topic'}
    assert {k: v for k, v in finals.items() if k[1] in ('go', 'go2', 'go3', 'go4', 'map', 'map2', 'map3')} == {
        ('action_client', 'go'): '/nav/goto', ('action_client', 'go2'): '/nav/goto',
        ('action_client', 'go3'): '/nav/go3', ('action_client', 'go4'): '/nav/go4',
        ('service_client', 'map'): '/nav/get_map', ('service_client', 'map2'): '/nav/get_map',
        ('service_client', 'map3'): '/nav/map3'}
    orphans = sorted((f.kind, f.endpoint) for f in _kinds(analysis, 'orphan-action-client',
                                                            'orphan-service-client'))
    assert orphans == [('orphan-action-client', '/nav/go3'), ('orphan-action-client', '/nav/go4'),
                       ('orphan-action-client', '/nav/undock'),
                       ('orphan-service-client', '/nav/lost'), ('orphan-service-client', '/nav/map3')]
    mismatches = sorted((f.endpoint, f.message) for f in _kinds(analysis, 'type-mismatch'))
    assert [m[0] for m in mismatches] == ['/nav/fib', '/nav/reset']
    assert 'test_msgs/action/NestedMessage (called by /nav/client)' in mismatches[0][1]
    assert 'std_srvs/srv/Trigger (served by /nav/server)' in mismatches[1][1]
    unused = {f.message.split("'")[1]: f for f in _kinds(analysis, 'unused-remap')}
    assert set(unused) == {'rosservice://go3:=goto', 'go4/_action/send_goal:=goto/_action/send_goal',
                           'rostopic://map3:=get_map'}
    assert unused['rosservice://go3:=goto'].diagnostic.line == 6
    internal = unused['go4/_action/send_goal:=goto/_action/send_goal']
    assert internal.diagnostic.line == 7
    assert "renames only the internal service '/nav/go4/_action/send_goal' of the action '/nav/go4'" \
        in internal.message
