"""The rclcpp base class of a node: ``<stem>_base.hpp`` and ``<stem>_base.cpp``.

:func:`render` turns a resolved node (what its implementation provides:
``main``'s entities; the base comes from rclcpp, mixins from other code)
into a header and a source.  The class derives from ``rclcpp::Node`` or
``rclcpp_lifecycle::LifecycleNode``; it creates every endpoint with the
declared QoS, declares every parameter with its descriptor, enforces the
validators at start-up and at set time, and leaves the callbacks to a
subclass as pure virtual methods.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from nodl.composition.entities import Entity, EntityKind, InterfaceType
from nodl.generate.cpp import parameter_code as cparams
from nodl.generate.cpp.qos_code import qos_expression
from nodl.generate.cpp.text import comment_lines, interface_cpp, interface_header, string_literal
from nodl.plan.identifiers import CPP_KEYWORDS, IdentifierScope, snake_case
from nodl.plan.parameter_plan import ParametersPlan

__all__ = ['CppEndpoint', 'CppNode', 'plan_node', 'render_header', 'render_source',
           'dependencies', 'LIFECYCLE_HOOKS', 'RESERVED_METHODS']

#: Transition -> the overridable hook the generated ``on_<transition>`` calls.
LIFECYCLE_HOOKS: dict[str, str] = {
    'configure': 'handle_configure', 'activate': 'handle_activate',
    'deactivate': 'handle_deactivate', 'cleanup': 'handle_cleanup', 'shutdown': 'handle_shutdown',
}

#: Methods of the generated class and of rclcpp's node classes that a callback must not take.
RESERVED_METHODS: frozenset[str] = frozenset({
    'params', 'is_old', 'try_update', 'on_parameters_changed', 'on_configure', 'on_activate',
    'on_deactivate', 'on_cleanup', 'on_shutdown', 'on_error', 'create_entities',
    'reset_entities', 'declare_parameters', 'validate_parameters', 'on_set_parameters',
    'on_post_set_parameters', *LIFECYCLE_HOOKS.values()})

#: Entity kind -> (member prefix, rclcpp handle template).
_MEMBERS: dict[EntityKind, tuple[str, str]] = {
    EntityKind.PUBLISHER: ('pub', 'rclcpp::Publisher<{t}>::SharedPtr'),
    EntityKind.SUBSCRIPTION: ('sub', 'rclcpp::Subscription<{t}>::SharedPtr'),
    EntityKind.SERVICE_SERVER: ('srv', 'rclcpp::Service<{t}>::SharedPtr'),
    EntityKind.SERVICE_CLIENT: ('cli', 'rclcpp::Client<{t}>::SharedPtr'),
    EntityKind.ACTION_SERVER: ('action_server', 'rclcpp_action::Server<{t}>::SharedPtr'),
    EntityKind.ACTION_CLIENT: ('action_client', 'rclcpp_action::Client<{t}>::SharedPtr'),
}
_LIFECYCLE_PUBLISHER = 'rclcpp_lifecycle::LifecyclePublisher<{t}>::SharedPtr'
_ACTION_CALLBACKS = ('goal', 'cancel', 'accepted')


@dataclass
class CppEndpoint:
    """One endpoint with its C++ names."""

    entity: Entity
    #: ``sensor_msgs::msg::LaserScan``.
    type: str
    #: ``pub_scan_``.
    member: str
    #: The callback method (subscriptions, service servers) or the stem of the action
    #: server's three (``on_capture_burst`` -> ``_goal``, ``_cancel``, ``_accepted``); ''.
    callback: str = ''


@dataclass
class CppNode:
    """Everything the templates need, named collision-free."""

    class_name: str
    params_name: str
    namespace: str
    node_name: str
    stem: str
    source: str
    lifecycle: bool
    description: str
    endpoints: list[CppEndpoint]
    parameters: ParametersPlan
    interfaces: list[InterfaceType] = field(default_factory=list)
    #: Include rclcpp_components' registration macro (the subclass registers itself).
    component: bool = False

    @property
    def base_class(self) -> str:
        """The rclcpp class the base derives from."""
        return 'rclcpp_lifecycle::LifecycleNode' if self.lifecycle else 'rclcpp::Node'

    def of_kind(self, kind: EntityKind) -> list[CppEndpoint]:
        """The endpoints of one kind."""
        return [e for e in self.endpoints if e.entity.kind is kind]

    @property
    def has_actions(self) -> bool:
        """True if the node serves or calls an action."""
        return bool(self.of_kind(EntityKind.ACTION_SERVER) or self.of_kind(EntityKind.ACTION_CLIENT))


def _interface(entity: Entity) -> InterfaceType:
    if not isinstance(entity.type, InterfaceType):
        from nodl.generate import GenerationError

        raise GenerationError(f'{entity.kind.word} {entity.name!r}: {entity.type_name!r} is not an '
                              'interface type (<package>/<namespace>/<Name>)')
    return entity.type


def plan_node(entities: list[Entity], *, class_name: str, namespace: str, node_name: str,
              source: str, lifecycle: bool, description: str, component: bool = False) -> CppNode:
    """Name everything: members, callbacks, the parameter struct (deterministic, collision-free)."""
    members = IdentifierScope((), CPP_KEYWORDS)
    methods = IdentifierScope(RESERVED_METHODS, CPP_KEYWORDS)
    endpoints: list[CppEndpoint] = []
    kinds = [k for k in EntityKind if k is not EntityKind.PARAMETER]
    for kind in kinds:
        of_kind = [e for e in entities if e.kind is kind]
        prefix = _MEMBERS[kind][0]
        names = members.assign([e.name for e in of_kind], prefix + '_{}')
        for entity in of_kind:
            iface = _interface(entity)
            endpoints.append(CppEndpoint(entity, interface_cpp(*iface), names[entity.name] + '_'))
    by_key = {e.entity.key: e for e in endpoints}
    for kind in (EntityKind.SUBSCRIPTION, EntityKind.SERVICE_SERVER):
        names = methods.assign([e.name for e in entities if e.kind is kind], 'on_{}')
        for name, method in names.items():
            by_key[(kind, name)].callback = method
    for entity in sorted((e for e in entities if e.kind is EntityKind.ACTION_SERVER),
                         key=lambda e: e.name):
        stem, n = 'on_' + snake_case(entity.name), 1
        candidate = stem
        while any(f'{candidate}_{s}' in methods.taken for s in _ACTION_CALLBACKS):
            n += 1
            candidate = f'{stem}_{n}'
        for suffix in _ACTION_CALLBACKS:
            methods.claim(f'{candidate}_{suffix}')
        by_key[(EntityKind.ACTION_SERVER, entity.name)].callback = candidate
    interfaces = sorted({_interface(e) for e in entities if not e.is_parameter})
    plan = cparams.cpp_parameter_plan([e for e in entities if e.is_parameter])
    return CppNode(class_name + 'Base', class_name + 'Params', namespace, node_name,
                   snake_case(class_name) + '_base', source, lifecycle, description,
                   endpoints, plan, interfaces, component)


def dependencies(node: CppNode) -> list[str]:
    """The packages the generated code needs (rclcpp, lifecycle and action packages, interfaces)."""
    packages = {'rclcpp', 'rcl_interfaces'}
    if node.lifecycle:
        packages.add('rclcpp_lifecycle')
    if node.has_actions:
        packages.add('rclcpp_action')
    if node.component:
        packages.add('rclcpp_components')
    packages.update(i.package for i in node.interfaces)
    return sorted(packages)


# --------------------------------------------------------------------------
# Header


def _banner(node: CppNode, header: bool = True) -> list[str]:
    lines = comment_lines(f'Generated by `nodl generate --language cpp` from {node.source}.', '', '//')
    lines.append('// Do not edit: regenerate it, and implement the node in a subclass.')
    if header:  # read by ament_nodl_generate_cpp (CMake)
        lines.append('// nodl-dependencies: ' + ' '.join(dependencies(node)))
    return lines


def _guard(node: CppNode) -> str:
    return f'{node.namespace.replace("::", "__")}__{node.stem}_HPP_'.upper()


def _handle_type(node: CppNode, endpoint: CppEndpoint) -> str:
    template = _MEMBERS[endpoint.entity.kind][1]
    if node.lifecycle and endpoint.entity.kind is EntityKind.PUBLISHER:
        template = _LIFECYCLE_PUBLISHER
    return template.format(t=endpoint.type)


def _entity_comment(endpoint: CppEndpoint, indent: str) -> list[str]:
    entity = endpoint.entity
    text = f'{entity.kind.word} {entity.name} ({entity.type_name})'
    if entity.description:
        text = f'{entity.description}\n{text}'
    return comment_lines(text, indent)


def _callback_declarations(node: CppNode) -> list[str]:
    lines: list[str] = []
    for e in node.of_kind(EntityKind.SUBSCRIPTION):
        lines += _entity_comment(e, '  ')
        lines.append(f'  virtual void {e.callback}(const {e.type}::ConstSharedPtr & msg) = 0;')
    for e in node.of_kind(EntityKind.SERVICE_SERVER):
        lines += _entity_comment(e, '  ')
        lines += [f'  virtual void {e.callback}(',
                  f'    const std::shared_ptr<{e.type}::Request> request,',
                  f'    std::shared_ptr<{e.type}::Response> response) = 0;']
    for e in node.of_kind(EntityKind.ACTION_SERVER):
        handle = f'std::shared_ptr<rclcpp_action::ServerGoalHandle<{e.type}>>'
        lines += _entity_comment(e, '  ')
        lines += comment_lines('Accept or reject a new goal.', '  ')
        lines += [f'  virtual rclcpp_action::GoalResponse {e.callback}_goal(',
                  '    const rclcpp_action::GoalUUID & uuid,',
                  f'    std::shared_ptr<const {e.type}::Goal> goal) = 0;']
        lines += comment_lines('Accept or reject a request to cancel a goal.', '  ')
        lines += [f'  virtual rclcpp_action::CancelResponse {e.callback}_cancel(',
                  f'    const {handle} goal_handle) = 0;']
        lines += comment_lines('Execute an accepted goal (return quickly: start a thread or a '
                               'timer).', '  ')
        lines += [f'  virtual void {e.callback}_accepted(const {handle} goal_handle) = 0;']
    return lines


def render_header(node: CppNode) -> str:
    """The header: parameter struct, custom validator hooks, the base class."""
    includes = ['<cstdint>', '<memory>', '<mutex>', '<string>', '<vector>']
    ros = ['"rclcpp/rclcpp.hpp"']
    if node.lifecycle:
        ros.append('"rclcpp_lifecycle/lifecycle_node.hpp"')
        ros.append('"rclcpp_lifecycle/lifecycle_publisher.hpp"')
    if node.has_actions:
        ros.append('"rclcpp_action/rclcpp_action.hpp"')
    if node.component:
        ros.append('"rclcpp_components/register_node_macro.hpp"')
    ros += sorted({f'"{interface_header(*i)}"' for i in node.interfaces})
    guard = _guard(node)
    lines = _banner(node) + ['', f'#ifndef {guard}', f'#define {guard}', '']
    lines += [f'#include {i}' for i in includes] + ['']
    lines += [f'#include {i}' for i in ros] + ['']
    custom = cparams.custom_declarations(node.parameters)
    if custom:
        lines += ['// Custom validators named in the definition: define each one in your code.',
                  '// Return an empty string to accept the value, or why it is rejected.']
        lines += custom + ['']
    lines += [f'namespace {node.namespace}', '{', '']
    lines += comment_lines(f'The parameters of {node.node_name}, nested by dotted name.')
    lines += cparams.struct_lines(node.parameters.root, node.params_name) + ['']
    lines += comment_lines(node.description or f'The interface of {node.node_name}.')
    lines += comment_lines(
        'Every endpoint and parameter of the definition; a subclass implements the callbacks.')
    lines += [f'class {node.class_name} : public {node.base_class}', '{', 'public:',
              f'  using Params = {node.params_name};']
    if node.lifecycle:
        lines.append('  using CallbackReturn = '
                     'rclcpp_lifecycle::node_interfaces::LifecycleNodeInterface::CallbackReturn;')
    lines += ['',
              *comment_lines('Declares the parameters (and validates them); '
                             + ('endpoints are created on configure.' if node.lifecycle
                                else 'creates every endpoint.'), '  '),
              f'  explicit {node.class_name}(',
              f'    const std::string & node_name = {string_literal(node.node_name)},',
              '    const rclcpp::NodeOptions & options = rclcpp::NodeOptions());',
              *comment_lines('For components: the default node name.', '  '),
              f'  explicit {node.class_name}(const rclcpp::NodeOptions & options);',
              f'  virtual ~{node.class_name}() = default;', '',
              *comment_lines('A consistent copy of the current parameter values.', '  '),
              '  Params params() const;',
              *comment_lines('True if a parameter changed since `params` was taken.', '  '),
              '  bool is_old(const Params & params) const;',
              *comment_lines('Updates `params` if it is old; true if it did.', '  '),
              '  bool try_update(Params & params) const;', '',
              'protected:']
    lines += _callback_declarations(node)
    lines += [*comment_lines('Called after a change of parameters was validated and committed.',
                             '  '),
              '  virtual void on_parameters_changed(const Params & params);']
    if node.lifecycle:
        lines += ['']
        for transition, hook in LIFECYCLE_HOOKS.items():
            what = ('after the endpoints are created' if transition == 'configure' else
                    'before the endpoints are released' if transition in ('cleanup', 'shutdown')
                    else 'with the publishers already switched')
            lines += comment_lines(f'Override to act on {transition} ({what}).', '  ')
            lines.append(f'  virtual CallbackReturn {hook}(const rclcpp_lifecycle::State & state);')
        lines += ['']
        for transition in LIFECYCLE_HOOKS:
            lines.append(f'  CallbackReturn on_{transition}(const rclcpp_lifecycle::State & state) '
                         'override;')
    lines += ['']
    for e in node.endpoints:
        lines += _entity_comment(e, '  ')
        lines.append(f'  {_handle_type(node, e)} {e.member};')
    lines += ['', 'private:',
              '  void declare_parameters();',
              '  void create_entities();',
              '  void reset_entities();',
              '  std::string validate_parameters(const Params & params) const;',
              '  rcl_interfaces::msg::SetParametersResult on_set_parameters(',
              '    const std::vector<rclcpp::Parameter> & parameters);',
              '  void on_post_set_parameters(const std::vector<rclcpp::Parameter> & parameters);',
              '',
              '  mutable std::mutex params_mutex_;',
              '  Params params_;',
              '  rclcpp::node_interfaces::OnSetParametersCallbackHandle::SharedPtr on_set_handle_;',
              '  rclcpp::node_interfaces::PostSetParametersCallbackHandle::SharedPtr '
              'post_set_handle_;',
              '};', '', f'}}  // namespace {node.namespace}', '', f'#endif  // {guard}']
    return '\n'.join(lines) + '\n'


# --------------------------------------------------------------------------
# Source


def _create_lines(node: CppNode) -> list[str]:
    lines: list[str] = []
    for e in node.endpoints:
        kind, name = e.entity.kind, string_literal(e.entity.name)
        qos = qos_expression(e.entity.qos)
        if kind is EntityKind.PUBLISHER:
            lines.append(f'  {e.member} = this->create_publisher<{e.type}>({name}, {qos});')
        elif kind is EntityKind.SUBSCRIPTION:
            lines += [f'  {e.member} = this->create_subscription<{e.type}>(',
                      f'    {name}, {qos},',
                      f'    [this](const {e.type}::ConstSharedPtr & msg) {{this->{e.callback}(msg);}});']
        elif kind is EntityKind.SERVICE_SERVER:
            lines += [f'  {e.member} = this->create_service<{e.type}>(',
                      f'    {name},',
                      f'    [this](const std::shared_ptr<{e.type}::Request> request,',
                      f'    std::shared_ptr<{e.type}::Response> response) {{',
                      f'      this->{e.callback}(request, response);',
                      f'    }}, {qos});']
        elif kind is EntityKind.SERVICE_CLIENT:
            lines.append(f'  {e.member} = this->create_client<{e.type}>({name}, {qos});')
        elif kind is EntityKind.ACTION_SERVER:
            handle = f'std::shared_ptr<rclcpp_action::ServerGoalHandle<{e.type}>>'
            lines += [f'  {e.member} = rclcpp_action::create_server<{e.type}>(',
                      f'    this, {name},',
                      '    [this](const rclcpp_action::GoalUUID & uuid,',
                      f'    std::shared_ptr<const {e.type}::Goal> goal) {{',
                      f'      return this->{e.callback}_goal(uuid, goal);',
                      '    },',
                      f'    [this](const {handle} goal_handle) {{',
                      f'      return this->{e.callback}_cancel(goal_handle);',
                      '    },',
                      f'    [this](const {handle} goal_handle) {{',
                      f'      this->{e.callback}_accepted(goal_handle);',
                      '    });']
        else:
            lines.append(f'  {e.member} = rclcpp_action::create_client<{e.type}>(this, {name});')
    return lines


def _lifecycle_lines(node: CppNode) -> list[str]:
    c = node.class_name
    publishers = node.of_kind(EntityKind.PUBLISHER)
    lines: list[str] = []
    for transition, hook in LIFECYCLE_HOOKS.items():
        lines += [f'{c}::CallbackReturn {c}::on_{transition}(const rclcpp_lifecycle::State & state)',
                  '{']
        if transition == 'configure':
            lines += ['  create_entities();', f'  return {hook}(state);']
        elif transition in ('activate', 'deactivate'):
            lines += [f'  {node.base_class}::on_{transition}(state);']
            lines += [f'  if ({p.member}) {{\n    {p.member}->on_{transition}();\n  }}'
                      for p in publishers]
            lines += [f'  return {hook}(state);']
        else:
            lines += [f'  const CallbackReturn result = {hook}(state);',
                      '  reset_entities();', '  return result;']
        lines += ['}', '']
        lines += [f'{c}::CallbackReturn {c}::{hook}(const rclcpp_lifecycle::State & /*state*/)',
                  '{', '  return CallbackReturn::SUCCESS;', '}', '']
    return lines


def render_source(node: CppNode) -> str:
    """The source: constructors, parameter handling, endpoint creation."""
    c, plan = node.class_name, node.parameters
    lines = _banner(node, header=False) + ['', f'#include "{node.stem}.hpp"', '',
                                 '#include <algorithm>', '#include <cstddef>', '#include <limits>',
                                 '#include <stdexcept>', '#include <utility>', '']
    if cparams.uses_unique(plan):
        lines += cparams.helper_lines() + ['']
    lines += [f'namespace {node.namespace}', '{', '',
              f'{c}::{c}(const std::string & node_name, const rclcpp::NodeOptions & options)',
              f': {node.base_class}(node_name, options)', '{', '  declare_parameters();']
    if not node.lifecycle:
        lines.append('  create_entities();')
    lines += ['}', '',
              f'{c}::{c}(const rclcpp::NodeOptions & options)',
              f': {c}({string_literal(node.node_name)}, options)', '{', '}', '',
              f'void {c}::declare_parameters()', '{']
    lines += cparams.declare_lines(plan, '  ')
    lines += ['  Params initial;']
    lines += cparams.read_lines(plan, 'initial', '  ')
    lines += ['  const std::string reason = validate_parameters(initial);',
              '  if (!reason.empty()) {',
              '    throw std::invalid_argument(reason);',
              '  }',
              '  {',
              '    std::lock_guard<std::mutex> lock(params_mutex_);',
              '    params_ = initial;',
              '  }',
              '  on_set_handle_ = this->add_on_set_parameters_callback(',
              '    [this](const std::vector<rclcpp::Parameter> & parameters) {',
              '      return this->on_set_parameters(parameters);',
              '    });',
              '  post_set_handle_ = this->add_post_set_parameters_callback(',
              '    [this](const std::vector<rclcpp::Parameter> & parameters) {',
              '      this->on_post_set_parameters(parameters);',
              '    });',
              '}', '',
              f'std::string {c}::validate_parameters(const Params & params) const', '{']
    checks = cparams.validate_lines(plan, 'params', '  ')
    if not any('params' in line for line in checks):
        # parameters without validators: nothing reads it (-Wunused-parameter)
        lines.append('  (void)params;')
    lines += checks
    lines += ['}', '',
              f'rcl_interfaces::msg::SetParametersResult {c}::on_set_parameters(',
              '  const std::vector<rclcpp::Parameter> & parameters)', '{',
              '  // Validate the whole batch against a candidate; commit in on_post_set_parameters.',
              '  Params candidate = params();',
              '  for (const auto & parameter : parameters) {',
              '    bool known = false;']
    lines += cparams.assign_lines(plan, 'candidate', 'parameter', '    ')
    lines += ['    (void)known;', '  }',
              '  rcl_interfaces::msg::SetParametersResult result;',
              '  result.reason = validate_parameters(candidate);',
              '  result.successful = result.reason.empty();',
              '  return result;', '}', '',
              f'void {c}::on_post_set_parameters(const std::vector<rclcpp::Parameter> & parameters)',
              '{', '  Params snapshot;', '  {',
              '    std::lock_guard<std::mutex> lock(params_mutex_);',
              '    bool changed = false;',
              '    for (const auto & parameter : parameters) {',
              '      bool known = false;']
    lines += cparams.assign_lines(plan, 'params_', 'parameter', '      ')
    lines += ['      changed = changed || known;', '    }',
              '    if (!changed) {', '      return;', '    }',
              f'    ++params_.{cparams.REVISION_FIELD};', '    snapshot = params_;', '  }',
              '  on_parameters_changed(snapshot);', '}', '',
              f'{c}::Params {c}::params() const', '{',
              '  std::lock_guard<std::mutex> lock(params_mutex_);', '  return params_;', '}', '',
              f'bool {c}::is_old(const Params & params) const', '{',
              '  std::lock_guard<std::mutex> lock(params_mutex_);',
              f'  return params.{cparams.REVISION_FIELD} != params_.{cparams.REVISION_FIELD};',
              '}', '',
              f'bool {c}::try_update(Params & params) const', '{',
              '  std::lock_guard<std::mutex> lock(params_mutex_);',
              f'  if (params.{cparams.REVISION_FIELD} == params_.{cparams.REVISION_FIELD}) {{',
              '    return false;', '  }', '  params = params_;', '  return true;', '}', '',
              f'void {c}::on_parameters_changed(const Params & /*params*/)', '{', '}', '',
              f'void {c}::create_entities()', '{']
    lines += _create_lines(node)
    lines += ['}', '', f'void {c}::reset_entities()', '{']
    lines += [f'  {e.member}.reset();' for e in node.endpoints]
    lines += ['}', '']
    if node.lifecycle:
        lines += _lifecycle_lines(node)
    lines += [f'}}  // namespace {node.namespace}']
    return '\n'.join(lines) + '\n'
