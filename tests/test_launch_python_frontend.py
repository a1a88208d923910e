"""Python launch files (nodl.launch.python_frontend): generate_launch_description()
evaluated against the stand-in launch/launch_ros API; what it cannot evaluate is a finding."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path
from typing import Any

from nodl.launch import load_launch


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
    from nodl.launch import parameter_overrides
    from nodl.launch.params import RuntimeValue

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


def test_what_the_launch_file_prints_goes_to_standard_error(tmp_path: Path, capfd: Any) -> None:
    # capfd: the launch file runs in a forked child, which writes to the file descriptors
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
    out, err = capfd.readouterr()
    assert out == ''  # standard output is the tools' (nodl analyse --format json)
    assert err == 'configuring the robot\ngenerating\n'


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


def test_an_exception_in_generate_launch_description_is_at_its_line_and_column() -> None:
    """The innermost frame in the launch file, at the expression that raised, with the
    exception's own message (not the reader's internals)."""
    from conftest import FIXTURES

    path = FIXTURES / 'launch' / 'sandbox' / 'raises.launch.py'
    result = load_launch(path, {})
    assert [(d.code, d.file, d.line, d.column) for d in result.diagnostics] == [
        ('NODL516', str(path), 6, 12)]
    assert result.diagnostics[0].message.startswith("the Python launch file raised KeyError: 'robot'")
    assert 'python_frontend' not in result.diagnostics[0].message


def test_a_recursion_error_is_at_the_recursing_line(tmp_path: Path) -> None:
    main = _write(tmp_path, {'x.launch.py': textwrap.dedent('''\
        def down(n):
            return  down(n + 1)
        def generate_launch_description():
            return down(0)
        ''')})
    result = load_launch(main, {})
    assert [(d.code, d.line, d.column) for d in result.diagnostics] == [('NODL516', 2, 13)]
    assert 'recurses without end (RecursionError' in result.diagnostics[0].message
