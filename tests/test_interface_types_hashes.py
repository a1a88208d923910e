"""RIHS01 hashes and type descriptions (nodl.interface_types.hashes).

The oracle is a real rclpy node in another process: the hash the middleware
reports for its endpoints, and its ~/get_type_description service, which
answers only for a type name and hash the node has registered.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from conftest import NodeProcess
from nodl.interface_types import InterfaceIndex
from nodl.interface_types.hashes import description_differences, installed_hash, type_description, type_hash

VENV = str(Path(sys.prefix))


@pytest.fixture(scope='module')
def index() -> InterfaceIndex:
    return InterfaceIndex([VENV])


@pytest.fixture(scope='module')
def typed() -> Iterator[NodeProcess]:
    node = NodeProcess('typed_node.py', 'typed', '/hashes')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def client() -> Iterator[object]:
    from ros_client import Client

    client = Client()
    try:
        yield client
    finally:
        client.node.destroy_node()
        client.context.try_shutdown()


def _reported(client, topic: str) -> str:  # type: ignore[no-untyped-def]
    infos: list = []

    def seen() -> bool:
        infos[:] = [i for i in client.node.get_publishers_info_by_topic(topic)
                    if i.node_name == 'typed']
        return bool(infos)

    assert client.spin_until(seen, 10.0), f'no publisher on {topic}'
    return str(infos[0].topic_type_hash)


@pytest.mark.parametrize('topic, type_name', [
    ('/hashes/chatter', 'std_msgs/msg/String'),
    ('/hashes/scan', 'sensor_msgs/msg/LaserScan'),
    ('/hashes/fibonacci/_action/feedback', 'test_msgs/action/Fibonacci_FeedbackMessage'),
    ('/hashes/fibonacci/_action/status', 'action_msgs/msg/GoalStatusArray'),
])
def test_computed_hash_equals_what_the_running_node_reports(typed: NodeProcess, client,  # type: ignore[no-untyped-def]
                                                            index: InterfaceIndex, topic: str,
                                                            type_name: str) -> None:
    assert type_hash(index, type_name) == _reported(client, topic)


def _describe(client, type_name: str, type_hash_text: str):  # type: ignore[no-untyped-def]
    from type_description_interfaces.srv import GetTypeDescription

    request = GetTypeDescription.Request(type_name=type_name, type_hash=type_hash_text,
                                         include_type_sources=False)
    return client.call(GetTypeDescription, '/hashes/typed/get_type_description', request)


@pytest.mark.parametrize('type_name', ['std_srvs/srv/Trigger', 'test_msgs/action/Fibonacci',
                                       'std_msgs/msg/String'])
def test_the_running_node_knows_the_service_and_action_by_the_computed_hash(
        typed: NodeProcess, client, index: InterfaceIndex, type_name: str) -> None:  # type: ignore[no-untyped-def]
    computed = type_hash(index, type_name)
    answer = _describe(client, type_name, computed)
    assert answer.successful, answer.failure_reason
    assert answer.type_description.type_description.type_name == type_name
    # a hash it does not know is refused: the check above can fail
    wrong = computed[:-4] + ('0000' if not computed.endswith('0000') else '1111')
    assert not _describe(client, type_name, wrong).successful


def test_every_installed_type_hashes_as_its_installed_json(index: InterfaceIndex) -> None:
    for package in ('std_msgs', 'std_srvs', 'test_msgs'):
        for name in index.package(package).names():  # type: ignore[union-attr]
            assert type_hash(index, name) == installed_hash(index, name), name


def test_description_lists_referenced_types_sorted(index: InterfaceIndex) -> None:
    description = type_description(index, 'sensor_msgs/msg/LaserScan')
    assert description['type_description']['type_name'] == 'sensor_msgs/msg/LaserScan'
    assert [r['type_name'] for r in description['referenced_type_descriptions']] == [
        'builtin_interfaces/msg/Time', 'std_msgs/msg/Header']


def test_differences_name_the_field() -> None:
    def described(fields: list[tuple[str, int]]) -> dict:
        return {'type_description': {'type_name': 'p/msg/T', 'fields': [
            {'name': n, 'type': {'type_id': t, 'capacity': 0, 'string_capacity': 0,
                                 'nested_type_name': ''}, 'default_value': ''}
            for n, t in fields]}, 'referenced_type_descriptions': []}

    installed = described([('data', 17), ('extra', 11)])
    running = described([('data', 17)])
    assert description_differences(installed, running) == [
        "p/msg/T: field 'extra' (double) is in the installed definition, not in the running node's"]
    changed = described([('data', 11), ('extra', 11)])
    assert description_differences(installed, changed) == [
        "p/msg/T: field 'data' is string in the installed definition, double in the running node"]
    assert description_differences(installed, installed) == []
