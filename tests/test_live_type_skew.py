"""Version skew (nodl.live.type_skew): a real node built against one definition of
std_msgs/msg/String, checked while the index reads another (a modified copy installed in a
private prefix in front of the environment's)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from conftest import NodeProcess
from nodl.live.check import check_node
from nodl.live.describe import describe_node, render_description
from skewed_prefix import FIBONACCI_WITH_PROGRESS, STRING_WITH_REVISION, TRIGGER_WITH_ATTEMPT, VENV, skewed_prefix


@pytest.fixture(scope='module')
def typed() -> Iterator[NodeProcess]:
    node = NodeProcess('typed_node.py', 'typed', '/skew')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def definition(typed: NodeProcess, tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp('skew') / 'typed.nodl.yaml'
    path.write_text(render_description(describe_node(typed.fqn, timeout=15)), encoding='utf-8')
    return path


def _modified_std_msgs(root: Path) -> Path:
    """A prefix whose std_msgs has a String with one more field (its .msg only: no .idl)."""
    return skewed_prefix(root, {'std_msgs/msg/String': STRING_WITH_REVISION})


def test_the_same_definition_installed_is_no_skew(typed: NodeProcess, definition: Path,
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(VENV))
    result = check_node(typed.fqn, definition, timeout=15)
    assert not [d for d in result.differences if d.code in ('NODL420', 'NODL421')]
    assert result.conforms


def test_a_modified_installed_message_is_a_skew_naming_the_field(
        typed: NodeProcess, definition: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = _modified_std_msgs(tmp_path)
    monkeypatch.setenv('AMENT_PREFIX_PATH', f'{prefix}:{VENV}')
    result = check_node(typed.fqn, definition, timeout=15)
    skew = [d for d in result.differences if d.kind == 'version_skew']
    assert [d.name for d in skew] == ['/skew/chatter']
    assert not result.conforms
    message = skew[0].message
    assert "field 'revision' (int32) is in the installed definition, not in the running node's" in message
    diagnostic = skew[0]  # a coded diagnostic, placed at the declaration
    assert diagnostic.code == 'NODL420' and diagnostic.file == str(definition) and diagnostic.line > 1
    # the check can be told not to compare hashes
    assert not [d for d in check_node(typed.fqn, definition, timeout=15, types=False).differences
                if d.kind == 'version_skew']


def test_an_action_built_against_another_version_is_caught_by_its_hidden_parts(
        typed: NodeProcess, definition: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # the installed Fibonacci has one more goal field and one more feedback field
    prefix = skewed_prefix(tmp_path, {'test_msgs/action/Fibonacci': FIBONACCI_WITH_PROGRESS})
    monkeypatch.setenv('AMENT_PREFIX_PATH', f'{prefix}:{VENV}')
    result = check_node(typed.fqn, definition, timeout=15)
    skew = [d for d in result.differences if d.kind == 'version_skew']
    assert [(d.section, d.name) for d in skew] == [('action_servers', '/skew/fibonacci')]
    message = skew[0].message
    # the feedback topic's hash, with the field the node's description lacks
    assert ("its feedback (test_msgs/action/Fibonacci_FeedbackMessage) differs: "
            "test_msgs/action/Fibonacci_Feedback: field 'progress' (double) is in the installed "
            "definition, not in the running node's") in message
    # the goal service's request (the hashes of the DDS topics beneath it)
    assert 'its request (test_msgs/action/Fibonacci_SendGoal_Request) differs' in message
    assert 'Fibonacci_GetResult' not in message and 'GoalStatusArray' not in message
    diagnostic = skew[0]  # a coded diagnostic, placed at the declaration
    assert diagnostic.code == 'NODL420' and diagnostic.file == str(definition) and diagnostic.line > 1
    assert not result.conforms


def test_a_service_built_against_another_version_is_caught(
        typed: NodeProcess, definition: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = skewed_prefix(tmp_path, {'std_srvs/srv/Trigger': TRIGGER_WITH_ATTEMPT})
    monkeypatch.setenv('AMENT_PREFIX_PATH', f'{prefix}:{VENV}')
    skew = [d for d in check_node(typed.fqn, definition, timeout=15).differences
            if d.kind == 'version_skew']
    assert [(d.section, d.name) for d in skew] == [('service_servers', '/skew/trigger')]
    assert 'its request (std_srvs/srv/Trigger_Request) differs' in skew[0].message
    assert 'its response' not in skew[0].message


def test_without_hashes_for_services_the_node_s_type_descriptions_decide(
        typed: NodeProcess, definition: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """On a middleware that reports no hash beneath services, ~/get_type_description is asked
    for the service type under the installed hash: it knows only the types the node uses."""
    import nodl.live.type_skew as type_skew

    monkeypatch.setattr(type_skew, 'SERVICE_TOPIC_MIDDLEWARES', ())
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(VENV))
    result = check_node(typed.fqn, definition, timeout=15)
    assert not [d for d in result.differences if d.code in ('NODL420', 'NODL421', 'NODL422')]
    prefix = skewed_prefix(tmp_path, {'std_srvs/srv/Trigger': TRIGGER_WITH_ATTEMPT,
                                      'test_msgs/action/Fibonacci': FIBONACCI_WITH_PROGRESS})
    monkeypatch.setenv('AMENT_PREFIX_PATH', f'{prefix}:{VENV}')
    skew = {d.name: d.message for d in check_node(typed.fqn, definition, timeout=15).differences
            if d.kind == 'version_skew'}
    assert sorted(skew) == ['/skew/fibonacci', '/skew/trigger']
    assert 'its ~/get_type_description knows no std_srvs/srv/Trigger of the installed hash' in skew['/skew/trigger']
    assert 'knows no test_msgs/action/Fibonacci_SendGoal of the installed hash' in skew['/skew/fibonacci']


def test_services_that_cannot_be_compared_are_said_once(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A node that serves no ~/get_type_description, on a middleware without hashes for
    services: one info for the node, naming what is unchecked; its topics are still checked."""
    import nodl.live.type_skew as type_skew

    monkeypatch.setattr(type_skew, 'SERVICE_TOPIC_MIDDLEWARES', ())
    node = NodeProcess('typed_node.py', 'mute', '/skew', '--ros-args', '-p',
                       'start_type_description_service:=false')
    try:
        path = tmp_path / 'mute.nodl.yaml'
        path.write_text(render_description(describe_node(node.fqn, timeout=15)), encoding='utf-8')
        prefix = skewed_prefix(tmp_path, {'std_msgs/msg/String': STRING_WITH_REVISION})
        monkeypatch.setenv('AMENT_PREFIX_PATH', f'{prefix}:{VENV}')
        result = check_node(node.fqn, path, timeout=15)
    finally:
        node.stop()
    once = [d for d in result.differences if d.code == 'NODL422']
    assert len(once) == 1 and once[0].severity == 'info'
    assert '/skew/trigger' in once[0].message and '/skew/fibonacci (goal)' in once[0].message
    assert 'serves no ~/get_type_description' in once[0].message
    skew = [d for d in result.differences if d.kind == 'version_skew']
    assert [d.name for d in skew] == ['/skew/chatter']
    assert 'the node serves no description of it' in skew[0].message
