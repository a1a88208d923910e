"""Python launch files (nodl_schema.launch.python_frontend): generate_launch_description()
evaluated against the stand-in launch/launch_ros API; what it cannot evaluate is a finding."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path
from typing import Any

from nodl_schema.launch import load_launch


def _write(tmp_path: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding='utf-8')
    return tmp_path / next(iter(files))


def test_opaque_function_and_unknown_action_are_findings(tmp_path: Path) -> None:
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        from launch.actions import OpaqueFunction, SomethingNew
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([
                OpaqueFunction(function=print),
                SomethingNew(x=1),
                Node(package='p', executable='e')])
        ''')})
    result = load_launch(main, {})
    assert [(d.code, d.line) for d in result.diagnostics] == [('NODL512', 6), ('NODL512', 7)]
    assert len(result.nodes) == 1
    assert 'launch' not in sys.modules and 'launch_ros.actions' not in sys.modules


def test_an_exception_in_the_launch_file_is_a_finding_at_its_line(tmp_path: Path) -> None:
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        def generate_launch_description():
            value = {}['missing']
            return LaunchDescription([])
        ''')})
    (problem,) = load_launch(main, {}).diagnostics
    assert (problem.code, problem.line) == ('NODL516', 3) and 'KeyError' in problem.message


def test_no_generate_function_and_syntax_errors(tmp_path: Path) -> None:
    main = _write(tmp_path, {'a.launch.py': 'x = 1\n'})
    assert [d.code for d in load_launch(main, {}).diagnostics] == ['NODL516']
    main = _write(tmp_path, {'b.launch.py': 'def generate_launch_description(:\n'})
    (problem,) = load_launch(main, {}).diagnostics
    assert (problem.code, problem.line) == ('NODL516', 1) and 'syntax' in problem.message
    assert 'launch' not in sys.modules


def test_unnamed_node_records_say_the_name_was_not_given(tmp_path: Path) -> None:
    main = _write(tmp_path, {'u.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([Node(package='p', executable='talker', namespace='ns')])
        ''')})
    (node,) = load_launch(main, {}).nodes
    assert (node.name, node.name_given, node.fqn, node.namespace) == (None, False, None, '/ns')
    assert node.to_dict()['name_given'] is False


REAL_WORLD = Path(__file__).parent / 'fixtures' / 'launch' / 'real_world'


def _rover(tmp_path: Path, prefix: Path, **arguments: str) -> Any:
    return load_launch(REAL_WORLD / 'rover_stack.launch.py', {'scratch': str(tmp_path), **arguments},
                       prefixes=[str(prefix)])


def test_a_stack_style_launch_file_with_installed_helpers_is_read_faithfully(tmp_path: Path) -> None:
    """Helper substitutions installed under the ament prefix (lib/python*/site-packages) import
    and run against the stand-ins (launch.utilities, context.launch_configurations), names used
    only by main() or in hints import, submodule imports give the same classes,
    PathSubstitution joins, FindPackageShare.find works; a $(command) parameter keeps its node."""
    from nodl_schema.launch import parameter_overrides
    from nodl_schema.launch.params import RuntimeValue

    path_before, modules_before = list(sys.path), set(sys.modules)
    result = _rover(tmp_path, REAL_WORLD / 'prefix')
    assert [(d.code, d.severity.value, d.line) for d in result.diagnostics] == [
        ('NODL513', 'warning', 35), ('NODL512', 'info', 48)]
    assert 'the node is analysed without this value' in result.diagnostics[0].message
    assert [(n.kind, n.name, n.namespace, n.container) for n in result.nodes] == [
        ('node', 'describer', '/rover1', None), ('container', 'stack', '/rover1', None),
        ('composable', 'planner', '/rover1', '/rover1/stack')]
    describer, _, planner = result.nodes
    values = {k: v.value for k, v in parameter_overrides(describer).items()}
    assert values['rate'] == 5.0 and isinstance(values['description'], RuntimeValue)
    assert {k: v.value for k, v in parameter_overrides(planner).items()} == {'horizon': 2.5, 'frame': 'map'}
    assert sys.path == path_before
    assert not {m for m in set(sys.modules) - modules_before
                if m.partition('.')[0] in ('launch', 'launch_ros', 'rover_launch_tools')}


def test_conditions_through_helper_substitutions_and_ros_processes(tmp_path: Path) -> None:
    result = _rover(tmp_path, REAL_WORLD / 'prefix', mode='processes', record='on', robot='r2')
    assert [(n.kind, n.name, n.namespace) for n in result.nodes] == [
        ('node', 'describer', '/r2'), ('node', 'planner', '/r2')]
    process = [d for d in result.diagnostics if d.line == 47]
    assert [(d.code, d.severity.value) for d in process] == [('NODL512', 'warning')]
    assert "'ros2 bag record -a'" in process[0].message and 'missing from the analysis' in process[0].message


def test_a_helper_package_that_is_not_installed_is_a_warning_and_the_rest_is_analysed(tmp_path: Path) -> None:
    import shutil

    prefix = tmp_path / 'prefix'
    shutil.copytree(REAL_WORLD / 'prefix' / 'share', prefix / 'share')  # no lib/python*/
    modules_before = set(sys.modules)
    result = _rover(tmp_path, prefix)
    assert [(d.code, d.severity.value, d.line) for d in result.diagnostics] == [
        ('NODL513', 'warning', 16), ('NODL513', 'warning', 35), ('NODL513', 'warning', 43),
        ('NODL513', 'warning', 47), ('NODL512', 'info', 48)]
    assert "imports 'rover_launch_tools', which is not installed here" in result.diagnostics[0].message
    planner_file = result.diagnostics[2]  # the planner's parameter file, at its item: the node stays
    assert "rover_launch_tools.NestUnder(...) ('rover_launch_tools' is not installed here)" \
        in planner_file.message and 'the composable node is analysed without the parameters' \
        in planner_file.message and 'missing from the analysis' not in planner_file.message
    assert [(n.kind, n.name) for n in result.nodes] == [('node', 'describer'), ('container', 'stack'),
                                                        ('composable', 'planner')]
    planner = result.nodes[2]
    assert not planner.parameters_complete and planner.remaps_complete
    assert [(s.part, s.source.line) for s in planner.run_time] == [('parameters', 43)]
    assert result.nodes[0].parameters_complete and result.nodes[0].run_time == ()
    assert not {m for m in set(sys.modules) - modules_before if m.startswith('rover_launch_tools')}


def test_a_package_not_found_by_ament_index_python_is_nodl511(tmp_path: Path) -> None:
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        from ament_index_python.packages import get_package_share_directory
        from launch import LaunchDescription
        def generate_launch_description():
            get_package_share_directory('no_such_package_here')
            return LaunchDescription([])
        ''')})
    (problem,) = load_launch(main, {}, prefixes=[str(tmp_path)]).diagnostics
    assert (problem.code, problem.line) == ('NODL511', 4)
    assert problem.message.startswith("package 'no_such_package_here' not found")


def test_unevaluable_values_say_what_is_missing(tmp_path: Path) -> None:
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        from launch.actions import IncludeLaunchDescription
        from launch.substitutions import Command, LaunchLogDir
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([
                Node(package='p', executable='e', name=Command('hostname')),
                IncludeLaunchDescription(LaunchLogDir()),
                Node(package='p', executable='f', parameters=[{'log': LaunchLogDir()}])])
        ''')})
    result = load_launch(main, {})
    assert [(d.code, d.line) for d in result.diagnostics] == [('NODL513', 7), ('NODL513', 8), ('NODL513', 9)]
    assert result.diagnostics[0].message.endswith('this node is missing from the analysis')
    assert 'nodes of the included launch file are missing' in result.diagnostics[1].message
    assert [n.executable for n in result.nodes] == ['f']


def test_sys_exit_in_the_launch_file_is_a_finding_not_an_exit(tmp_path: Path) -> None:
    at_import = _write(tmp_path, {'a.launch.py': 'import sys\n\nsys.exit(3)\n'})
    [problem] = load_launch(at_import, {}).diagnostics
    assert (problem.code, problem.line) == ('NODL516', 3)
    assert problem.message.startswith('the Python launch file exits (sys.exit(3)) before it gives')
    generating = _write(tmp_path, {'b.launch.py': textwrap.dedent('''\
        import sys
        def generate_launch_description():
            sys.exit('no robot here')
        ''')})
    [problem] = load_launch(generating, {}).diagnostics
    assert (problem.code, problem.line) == ('NODL516', 3)
    assert "sys.exit('no robot here')" in problem.message


def test_what_the_launch_file_prints_goes_to_standard_error(tmp_path: Path, capsys: Any) -> None:
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        from launch_ros.actions import Node
        print('configuring the robot')
        def generate_launch_description():
            print('generating')
            return LaunchDescription([Node(package='p', executable='e', name='n')])
        ''')})
    result = load_launch(main, {})
    assert len(result.nodes) == 1 and not result.diagnostics
    out, err = capsys.readouterr()
    assert out == ''  # standard output is the tools' (nodl analyse --format json)
    assert err == 'configuring the robot\ngenerating\n'


MISSING = Path(__file__).parent / 'fixtures' / 'launch' / 'missing_modules'
ANALYSIS_PREFIX = Path(__file__).parent / 'fixtures' / 'analysis' / 'prefix'


def test_modules_not_installed_here_are_placeholders_and_the_analysis_goes_on() -> None:
    """xacro and nav2_common are not installed here: one warning per module at its import,
    the robot_description from xacro a run-time value, the registered node analysed."""
    import importlib.util

    from nodl_schema.analysis import analyse_launch
    from nodl_schema.launch import parameter_overrides
    from nodl_schema.launch.params import RuntimeValue

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
        ('NODL513', 24, "parameter 'path': the value of a text with helpers.config.load(...)[...]"),
        ('NODL513', 24, "parameter 'name': the value of a text with helpers.config.load(...)[...]"),
        ('NODL513', 24, "parameter 'plain': the value of a text with helpers.config.load(...)[...]"),
        ('NODL513', 26, 'the value of helpers.config.load(...)[...]'),
        ('NODL513', 27, 'the value of helpers.config.enabled'),
        ('NODL513', 28, 'parameters entry: the value of a text with helpers.config.load(...)[...]'),
        ('NODL512', 29, 'Mine(...)'),
        ('NODL512', 31, 'helpers.config.tail() cannot be evaluated without running the launch')]
    assert 'this node is missing from the analysis' in result.diagnostics[4].message
    assert 'the node is analysed without the parameters' in result.diagnostics[6].message
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


def test_an_unknown_launch_event_handler_is_a_finding_not_an_exception(tmp_path: Path) -> None:
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        from launch import LaunchDescription
        from launch.actions import RegisterEventHandler
        from launch.event_handlers import OnSomethingNew
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([RegisterEventHandler(OnSomethingNew(on_exit=[])),
                                      Node(package='p', executable='e', name='n')])
        ''')})
    result = load_launch(main, {})
    assert [(d.code, d.line) for d in result.diagnostics] == [('NODL512', 6)]
    assert len(result.nodes) == 1


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
