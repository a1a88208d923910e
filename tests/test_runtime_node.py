"""nodl.runtime: nodes built from definitions at run time, checked with real processes.

The same scenarios as the generated code (tests/test_generate_python.py): a node built by
tests/nodes/runtime_node.py conforms (nodl check), enforces every validator through a real
parameter client with the validator's words, refuses read-only and missing required
parameters, and every callback kind answers real messages, service calls and action goals.
"""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from nodl.runtime import RuntimeDefinitionError, callback
from ros_client import Client

FIXTURES = Path(__file__).parent / 'fixtures' / 'generate'
NODES = Path(__file__).parent / 'nodes'


@pytest.fixture
def client() -> Iterator[Client]:
    c = Client()
    yield c
    c.close()


def _start(ros_node: Any, kind: str, name: str, *ros_args: str) -> Any:
    extra = ['--ros-args', *ros_args] if ros_args else []
    return ros_node('runtime_node.py', name, '/rt', '--definition', str(FIXTURES / f'{kind}.nodl.yaml'),
                    '--kind', kind, *extra)


def _conforms(fqn: str, kind: str) -> None:
    from nodl.live.check import check_node
    from nodl.live.report import format_check_text

    result = check_node(fqn, FIXTURES / f'{kind}.nodl.yaml', timeout=15)
    assert result.conforms, format_check_text(result, verbose=True)


# -- what is refused before a node exists ------------------------------------------------------


def test_importing_the_runtime_does_not_import_rclpy() -> None:
    code = 'import sys, nodl.runtime; print("rclpy" in sys.modules)'
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, timeout=60,
                         cwd=Path(__file__).resolve().parent.parent)
    assert out.stdout.strip() == 'False', out.stderr


def test_a_missing_callback_is_an_error() -> None:
    from nodl.runtime import NodlNode

    with pytest.raises(RuntimeDefinitionError) as raised:
        NodlNode(FIXTURES / 'talker.nodl.yaml')
    assert "subscription '~/command' has no callback" in str(raised.value)


def test_a_callback_for_an_undeclared_entity_is_an_error() -> None:
    from nodl.runtime import NodlNode

    with pytest.raises(RuntimeDefinitionError) as raised:
        NodlNode(FIXTURES / 'talker.nodl.yaml', callbacks={'~/command': print, '~/comand': print})
    assert "'~/comand'" in str(raised.value)


def test_a_type_that_is_not_installed_is_named_before_the_node_is_created() -> None:
    from nodl.runtime import NodlNode

    with pytest.raises(RuntimeDefinitionError) as raised:
        NodlNode(FIXTURES.parent / 'runtime' / 'missing_type.nodl.yaml')
    message = str(raised.value)
    assert 'missing_type.nodl.yaml:8:7:' in message
    assert 'nodl_absent_msgs/msg/Nothing' in message and 'is not installed' in message


def test_custom_validators_and_base_are_required() -> None:
    from nodl.runtime import NodlNode

    class Everything(NodlNode):
        @callback('~/in')
        def on_in(self, msg: Any) -> None: ...

        @callback('~/trigger')
        def trigger(self, request: Any, response: Any) -> Any: ...

        @callback('~/configure')
        def configure(self, request: Any, response: Any) -> Any: ...

        @callback('~/fibonacci')
        def execute(self, goal_handle: Any) -> Any: ...

    with pytest.raises(RuntimeDefinitionError) as raised:
        Everything(FIXTURES / 'everything.nodl.yaml')
    assert "custom validator 'my_pkg::is_even'" in str(raised.value)
    with pytest.raises(RuntimeDefinitionError) as lifecycle:
        NodlNode(FIXTURES / 'managed_camera.nodl.yaml', callbacks={'~/snapshot': print})
    assert 'NodlLifecycleNode' in str(lifecycle.value)


# -- real nodes ------------------------------------------------------------------------------


def test_runtime_node_conforms_and_enforces_validators(ros_node: Any, client: Client) -> None:
    import std_msgs.msg

    node = _start(ros_node, 'talker', 'talker')
    _conforms(node.fqn, 'talker')
    chatter = client.collect(std_msgs.msg.String, '/rt/talker/chatter')
    command = client.node.create_publisher(std_msgs.msg.String, '/rt/talker/command', 5)

    def answered() -> bool:
        command.publish(std_msgs.msg.String(data='ping'))
        client.executor.spin_once(timeout_sec=0.1)
        return any(m.data == 'hello:ping' for m in chatter)
    assert client.spin_until(answered, 15), [m.data for m in chatter]
    rejected = client.set_parameter(node.fqn, 'rate', 20.0)
    assert not rejected.successful and 'must be between 0.5 and 10.0' in rejected.reason
    assert client.get_parameter(node.fqn, 'rate') == 2.0
    accepted = client.set_parameter(node.fqn, 'rate', 5.0)
    assert accepted.successful, accepted.reason
    assert client.spin_until(lambda: any(m.data == 'rate:2.0->5.0' for m in chatter), 10)


def test_runtime_lifecycle_node_publishes_only_when_active(ros_node: Any, client: Client) -> None:
    import std_msgs.msg
    import std_srvs.srv
    from lifecycle_msgs.msg import Transition
    from lifecycle_msgs.srv import ChangeState

    node = _start(ros_node, 'managed_camera', 'camera')
    frames = client.collect(std_msgs.msg.String, '/rt/camera/frames')
    read_only = client.set_parameter(node.fqn, 'device', '/dev/video9')
    assert not read_only.successful and 'read-only' in read_only.reason
    change = f'{node.fqn}/change_state'
    assert client.call(ChangeState, change, ChangeState.Request(
        transition=Transition(id=Transition.TRANSITION_CONFIGURE))).success
    client.spin_until(lambda: False, 1.5)
    assert frames == [], 'an inactive lifecycle node published'
    reply = client.call(std_srvs.srv.Trigger, '/rt/camera/snapshot', std_srvs.srv.Trigger.Request())
    assert reply.success and reply.message == '/dev/video0'
    assert client.call(ChangeState, change, ChangeState.Request(
        transition=Transition(id=Transition.TRANSITION_ACTIVATE))).success
    assert client.spin_until(lambda: bool(frames), 10), 'an active lifecycle node did not publish'
    _conforms(node.fqn, 'managed_camera')


def test_runtime_required_parameter_refuses_to_start() -> None:
    run = subprocess.run([sys.executable, str(NODES / 'runtime_node.py'), '--name', 'everything',
                          '--definition', str(FIXTURES / 'everything.nodl.yaml'), '--kind', 'everything'],
                         capture_output=True, text=True, timeout=60, cwd=NODES)
    assert run.returncode == 1, run.stdout + run.stderr
    assert ("everything: required parameter 'required_scale' (double) is not set: pass it with "
            '--ros-args -p required_scale:=VALUE or a parameter file') in run.stdout


def test_runtime_every_kind_of_callback(ros_node: Any, client: Client) -> None:
    import std_msgs.msg
    import std_srvs.srv
    import test_msgs.action
    from rclpy.action import ActionClient

    node = _start(ros_node, 'everything', 'everything', '-p', 'required_scale:=1.5')
    _conforms(node.fqn, 'everything')
    out = client.collect(std_msgs.msg.String, '/rt/everything/out')
    pub = client.node.create_publisher(std_msgs.msg.String, '/rt/everything/in', 3)

    def echoed() -> bool:
        pub.publish(std_msgs.msg.String(data='x'))
        client.executor.spin_once(timeout_sec=0.1)
        return any(m.data == 'got:x' for m in out)
    assert client.spin_until(echoed, 15)
    trigger = client.call(std_srvs.srv.Trigger, '/rt/everything/trigger', std_srvs.srv.Trigger.Request())
    assert trigger.success and trigger.message == 'fast 2 3'
    set_bool = client.call(std_srvs.srv.SetBool, '/rt/everything/configure',
                           std_srvs.srv.SetBool.Request(data=True))
    assert set_bool.success
    action = ActionClient(client.node, test_msgs.action.Fibonacci, '/rt/everything/fibonacci')
    assert client.spin_until(lambda: action.server_is_ready(), 10)
    goal = action.send_goal_async(test_msgs.action.Fibonacci.Goal(order=5))
    assert client.spin_until(goal.done, 10)
    assert goal.result().accepted
    result = goal.result().get_result_async()
    assert client.spin_until(result.done, 10)
    assert list(result.result().result.sequence) == [0, 1, 1, 2, 3, 5]
    rejected = action.send_goal_async(test_msgs.action.Fibonacci.Goal(order=99))
    assert client.spin_until(rejected.done, 10)
    assert not rejected.result().accepted
    action.destroy()
    odd = client.set_parameter(node.fqn, 'checked', 3)
    assert not odd.successful and 'must be even' in odd.reason
    for name, value, words in (('ints', [1, 1], 'must not hold any value twice'),
                               ('limit.gt', 10, 'must be greater than 10'),
                               ('gain', 0.0, 'must be greater than 0.0'),
                               ('fixed_ints', [1, 2, 3, 4], 'must hold at most 3 elements'),
                               ('name', 'nine char', 'must hold at most 8 characters')):
        answer = client.set_parameter(node.fqn, name, value)
        assert not answer.successful and words in answer.reason, answer.reason
    assert client.set_parameter(node.fqn, 'fixed_ints', [1, 2, 3]).successful


# -- a name two kinds share; local set_parameters ---------------------------------------------


def test_a_name_two_kinds_share_needs_its_kind() -> None:
    from nodl.runtime import NodlNode

    shared = FIXTURES.parent / 'runtime' / 'shared_name.nodl.yaml'
    with pytest.raises(RuntimeDefinitionError) as ambiguous:
        NodlNode(shared, callbacks={'~/reset': print})
    assert "names more than one entity: key it by kind and name (('service_server', '~/reset'), " \
        "('subscription', '~/reset'))" in str(ambiguous.value)
    with pytest.raises(RuntimeDefinitionError) as missing:
        NodlNode(shared, callbacks={('subscription', '~/reset'): print})
    assert "service server '~/reset' has no callback: pass callbacks={('service_server', '~/reset'): ...}" \
        in str(missing.value)
    assert "subscription '~/reset' has no callback" not in str(missing.value)
    with pytest.raises(RuntimeDefinitionError) as wrong_kind:
        NodlNode(shared, callbacks={('action_server', '~/reset'): print, ('topic', '~/reset'): print})
    assert "('action_server', '~/reset'), which the definition does not declare" in str(wrong_kind.value)
    assert "'topic' is not an entity kind" in str(wrong_kind.value)


def test_callbacks_keyed_by_kind_and_local_set_parameters_give_the_validators_words(client: Client) -> None:
    import std_msgs.msg
    import std_srvs.srv
    from rclpy.parameter import Parameter

    from nodl.runtime import NodlNode

    shared = FIXTURES.parent / 'runtime' / 'shared_name.nodl.yaml'
    messages: list[str] = []

    def reset(request: Any, response: Any) -> Any:
        response.success = True
        response.message = 'by request'
        return response

    node = NodlNode(shared, 'shared', namespace='/rt', context=client.context,
                    callbacks={('subscription', '~/reset'): lambda msg: messages.append(msg.data),
                               ('service_server', '~/reset'): reset})

    class Decorated(NodlNode):
        @callback('~/reset', kind='subscription')
        def on_message(self, msg: Any) -> None:
            messages.append('decorated:' + msg.data)

        @callback('~/reset', kind='service_server')
        def on_request(self, request: Any, response: Any) -> Any:
            return reset(request, response)
    decorated = Decorated(shared, 'decorated', namespace='/rt', context=client.context)
    try:
        client.executor.add_node(node)
        client.executor.add_node(decorated)
        assert node.endpoint('~/reset', 'subscription') is not node.endpoint('~/reset', 'service_server')
        pub = client.node.create_publisher(std_msgs.msg.String, '/rt/shared/reset', 1)
        dpub = client.node.create_publisher(std_msgs.msg.String, '/rt/decorated/reset', 1)

        def received() -> bool:
            pub.publish(std_msgs.msg.String(data='m'))
            dpub.publish(std_msgs.msg.String(data='m'))
            client.executor.spin_once(timeout_sec=0.1)
            return 'm' in messages and 'decorated:m' in messages
        assert client.spin_until(received, 15), messages
        for fqn in ('/rt/shared', '/rt/decorated'):
            answer = client.call(std_srvs.srv.Trigger, f'{fqn}/reset', std_srvs.srv.Trigger.Request())
            assert answer.success and answer.message == 'by request'
        # a local call gets the validator's words too (not rclpy's range message), value unchanged
        [local] = node.set_parameters([Parameter('rate', value=20.0)])
        assert not local.successful and 'must be between 0.5 and 10.0' in local.reason, local.reason
        assert node.params.rate == 2.0
        [fine] = node.set_parameters([Parameter('rate', value=4.0)])
        assert fine.successful and node.params.rate == 4.0
    finally:
        for n in (node, decorated):
            client.executor.remove_node(n)
            n.destroy_node()


def test_a_missing_definition_file_is_named_in_words(tmp_path) -> None:  # type: ignore[no-untyped-def]
    from nodl.runtime import NodlNode

    missing = tmp_path / 'absent.nodl.yaml'
    with pytest.raises(RuntimeDefinitionError) as raised:
        NodlNode(missing)
    message = str(raised.value)
    assert '[Errno' not in message
    assert message.startswith(f'{missing}: ') and 'no such file' in message.lower()
