"""Python launch files (nodl_schema.launch.python_frontend): generate_launch_description()
evaluated against the stand-in launch/launch_ros API; what it cannot evaluate is a finding."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

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
