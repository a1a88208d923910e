"""The user's side of a generated C++ node: a subclass with a placeholder for every callback.

``nodl new`` writes it once (``src/<executable>.cpp``); it is the user's file from
then on.  Every callback has a body that compiles and lets the node run right
away: messages and requests are accepted and ignored, action goals are
accepted and succeed at once with an empty result, custom validators accept
every value.
"""

from __future__ import annotations

from nodl.composition.entities import EntityKind
from nodl.generate.cpp import parameter_code as cparams
from nodl.generate.cpp.node_code import CppNode
from nodl.generate.cpp.text import comment_lines

__all__ = ['render_user_source']


def _methods(node: CppNode) -> list[str]:
    lines: list[str] = []
    for e in node.of_kind(EntityKind.SUBSCRIPTION):
        lines += [f'  void {e.callback}(const {e.type}::ConstSharedPtr & msg) override', '  {',
                  f'    (void)msg;  // TODO: handle a message of {e.entity.kind.word} '
                  f'{_plain(e.entity.name)}', '  }', '']
    for e in node.of_kind(EntityKind.SERVICE_SERVER):
        lines += [f'  void {e.callback}(',
                  f'    const std::shared_ptr<{e.type}::Request> request,',
                  f'    std::shared_ptr<{e.type}::Response> response) override', '  {',
                  '    (void)request;  // TODO: fill the response',
                  '    (void)response;', '  }', '']
    for e in node.of_kind(EntityKind.ACTION_SERVER):
        handle = f'std::shared_ptr<rclcpp_action::ServerGoalHandle<{e.type}>>'
        lines += [f'  rclcpp_action::GoalResponse {e.callback}_goal(',
                  '    const rclcpp_action::GoalUUID & uuid,',
                  f'    std::shared_ptr<const {e.type}::Goal> goal) override', '  {',
                  '    (void)uuid;', '    (void)goal;',
                  '    return rclcpp_action::GoalResponse::ACCEPT_AND_EXECUTE;', '  }', '',
                  f'  rclcpp_action::CancelResponse {e.callback}_cancel(',
                  f'    const {handle} goal_handle) override', '  {', '    (void)goal_handle;',
                  '    return rclcpp_action::CancelResponse::ACCEPT;', '  }', '',
                  f'  void {e.callback}_accepted(const {handle} goal_handle) override', '  {',
                  '    // TODO: execute the goal (in a thread or a timer for long work)',
                  f'    goal_handle->succeed(std::make_shared<{e.type}::Result>());', '  }', '']
    if lines and not lines[-1]:
        lines.pop()
    return lines


def _plain(name: str) -> str:
    return ' '.join(comment_lines(name, '', '')).strip()


def render_user_source(node: CppNode, class_name: str) -> str:
    """``src/<executable>.cpp``: the subclass ``class_name`` of the base, and ``main`` (for a
    component, generated with ``component=True``: its ``RCLCPP_COMPONENTS_REGISTER_NODE`` instead)."""
    lines = comment_lines(f'The implementation of {node.node_name}, written once by `nodl new`: '
                          'yours to edit (regenerating never touches it).', '', '//')
    lines += ['', '#include <memory>', '#include <string>', '', f'#include "{node.stem}.hpp"', '']
    custom = cparams.custom_definitions(node.parameters)
    if custom:
        lines += custom + ['']
    lines += [f'namespace {node.namespace}', '{', '',
              f'class {class_name} : public {node.class_name}', '{', 'public:',
              f'  using {node.class_name}::{node.class_name};']
    methods = _methods(node)
    if methods:
        lines += ['', 'protected:'] + methods
    lines += ['};', '', f'}}  // namespace {node.namespace}', '']
    if node.component:
        lines += comment_lines('A component: load it into a container, or run the executable '
                               'of the package that runs it alone.', '', '//')
        lines.append(f'RCLCPP_COMPONENTS_REGISTER_NODE({node.namespace}::{class_name})')
        return '\n'.join(lines) + '\n'
    lines += ['int main(int argc, char ** argv)', '{', '  rclcpp::init(argc, argv);',
              f'  auto node = std::make_shared<{node.namespace}::{class_name}>();']
    lines.append('  rclcpp::spin(node->get_node_base_interface());' if node.lifecycle
                 else '  rclcpp::spin(node);')
    lines += ['  rclcpp::shutdown();', '  return 0;', '}']
    return '\n'.join(lines) + '\n'
