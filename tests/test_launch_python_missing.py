"""Modules a Python launch file imports that are not installed here
(nodl.launch.python_missing): placeholders, one warning per module, and the analysis
goes on; what only the running launch knows stays a run-time value."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

from nodl.launch import load_launch


def _write(tmp_path: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding='utf-8')
    return tmp_path / next(iter(files))


MISSING = Path(__file__).parent / 'fixtures' / 'launch' / 'missing_modules'
ANALYSIS_PREFIX = Path(__file__).parent / 'fixtures' / 'analysis' / 'prefix'


def test_modules_not_installed_here_are_placeholders_and_the_analysis_goes_on() -> None:
    """xacro and nav2_common are not installed here: one warning per module at its import,
    the robot_description from xacro a run-time value, the registered node analysed."""
    import importlib.util

    from nodl.analysis import analyse_launch
    from nodl.launch import parameter_overrides
    from nodl.launch.params import RuntimeValue

    path_before, finders_before = list(sys.path), list(sys.meta_path)
    result = load_launch(MISSING / 'robot.launch.py', {}, prefixes=[str(ANALYSIS_PREFIX)])
    assert [(d.code, d.severity.value, d.line) for d in result.diagnostics] == [
        ('NODL513', 'warning', 5), ('NODL513', 'warning', 10), ('NODL513', 'warning', 21),
        ('NODL513', 'warning', 27)]
    xacro, nav2, description, rewritten = (d.message for d in result.diagnostics)
    assert xacro.startswith("the Python launch file imports 'xacro', which is not installed here")
    assert 'known only when the launch runs' in xacro
    assert "imports 'nav2_common'" in nav2  # one warning for the module, however many names
    assert description.startswith("parameter 'robot_description': the value of xacro.process_file(...)"
                                  ".toxml() ('xacro' is not installed here) is known only when")
    assert rewritten.startswith('parameters entry: the value of nav2_common.launch.RewrittenYaml(...)')
    assert rewritten.endswith('the node is analysed without the parameters this entry gives (the known '
                              'ones are checked; no parameter is reported missing for it)')
    publisher, lidar, rewritten_lidar = result.nodes
    assert rewritten_lidar.fqn == '/lidar_rewritten' and rewritten_lidar.parameters == []
    assert not rewritten_lidar.parameters_complete
    values = {k: v.value for k, v in parameter_overrides(publisher).items()}
    assert isinstance(values['robot_description'], RuntimeValue) and values['publish_frequency'] == 20.0
    assert (lidar.package, lidar.fqn) == ('sensors', '/lidar')
    # the stubs do not outlive the evaluation
    assert 'xacro' not in sys.modules and not [m for m in sys.modules if m.startswith('nav2_common')]
    assert importlib.util.find_spec('xacro') is None
    assert sys.path == path_before and sys.meta_path == finders_before

    analysis = analyse_launch(MISSING / 'robot.launch.py', prefixes=[str(ANALYSIS_PREFIX)])
    assert not analysis.unreadable  # warnings: exit status 0, not 2
    analysed = {n.created_name: n for n in analysis.nodes}
    assert analysed['lidar'].match.resolved is not None  # the registered definition is used
    assert analysed['lidar'].instance is not None and analysed['robot_state_publisher'].instance is None


def test_a_module_that_exists_but_raises_on_import_is_still_an_error() -> None:
    result = load_launch(MISSING / 'raises.launch.py', {},
                         prefixes=[str(ANALYSIS_PREFIX), str(MISSING / 'prefix')])
    (problem,) = result.diagnostics
    assert (problem.code, problem.severity.value, problem.line) == ('NODL516', 'error', 3)
    assert 'RuntimeError: this helper needs a robot attached' in problem.message
    assert 'raises_on_import' not in sys.modules


def test_missing_submodules_of_installed_packages_and_relative_imports_stay_errors(tmp_path: Path) -> None:
    submodule = _write(tmp_path, {'a.launch.py': 'import json.no_such_part\n'})
    (problem,) = load_launch(submodule, {}).diagnostics
    assert problem.code == 'NODL516' and "imports 'json.no_such_part'" in problem.message
    relative = _write(tmp_path, {'b.launch.py': 'from .helpers import x\n'})
    (problem,) = load_launch(relative, {}).diagnostics
    assert problem.code == 'NODL516' and 'relative import' in problem.message


def test_python_operations_on_placeholders_go_on(tmp_path: Path) -> None:
    """str(), f-strings, +, os.path.join, iteration, truth, comparisons, in, indexing, with,
    a class derived from a placeholder: the evaluation goes on; a number cannot be known."""
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        import os
        import importlib.util
        from launch import LaunchDescription
        from launch_ros.actions import Node
        import helpers.config as config
        from helpers import Tool

        class Mine(Tool):
            def execute(self, context):
                raise RuntimeError('not called: the walk does not run it')

        def generate_launch_description():
            value = config.load('robot.yaml')['robot']
            text = str(value)
            assert text == f'{value}' == '<helpers.config.load(...)[...]: known at run time>'
            joined = os.path.join('/opt', value, 'x.yaml')
            assert joined == '/opt/<helpers.config.load(...)[...]: known at run time>/x.yaml'
            assert list(value) == [] and len(value) == 0 and value and 'a' not in value
            assert not value == 'a' and value != 'a' and not value < 1 and not isinstance(1, Tool)
            with config.lock() as held:
                pass
            assert importlib.util.find_spec('more_helpers') is None  # asking is not importing
            return LaunchDescription([
                Node(package='p', executable='e', name='a', parameters=[
                    {'path': joined, 'name': 'robot_' + value, 'plain': f'{value}!', 'n': 1}]),
                Node(package='p', executable='e', name=value),
                Node(package='p', executable='e', name='b', condition=config.enabled),
                Node(package='p', executable='e', name='c', parameters=[os.path.join('/x', value)]),
                Mine(1, name='m'),
                *config.more_nodes(),
            ] + config.tail())
        ''')})
    result = load_launch(main, {})
    found = [(d.code, d.line, d.message.split(' (')[0]) for d in result.diagnostics]
    assert found == [
        ('NODL513', 5, "the Python launch file imports 'helpers', which is not installed here"),
        ('NODL512', 18, 'helpers.config.load(...)[...] is iterated, but its items are known only when the '
                        'launch runs'),
        # *config.more_nodes(): the interpreter places the unpacking at the list it is in
        ('NODL512', 23, 'helpers.config.more_nodes() is iterated, but its items are known only when the '
                        'launch runs'),
        ('NODL513', 24, "parameter 'path': the value of a text with helpers.config.load(...)[...]"),
        ('NODL513', 24, "parameter 'name': the value of a text with helpers.config.load(...)[...]"),
        ('NODL513', 24, "parameter 'plain': the value of a text with helpers.config.load(...)[...]"),
        ('NODL513', 26, 'the value of helpers.config.load(...)[...]'),
        ('NODL513', 27, 'the value of helpers.config.enabled'),
        ('NODL513', 28, 'parameters entry: the value of a text with helpers.config.load(...)[...]'),
        ('NODL512', 29, 'Mine(...)'),
        ('NODL512', 31, 'helpers.config.tail() cannot be evaluated without running the launch')]
    assert 'this node is missing from the analysis' in result.diagnostics[6].message
    assert 'the node is analysed without the parameters' in result.diagnostics[8].message
    assert [node.fqn for node in result.nodes] == ['/a', '/c']

    number = _write(tmp_path, {'n.launch.py': 'import helpers\n\nrate = float(helpers.RATE)\n'})
    warning, problem = load_launch(number, {}).diagnostics
    assert (warning.code, problem.code, problem.line) == ('NODL513', 'NODL516', 3)
    assert "helpers.RATE comes from 'helpers', which is not installed here" in problem.message


def test_actions_from_missing_modules_are_said_not_dropped(tmp_path: Path) -> None:
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        from launch.actions import GroupAction, IncludeLaunchDescription, RegisterEventHandler
        from launch_ros.actions import ComposableNodeContainer, Node
        from ros_gz_bridge.actions import RosGzBridge
        from robot_helpers import make

        def generate_launch_description():
            return LaunchDescription([
                RosGzBridge(bridge_name='bridge', config_file='bridge.yaml'),
                GroupAction(make.group()),
                IncludeLaunchDescription(make.source()),
                RegisterEventHandler(make.handler()),
                ComposableNodeContainer(name='c', namespace='', package='rclcpp_components',
                                        executable='component_container',
                                        composable_node_descriptions=[make.component()]),
                Node(package='p', executable='e', name='n', parameters=make.parameters()),
            ])
        ''')})
    result = load_launch(main, {})
    assert [(d.code, d.line) for d in result.diagnostics] == [
        ('NODL513', 4), ('NODL513', 5), ('NODL512', 9), ('NODL512', 10), ('NODL513', 11), ('NODL512', 12),
        ('NODL513', 15), ('NODL513', 16)]
    bridge = result.diagnostics[2].message
    assert bridge.startswith('ros_gz_bridge.actions.RosGzBridge(...) cannot be evaluated without running')
    assert 'the composable node it describes is missing' in result.diagnostics[6].message
    assert 'the node is analysed without the parameters' in result.diagnostics[7].message
    assert [n.kind for n in result.nodes] == ['container', 'node']
    returned = _write(tmp_path, {'r.launch.py': textwrap.dedent('''\
        from moveit_configs_utils import MoveItConfigsBuilder
        from moveit_configs_utils.launches import generate_demo_launch

        def generate_launch_description():
            return generate_demo_launch(MoveItConfigsBuilder('arm').to_moveit_configs())
        ''')})
    warning, demo = load_launch(returned, {}).diagnostics
    assert (warning.code, warning.line, demo.code, demo.line) == ('NODL513', 1, 'NODL512', 5)
    assert demo.message.startswith('moveit_configs_utils.launches.generate_demo_launch(...) cannot be')


def test_stubs_do_not_leak_into_the_next_evaluation(tmp_path: Path) -> None:
    first = _write(tmp_path, {'a.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        import xacro
        def generate_launch_description():
            return LaunchDescription([])
        ''')})
    second = _write(tmp_path, {'b.launch.py': textwrap.dedent('''\
        import sys
        from launch import LaunchDescription
        assert 'xacro' not in sys.modules
        try:
            import xacro
        finally:
            assert 'xacro' in sys.modules
        def generate_launch_description():
            return LaunchDescription([])
        ''')})
    assert [(d.code, d.line) for d in load_launch(first, {}).diagnostics] == [('NODL513', 2)]
    assert [(d.code, d.line) for d in load_launch(second, {}).diagnostics] == [('NODL513', 5)]
    assert [(d.code, d.line) for d in load_launch(first, {}).diagnostics] == [('NODL513', 2)]
    assert 'xacro' not in sys.modules


def test_lists_and_parameter_entries_from_missing_modules_keep_their_nodes(tmp_path: Path) -> None:
    """MoveIt's moveit_config.robot_description as a parameters entry, remappings= and
    arguments=/ros_arguments= given whole by a module not installed here: the node stays, one
    NODL513 each at the argument, and the record says what only the running launch gives."""
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        from launch_ros.actions import ComposableNodeContainer, Node
        from launch_ros.descriptions import ComposableNode
        from moveit_configs_utils import MoveItConfigsBuilder
        import robot_helpers as h

        def generate_launch_description():
            moveit_config = MoveItConfigsBuilder('arm').to_moveit_configs()
            return LaunchDescription([
                Node(package='moveit_ros_move_group', executable='move_group', name='move_group',
                     parameters=[moveit_config.robot_description, {'use_sim_time': True}]),
                Node(package='p', executable='e', name='a', arguments=h.args(), ros_arguments=h.ros(),
                     remappings=h.rules()),
                ComposableNodeContainer(package='rclcpp_components', executable='component_container',
                                        name='box', namespace='', composable_node_descriptions=[
                    ComposableNode(package='p', plugin='p::C', name='c', remappings=h.rules())]),
                Node(package='p', executable='e', name='plain', remappings=[('x', 'y')]),
            ])
        ''')})
    result = load_launch(main, {})
    assert [n.name for n in result.nodes] == ['move_group', 'a', 'box', 'c', 'plain']
    found = [(d.code, d.line, d.column, d.message.split(':')[0]) for d in result.diagnostics]
    assert found == [
        ('NODL513', 4, 1, "the Python launch file imports 'moveit_configs_utils', which is not installed here "
                          '(neither on the Python path nor in the Python folders of an ament prefix)'),
        ('NODL513', 5, 1, "the Python launch file imports 'robot_helpers', which is not installed here "
                          '(neither on the Python path nor in the Python folders of an ament prefix)'),
        ('NODL513', 11, 26, 'parameters entry'), ('NODL513', 12, 63, 'arguments'),
        ('NODL513', 12, 87, 'ros_arguments'), ('NODL513', 13, 25, 'remappings'),
        ('NODL513', 16, 77, 'remappings')]
    messages = [d.message for d in result.diagnostics]
    assert "moveit_configs_utils.MoveItConfigsBuilder(...).to_moveit_configs().robot_description " \
        "('moveit_configs_utils' is not installed here)" in messages[2]
    assert messages[3].endswith('the node is analysed without its arguments (nor the -r, -p and '
                                '--params-file rules they may hold)')
    assert messages[5].endswith('the node is analysed without its remapping rules')
    assert messages[6].endswith('the composable node is analysed without its remapping rules')
    move_group, a, box, c, plain = result.nodes
    assert [p.values for p in move_group.parameters] == [{'use_sim_time': True}]
    assert not move_group.parameters_complete and move_group.remaps_complete
    assert [s.part for s in a.run_time] == ['arguments', 'arguments', 'remaps']
    assert a.arguments == [] and a.remaps == [] and not a.parameters_complete and not a.remaps_complete
    assert [s.part for s in c.run_time] == ['remaps'] and c.parameters_complete and not c.remaps_complete
    assert plain.run_time == () and plain.remaps == [('x', 'y')] and box.run_time == ()


def test_placeholders_unpacked_into_parameters_or_iterated_are_said_not_dropped() -> None:
    """MoveIt's {**moveit_config.to_dict(), 'speed': 2}, dict.update() and dict() with a value of
    a module not installed here: the node stays, one NODL513 at its parameters entry, the names
    written out checked and none reported missing; nodes made in a loop over such a value: one
    NODL512 at the loop (once however often it runs)."""
    from nodl.analysis import analyse_launch
    from nodl.analysis.report import analysis_to_dict

    analysis = analyse_launch(MISSING / 'unpack.launch.py', prefixes=[str(ANALYSIS_PREFIX)])
    said = [(f.code, f.diagnostic.line, f.diagnostic.column) for f in analysis.findings
            if f.code in ('NODL512', 'NODL513')]
    assert said == [('NODL513', 6, 1), ('NODL512', 11, 5), ('NODL513', 22, 26), ('NODL513', 23, 78),
                    ('NODL513', 28, 44), ('NODL513', 30, 44), ('NODL512', 35, 9)]
    messages = [f.message for f in analysis.findings if f.code in ('NODL512', 'NODL513')]
    assert messages[1].startswith('moveit_configs_utils.MoveItConfigsBuilder(...).to_moveit_configs()'
                                  '.sensor_names is iterated, but its items are known only when the launch '
                                  "runs (it comes from 'moveit_configs_utils', which is not installed here)")
    assert messages[1].endswith('what would be made from its items (nodes, parameters, arguments...) is '
                                'missing from the analysis')
    assert messages[2].startswith('parameters entry: the value of the entries of moveit_configs_utils.'
                                  'MoveItConfigsBuilder(...).to_moveit_configs().to_dict() (')
    assert all(m.endswith('no parameter is reported missing for it)') for m in messages[2:6])
    nodes = {n['name']: n for n in analysis_to_dict(analysis)['nodes']}
    assert list(nodes) == ['/planner', '/merged', '/box', '/camera', '/camera_nested', '/camera_known']
    assert nodes['/planner']['parameters'] == {'speed': 2} and nodes['/merged']['parameters'] == {
        'robot_name': 'arm'}
    assert nodes['/camera_nested']['parameters'] == {'fps': 30.0}  # the nested marker is no name
    assert [n['parameters_complete'] for n in nodes.values()] == [False, False, True, False, False, True]
    found = {(f.kind, f.nodes[0], f.parameter) for f in analysis.findings if f.parameter}
    assert found == {('parameter-type', '/planner', 'speed'), ('parameter-invalid', '/camera', 'fps'),
                     ('missing-parameter', '/camera_known', 'device')}  # not /camera's nor the others'
    assert not analysis.unreadable
