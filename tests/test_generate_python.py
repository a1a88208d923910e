"""nodl generate --language python: golden output, lint and types, and generated nodes run for real.

The generated module is imported by a real rclpy process (tests/nodes/generated_node.py
subclasses it as a user would); this process talks to it through real topics,
services, actions and parameter services, and nodl check says it conforms.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from nodl.generate import (
    GenerateOptions,
    default_class_name,
    default_node_name,
    write_files,
)
from nodl.generate.python import generate_python
from nodl.system import resolve_node
from nodl.writing import mark
from ros_client import Client

FIXTURES = Path(__file__).parent / 'fixtures' / 'generate'
KINDS = ('talker', 'managed_camera', 'everything')
VENV_BIN = Path(sys.executable).parent


def _generate(kind: str) -> str:
    path = FIXTURES / f'{kind}.nodl.yaml'
    options = GenerateOptions(default_class_name(str(path)), default_node_name(str(path)))
    [generated] = generate_python(resolve_node(path), options)
    assert generated.path == f'{kind}_base.py'
    return generated.text


@pytest.fixture(scope='module')
def module_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp('generated')
    for kind in KINDS:
        (out / f'{kind}_base.py').write_text(_generate(kind), encoding='utf-8')
    return out


# -- the text -------------------------------------------------------------------------------


@pytest.mark.parametrize('kind', KINDS)
def test_golden(kind: str, golden: Any) -> None:
    golden.check(_generate(kind), FIXTURES / 'python' / f'{kind}_base.py')


@pytest.mark.parametrize('kind', KINDS)
def test_regenerating_is_byte_identical_and_leaves_files_alone(kind: str, tmp_path: Path) -> None:
    path = FIXTURES / f'{kind}.nodl.yaml'
    options = GenerateOptions(default_class_name(str(path)), default_node_name(str(path)))
    files = generate_python(resolve_node(path), options)
    assert write_files(files, str(tmp_path)) == [str(tmp_path / f'{kind}_base.py')]
    stamp = (tmp_path / f'{kind}_base.py').stat().st_mtime_ns
    again = generate_python(resolve_node(path), options)
    assert again == files
    assert write_files(again, str(tmp_path)) == []
    assert write_files(again, str(tmp_path), check=True) == []
    assert (tmp_path / f'{kind}_base.py').stat().st_mtime_ns == stamp


def test_description_is_escaped_and_names_are_mapped() -> None:
    text = _generate('everything')
    compile(text, 'everything_base.py', 'exec')
    # the value unchanged; a backslash only as \\u (else D301), ''' quotes around \"\"\" (else D300)
    assert '\'\'\'\nThe generated base of the everything node: EverythingBase.\n\n' in text
    assert 'description with \\u005c and \"\"\" in it.\n\'\'\'\n' in text
    # '~/out' and 'out' both sanitise to out: the exact one keeps it, the mapping says so
    assert "#   publisher 'out' (std_msgs/msg/Int32) -> self.pub_out\n" in text
    assert "#   publisher '~/out' (std_msgs/msg/String) -> self.pub_out_2\n" in text
    # a service called configure must not override the lifecycle hook name
    assert 'def on_configure_2(' in text
    # a keyword parameter name becomes a field with a trailing underscore
    assert 'self.class_: int = 3' in text


def test_ruff_and_mypy_pass_on_generated_code(module_dir: Path) -> None:
    ruff = shutil.which('ruff', path=str(VENV_BIN)) or shutil.which('ruff')
    assert ruff, 'ruff is part of the test extra'
    # 99: ament_flake8's limit (the lint test of an ament_python package checks generated files too);
    # imports sorted by module, `import` and `from` mixed: flake8-import-order's google style, which
    # ament_flake8 configures (the real ament_flake8 runs in tests/test_scaffold.py)
    lint = subprocess.run([ruff, 'check', '--isolated', '--no-cache', '--select', 'E,F,W,I,B,N',
                           '--config', 'lint.isort.force-sort-within-sections = true',
                           '--line-length', '99', str(module_dir)],
                          capture_output=True, text=True, timeout=120)
    assert lint.returncode == 0, lint.stdout + lint.stderr
    types = subprocess.run([sys.executable, '-m', 'mypy', '--strict', '--ignore-missing-imports',
                            '--no-incremental', '--cache-dir', '/dev/null', str(module_dir)],
                           capture_output=True, text=True, timeout=300)
    assert types.returncode == 0, types.stdout + types.stderr


def test_cli_generate_and_check(tmp_path: Path) -> None:
    definition = FIXTURES / 'talker.nodl.yaml'
    run = [sys.executable, '-m', 'nodl', 'generate', str(definition), '--language', 'python',
           '-o', str(tmp_path)]
    first = subprocess.run(run, capture_output=True, text=True, timeout=60)
    assert first.returncode == 0, first.stderr
    written = (tmp_path / 'talker_base.py').read_text()
    assert written == mark(_generate('talker'), '#')  # the marker first, then the module
    assert subprocess.run(run + ['--check'], capture_output=True, timeout=60).returncode == 0
    (tmp_path / 'talker_base.py').write_text(written + '# an edit\n')
    stale = subprocess.run(run + ['--check'], capture_output=True, text=True, timeout=60)
    assert stale.returncode == 1
    assert 'talker_base.py: stale or missing' in stale.stderr
    refused = subprocess.run(run, capture_output=True, text=True, timeout=60)
    assert refused.returncode == 2 and 'Traceback' not in refused.stderr
    assert refused.stderr.splitlines()[-1] == (
        f'{tmp_path / "talker_base.py"}: error: the file was edited since nodl wrote it (its text no '
        'longer matches its nodl marker): not replaced; keep your changes elsewhere and give --force '
        'to replace it [NODL032]')
    assert (tmp_path / 'talker_base.py').read_text() == written + '# an edit\n'
    forced = subprocess.run(run + ['--force'], capture_output=True, text=True, timeout=60)
    assert forced.returncode == 0 and (tmp_path / 'talker_base.py').read_text() == written
    bad = subprocess.run(run + ['--node-name', '../talker'], capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and '[NODL707]' in bad.stderr and not (tmp_path.parent / 'talker_base.py').exists()
    unknown = subprocess.run(run[:-4] + ['--language', 'cobol', '-o', str(tmp_path)],
                             capture_output=True, text=True, timeout=60)
    assert unknown.returncode == 2
    assert "no generator for language 'cobol'" in unknown.stderr
    assert 'Traceback' not in unknown.stderr


# -- the generated nodes, for real --------------------------------------------------------------


@pytest.fixture
def client() -> Iterator[Client]:
    c = Client()
    yield c
    c.close()


def _start(ros_node: Any, module_dir: Path, kind: str, name: str, *ros_args: str) -> Any:
    extra = ['--ros-args', *ros_args] if ros_args else []
    return ros_node('generated_node.py', name, '/gen', '--module-dir', str(module_dir), '--kind', kind,
                    *extra)


def _conforms(fqn: str, kind: str) -> None:
    from nodl.live.check import check_node
    from nodl.live.report import format_check_text

    result = check_node(fqn, FIXTURES / f'{kind}.nodl.yaml', timeout=15)
    assert result.conforms, format_check_text(result, verbose=True)


def test_plain_node_runs_conforms_and_enforces_validators(ros_node: Any, module_dir: Path,
                                                          client: Client) -> None:
    import std_msgs.msg

    node = _start(ros_node, module_dir, 'talker', 'talker')
    _conforms(node.fqn, 'talker')
    chatter = client.collect(std_msgs.msg.String, '/gen/talker/chatter')
    command = client.node.create_publisher(std_msgs.msg.String, '/gen/talker/command', 5)
    assert client.spin_until(lambda: command.get_subscription_count() > 0)

    def answered() -> bool:
        command.publish(std_msgs.msg.String(data='ping'))
        client.executor.spin_once(timeout_sec=0.1)
        return any(m.data == 'hello:ping' for m in chatter)
    assert client.spin_until(answered, 15), [m.data for m in chatter]
    # outside the bounds: rejected with the validator's own words
    rejected = client.set_parameter(node.fqn, 'rate', 20.0)
    assert not rejected.successful
    assert 'must be between 0.5 and 10.0' in rejected.reason
    assert client.get_parameter(node.fqn, 'rate') == 2.0
    # of another type: rejected (an integer is not a double)
    assert not client.set_parameter(node.fqn, 'rate', 5).successful
    # inside: accepted, committed and visible in the params snapshot (the on-change hook saw it)
    accepted = client.set_parameter(node.fqn, 'rate', 5.0)
    assert accepted.successful, accepted.reason
    assert client.spin_until(lambda: any(m.data == 'rate:2.0->5.0' for m in chatter), 10)
    assert not client.set_parameter(node.fqn, 'greeting', '').successful


def test_lifecycle_node_publishes_only_when_active(ros_node: Any, module_dir: Path, client: Client) -> None:
    import std_msgs.msg
    import std_srvs.srv
    from lifecycle_msgs.msg import Transition
    from lifecycle_msgs.srv import ChangeState

    node = _start(ros_node, module_dir, 'managed_camera', 'camera')
    frames = client.collect(std_msgs.msg.String, '/gen/camera/frames')
    read_only = client.set_parameter(node.fqn, 'device', '/dev/video9')
    assert not read_only.successful
    assert 'read-only' in read_only.reason
    change = f'{node.fqn}/change_state'
    assert client.call(ChangeState, change, ChangeState.Request(
        transition=Transition(id=Transition.TRANSITION_CONFIGURE))).success
    client.spin_until(lambda: False, 1.5)
    assert frames == [], 'an inactive lifecycle node published'
    reply = client.call(std_srvs.srv.Trigger, '/gen/camera/snapshot', std_srvs.srv.Trigger.Request())
    assert reply.success and reply.message == '/dev/video0'
    assert client.call(ChangeState, change, ChangeState.Request(
        transition=Transition(id=Transition.TRANSITION_ACTIVATE))).success
    assert client.spin_until(lambda: bool(frames), 10), 'an active lifecycle node did not publish'
    assert frames[0].data == 'frame at 30 fps'
    _conforms(node.fqn, 'managed_camera')
    bad = client.set_parameter(node.fqn, 'fps', 500)
    assert not bad.successful and 'must be between 1 and 120' in bad.reason


def test_required_parameter_missing_refuses_to_start(module_dir: Path) -> None:
    nodes = Path(__file__).parent / 'nodes'
    run = subprocess.run([sys.executable, str(nodes / 'generated_node.py'), '--name', 'everything',
                          '--module-dir', str(module_dir), '--kind', 'everything'],
                         capture_output=True, text=True, timeout=60, cwd=nodes)
    assert run.returncode == 1, run.stdout + run.stderr
    assert ("everything: required parameter 'required_scale' (double) is not set: pass it with "
            '--ros-args -p required_scale:=VALUE or a parameter file') in run.stdout
    invalid = subprocess.run([sys.executable, str(nodes / 'generated_node.py'), '--name', 'everything',
                              '--module-dir', str(module_dir), '--kind', 'everything', '--ros-args',
                              '-p', 'required_scale:=1.0', '-p', 'mode:=medium'],
                             capture_output=True, text=True, timeout=60, cwd=nodes)
    assert invalid.returncode == 1, invalid.stdout + invalid.stderr
    assert "parameter 'mode' = 'medium': must be one of 'fast' or 'slow'" in invalid.stdout


def test_every_kind_of_callback(ros_node: Any, module_dir: Path, client: Client) -> None:
    import std_msgs.msg
    import std_srvs.srv
    import test_msgs.action
    from action_msgs.msg import GoalStatus
    from rclpy.action import ActionClient

    node = _start(ros_node, module_dir, 'everything', 'everything', '-p', 'required_scale:=1.5')
    _conforms(node.fqn, 'everything')
    assert client.get_parameter(node.fqn, 'required_scale') == 1.5
    out = client.collect(std_msgs.msg.String, '/gen/everything/out')
    pub = client.node.create_publisher(std_msgs.msg.String, '/gen/everything/in', 3)

    def echoed() -> bool:
        pub.publish(std_msgs.msg.String(data='x'))
        client.executor.spin_once(timeout_sec=0.1)
        return any(m.data == 'got:x' for m in out)
    assert client.spin_until(echoed, 15)
    trigger = client.call(std_srvs.srv.Trigger, '/gen/everything/trigger', std_srvs.srv.Trigger.Request())
    assert trigger.success and trigger.message == 'fast 2 3'
    set_bool = client.call(std_srvs.srv.SetBool, '/gen/everything/configure',
                           std_srvs.srv.SetBool.Request(data=True))
    assert set_bool.success and set_bool.message == 'set'
    action = ActionClient(client.node, test_msgs.action.Fibonacci, '/gen/everything/fibonacci')
    assert client.spin_until(lambda: action.server_is_ready(), 10)
    goal = action.send_goal_async(test_msgs.action.Fibonacci.Goal(order=5))
    assert client.spin_until(goal.done, 10)
    handle = goal.result()
    assert handle.accepted
    result = handle.get_result_async()
    assert client.spin_until(result.done, 10)
    assert list(result.result().result.sequence) == [0, 1, 1, 2, 3, 5]
    rejected = action.send_goal_async(test_msgs.action.Fibonacci.Goal(order=99))
    assert client.spin_until(rejected.done, 10)
    assert not rejected.result().accepted
    # the cancel callback: a goal that runs until it is cancelled
    running = action.send_goal_async(test_msgs.action.Fibonacci.Goal(order=42))
    assert client.spin_until(running.done, 10) and running.result().accepted
    cancel = running.result().cancel_goal_async()
    assert client.spin_until(cancel.done, 10)
    assert len(cancel.result().goals_canceling) == 1
    cancelled = running.result().get_result_async()
    assert client.spin_until(cancelled.done, 10)
    assert cancelled.result().status == GoalStatus.STATUS_CANCELED
    assert list(cancelled.result().result.sequence) == [42]
    action.destroy()
    # the custom validator is called through the user's hook
    odd = client.set_parameter(node.fqn, 'checked', 3)
    assert not odd.successful and 'must be even' in odd.reason
    assert client.set_parameter(node.fqn, 'checked', 6).successful
    for name, value, words in (('ints', [1, 1], 'must not hold any value twice'),
                               ('strings', ['a', 'z'], 'may only hold'),
                               ('doubles', [0.5, 3.0], 'every element must be between 0.0 and 2.0'),
                               ('limit.gt', 10, 'must be greater than 10'),
                               ('gain', 0.0, 'must be greater than 0.0'),
                               # fixed sizes are maximum lengths, as for a parameter file
                               ('fixed_ints', [1, 2, 3, 4], 'must hold at most 3 elements'),
                               ('name', 'nine char', 'must hold at most 8 characters')):
        answer = client.set_parameter(node.fqn, name, value)
        assert not answer.successful, name
        assert words in answer.reason, answer.reason
    assert client.set_parameter(node.fqn, 'fixed_ints', [1, 2, 3]).successful
    assert client.set_parameter(node.fqn, 'bytes', [b'\x07']).successful


# -- parameters of a generated node, in this process (a real rclpy node, real parameter services) --


@pytest.fixture
def talker_class(module_dir: Path) -> Iterator[Any]:
    import importlib

    sys.path.insert(0, str(module_dir))
    try:
        module = importlib.import_module('talker_base')

        class Talker(module.TalkerBase):  # type: ignore[misc, name-defined]
            def on_command(self, msg: Any) -> None:
                pass
        yield Talker
    finally:
        sys.path.remove(str(module_dir))
        sys.modules.pop('talker_base', None)


def test_parameters_descriptors_batches_and_a_later_rejecting_callback(talker_class: Any,
                                                                      client: Client) -> None:
    from rcl_interfaces.msg import SetParametersResult
    from rcl_interfaces.srv import DescribeParameters, SetParametersAtomically
    from rclpy.parameter import Parameter

    changes: list[tuple[float, float]] = []

    class Observed(talker_class):  # type: ignore[misc, valid-type]
        def on_parameters_changed(self, old: Any, new: Any) -> None:
            changes.append((old.rate, new.rate))

    node = Observed('observed', namespace='/gen', context=client.context)
    client.executor.add_node(node)
    try:
        # descriptors as `ros2 param describe` shows them, through a real parameter client
        described = client.call(DescribeParameters, '/gen/observed/describe_parameters',
                                DescribeParameters.Request(names=['rate', 'greeting']))
        rate, greeting = described.descriptors
        assert rate.description == 'Greetings per second.'
        assert [(r.from_value, r.to_value) for r in rate.floating_point_range] == [(0.5, 10.0)]
        assert rate.additional_constraints == 'must be between 0.5 and 10.0'
        assert greeting.description == 'The text of each greeting.'
        assert greeting.additional_constraints == 'must not be empty'
        # a local call gets the validator's words too (rclpy alone would give its range message)
        [local] = node.set_parameters([Parameter('rate', value=20.0)])
        assert not local.successful and 'must be between 0.5 and 10.0' in local.reason, local.reason
        # the whole batch is rejected: the valid rate is not set either
        batch = [Parameter('rate', value=4.0).to_parameter_msg(), Parameter('greeting', value='').to_parameter_msg()]
        answer = client.call(SetParametersAtomically, '/gen/observed/set_parameters_atomically',
                             SetParametersAtomically.Request(parameters=batch)).result
        assert not answer.successful and "parameter 'greeting' = '': " in answer.reason, answer.reason
        assert node.get_parameter('rate').value == 2.0 and node.params.rate == 2.0 and changes == []
        # is_old / try_update and the on-change hook
        first = node.params
        assert not node.is_old(first) and node.try_update(first) is first
        [ok] = node.set_parameters([Parameter('rate', value=4.0)])
        assert ok.successful and node.params.rate == 4.0 and changes == [(2.0, 4.0)]
        assert node.is_old(first) and node.try_update(first) is node.params and first.rate == 2.0
        # a later on-set callback that rejects: the snapshot is not committed (no stale value)
        node.add_on_set_parameters_callback(
            lambda params: SetParametersResult(successful=False, reason='vetoed by the user'))
        [vetoed] = node.set_parameters([Parameter('rate', value=6.0)])
        assert not vetoed.successful and vetoed.reason == 'vetoed by the user'
        assert node.get_parameter('rate').value == 4.0 and node.params.rate == 4.0
        assert not node.is_old(node.params) and changes == [(2.0, 4.0)]
    finally:
        client.executor.remove_node(node)
        node.destroy_node()


def test_generated_code_runs_without_the_toolkit(module_dir: Path, tmp_path: Path) -> None:
    """No runtime dependency: the generated base imports and runs with nodl unimportable."""
    code = ('import sys\n'
            'sys.modules["nodl"] = None  # any import of the toolkit fails\n'
            f'sys.path.insert(0, {str(module_dir)!r})\n'
            'import rclpy, everything_base, talker_base, managed_camera_base\n'
            'class T(talker_base.TalkerBase):\n'
            '    def on_command(self, msg): pass\n'
            'rclpy.init()\n'
            'node = T()\n'
            'print(node.get_name(), node.params.rate, [m for m, v in sys.modules.items() if v and "nodl" in m])\n'
            'node.destroy_node()\n'
            'rclpy.shutdown()\n')
    run = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, timeout=60,
                         cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.split() == ['talker', '2.0', '[]']


def test_cli_generate_package_executable(tmp_path: Path) -> None:
    """``nodl generate PACKAGE EXECUTABLE``: the registered definition, names from the executable."""
    import os

    prefix = Path(__file__).parent / 'fixtures' / 'index' / 'first'
    env = {**os.environ, 'AMENT_PREFIX_PATH': str(prefix)}
    run = [sys.executable, '-m', 'nodl', 'generate', 'alpha', 'talker', '-o', str(tmp_path)]
    for language in ('python', 'cpp'):
        done = subprocess.run(run + ['--language', language], capture_output=True, text=True,
                              timeout=60, env=env, cwd=tmp_path)
        assert done.returncode == 0, done.stderr
    text = (tmp_path / 'talker_base.py').read_text(encoding='utf-8')
    assert 'from talker.nodl.yaml' in text and 'class TalkerBase(Node' in text
    assert "_PARAMETER_NAMES = frozenset({'period'})" in text
    assert 'class TalkerBase : public rclcpp::Node' in (tmp_path / 'talker_base.hpp').read_text(encoding='utf-8')
    check = subprocess.run(run + ['--language', 'python', '--check'], capture_output=True, timeout=60,
                           env=env, cwd=tmp_path)
    assert check.returncode == 0
    unknown = subprocess.run([*run[:-4], 'alpha', 'talkr', '--language', 'python', '-o', str(tmp_path)],
                             capture_output=True, text=True, timeout=60, env=env, cwd=tmp_path)
    assert unknown.returncode == 1
    assert "package 'alpha' registers no node definition for 'talkr' (it has: inline, talker) [NODL306]" \
        in unknown.stderr
    assert 'Traceback' not in unknown.stderr


def test_lines_stay_within_ament_flake8s_limit(tmp_path: Path) -> None:
    """Long descriptions (quotes, backslashes) are wrapped (a word longer than a line stands
    alone, which the linters allow); a line that holds long data from the definition says
    ``# noqa: E501``; the module still compiles and ruff passes at 99 columns."""
    long_words = ' '.join(['a "quoted" \\ word', '"""', 'x' * 120] * 8)
    definition = tmp_path / 'wide_node.nodl.yaml'
    definition.write_text(
        'nodl_version: 2\nbase: node\nmain:\n  nodl_version: 2\n'
        f'  description: {json.dumps(long_words)}\n'
        '  parameters:\n'
        '    a_rather_long_parameter_name_for_choices:\n'
        '      type: string\n      default_value: first_choice_of_many\n'
        f'      description: {json.dumps(long_words)}\n'
        '      validation: {one_of<>: [[first_choice_of_many, second_choice_of_many, third_choice]]}\n'
        '  publishers:\n'
        '    - name: ~/a_very_long_topic_name_that_goes_on_and_on_and_on_and_on\n'
        '      type: std_msgs/msg/String\n'
        f'      description: {json.dumps(long_words)}\n'
        '      qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}\n', encoding='utf-8')
    options = GenerateOptions(default_class_name(str(definition)), default_node_name(str(definition)))
    [generated] = generate_python(resolve_node(definition), options)
    compile(generated.text, generated.path, 'exec')
    long_lines = [line for line in generated.text.splitlines() if len(line) > 99]
    # flake8 and ruff let a line that is one word (in a docstring) be long
    marked = [line for line in long_lines if len(line.split()) > 1]
    assert marked and all(line.endswith('  # noqa: E501') for line in marked), marked
    (tmp_path / generated.path).write_text(generated.text, encoding='utf-8')
    ruff = shutil.which('ruff', path=str(VENV_BIN)) or shutil.which('ruff')
    assert ruff
    lint = subprocess.run([ruff, 'check', '--isolated', '--no-cache', '--select', 'E,W',
                           '--line-length', '99', str(tmp_path / generated.path)],
                          capture_output=True, text=True, timeout=120)
    assert lint.returncode == 0, lint.stdout + lint.stderr


def test_parameter_names_python_would_mangle_work_in_a_running_node(client: Client, tmp_path: Path) -> None:
    """__x, __x__, _Class__x, a.__b, __init__, __slots__: inside a class Python mangles
    ``self.__x`` to ``self._Class__x``; the generated node still declares each parameter under
    its own name and reads it into its own field, in a real rclpy node."""
    import importlib

    from rclpy.parameter import Parameter

    path = FIXTURES / 'mangled.nodl.yaml'
    [generated] = generate_python(resolve_node(path), GenerateOptions('Mangled', 'mangled'))
    (tmp_path / generated.path).write_text(generated.text, encoding='utf-8')
    sys.path.insert(0, str(tmp_path))
    try:
        module = importlib.import_module(generated.path[:-3])
        node = module.MangledBase('mangled', namespace='/gen', context=client.context)
        try:
            names = {'__x', '__x__', '_Class__x', 'a.__b', '__init__', '__slots__'}
            assert names <= set(node._parameters)
            params = node.params
            assert (params.x, params.x_2, params.class_x, params.a.b, params.init, params.slots) == (
                1, 2, 3, 'four', True, 6.5)
            results = node.set_parameters([Parameter('__x', value=10), Parameter('__x__', value=20),
                                           Parameter('a.__b', value='five')])
            assert all(r.successful for r in results)
            assert (node.params.x, node.params.x_2, node.params.a.b) == (10, 20, 'five')
            assert node.get_parameter('__x').value == 10
        finally:
            node.destroy_node()
    finally:
        sys.path.remove(str(tmp_path))
        sys.modules.pop(generated.path[:-3], None)
