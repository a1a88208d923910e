"""The arguments of a stand-in action given values of a missing module
(nodl.launch.python_arguments): each becomes what the action reads as a run-time value.
Whole launch files with missing modules are in tests/test_launch_python_missing.py."""

from __future__ import annotations

from nodl.launch import actions as A
from nodl.launch import conditions as C
from nodl.launch.python_arguments import action_arguments
from nodl.launch.python_missing import Placeholder, make_placeholder
from nodl.launch.ros_actions import RUN_TIME_KEYWORD, ComposableNode, ComposableNodeContainer, Node


def test_an_argument_s_name_and_description_are_marker_texts_and_choices_go() -> None:
    name = make_placeholder('xacro.NAME', 'xacro')
    args, kwargs = action_arguments(A.DeclareLaunchArgument, (name,), {
        'description': 'plain', 'choices': make_placeholder('xacro.CHOICES', 'xacro')})
    assert type(args[0]) is str and 'xacro.NAME' in args[0] and 'known at run time' in args[0]
    assert kwargs == {'description': 'plain', 'choices': None}


def test_a_placeholder_condition_is_evaluated_at_run_time() -> None:
    _, kwargs = action_arguments(A.GroupAction, ([],), {'condition': make_placeholder('m.ON', 'm')})
    assert isinstance(kwargs['condition'], C.IfCondition)


def test_a_node_s_lists_given_whole_are_known_at_run_time() -> None:
    remaps = make_placeholder('helpers.REMAPS', 'helpers')
    _, kwargs = action_arguments(Node, (), {'package': 'p', 'executable': 'e', 'remappings': remaps})
    assert 'remappings' not in kwargs and kwargs[RUN_TIME_KEYWORD] == {'remappings': remaps}
    assert kwargs['package'] == 'p'


def test_a_placeholder_composable_node_is_one_known_at_run_time() -> None:
    description = make_placeholder('helpers.describe()', 'helpers')
    _, kwargs = action_arguments(ComposableNodeContainer, (), {
        'name': 'c', 'namespace': '', 'package': 'rclcpp_components', 'executable': 'component_container',
        'composable_node_descriptions': [description]})
    (made,) = kwargs['composable_node_descriptions']
    assert isinstance(made, ComposableNode) and not isinstance(made, Placeholder)
    (package,) = made.package
    (plugin,) = made.plugin
    assert isinstance(package, Placeholder) and package is plugin
    assert package._nodl_what == 'helpers.describe()' and package._nodl_module == 'helpers'
