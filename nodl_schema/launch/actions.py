"""Launch actions: what the frontends (XML, YAML, Python) build and the walk executes.

Each class reproduces what its ``launch``/``launch_ros`` namesake does at launch time,
without starting anything: a :class:`Node` adds a
:class:`~nodl_schema.launch.model.LaunchedNode` to the result instead of a process.
"""

from __future__ import annotations

import os
from typing import Any

from nodl_schema.launch.errors import LaunchProblem
from nodl_schema.launch.model import LaunchArgument, LaunchedNode, ParameterSource, SourceLocation
from nodl_schema.launch.params import ParameterValue, evaluate_value, normalize_python_dict
from nodl_schema.launch.substitutions import Substitution, normalize, perform, yaml_bool

TYPE_CHECKING = False
if TYPE_CHECKING:
    from nodl_schema.launch.context import LaunchContext

__all__ = ['Condition', 'IfCondition', 'UnlessCondition', 'LaunchConfigurationEquals',
           'LaunchConfigurationNotEquals', 'Action', 'LaunchDescription', 'DeclareLaunchArgument',
           'SetLaunchConfiguration', 'UnsetLaunchConfiguration', 'GroupAction',
           'IncludeLaunchDescription', 'PushRosNamespace', 'SetRemap', 'SetParameter',
           'SetParametersFromFile', 'SetEnvironmentVariable', 'UnsetEnvironmentVariable',
           'AppendEnvironmentVariable', 'Node', 'ComposableNode', 'ComposableNodeContainer',
           'LoadComposableNodes', 'Unevaluated', 'Ignored', 'Container', 'ParameterFileEntry',
           'make_namespace_absolute', 'prefix_namespace']


# -- conditions ------------------------------------------------------------------------------

class Condition:
    """Decides whether an action runs."""

    def evaluate(self, context: LaunchContext) -> bool:
        """True if the action runs."""
        raise NotImplementedError


def _condition_value(context: LaunchContext, expression: list[Substitution]) -> bool:
    text = perform(context, expression).strip().lower()
    if text in ('true', '1'):
        return True
    if text in ('false', '0'):
        return False
    raise LaunchProblem('NODL514', f"condition expression '{text}' is neither true nor false; "
                                   "expected 'true', 'false', '1' or '0' (any case)")


class IfCondition(Condition):
    """``if="..."``: runs when the expression is true."""

    def __init__(self, predicate_expression: Any) -> None:
        self.expression = normalize(predicate_expression)

    def evaluate(self, context: LaunchContext) -> bool:
        return _condition_value(context, self.expression)


class UnlessCondition(IfCondition):
    """``unless="..."``: runs when the expression is false."""

    def evaluate(self, context: LaunchContext) -> bool:
        return not _condition_value(context, self.expression)


class LaunchConfigurationEquals(Condition):
    """Runs when a launch configuration equals a value (None: the configuration is unset)."""

    def __init__(self, launch_configuration_name: str, expected_value: Any) -> None:
        self.name = launch_configuration_name
        self.expected = None if expected_value is None else normalize(expected_value)

    def evaluate(self, context: LaunchContext) -> bool:
        value = context.configurations.get(self.name)
        expected = None if self.expected is None else perform(context, self.expected)
        return (value if isinstance(value, str) else None) == expected


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    """The opposite of :class:`LaunchConfigurationEquals`."""

    def evaluate(self, context: LaunchContext) -> bool:
        return not super().evaluate(context)


# -- actions ---------------------------------------------------------------------------------

class Action:
    """A launch entity: a condition, a location, and what it does when executed."""

    location: SourceLocation = SourceLocation('', 0, 0)
    condition: Condition | None = None

    def execute(self, context: LaunchContext) -> list[Action] | None:
        """Do what launch would do; return the entities to visit next."""
        return None


class LaunchDescription(Action):
    """A list of entities (a launch file's content)."""

    def __init__(self, initial_entities: Any = None, *, deprecated_reason: str | None = None) -> None:
        self.entities: list[Any] = list(initial_entities or [])

    def add_action(self, action: Any) -> None:
        """Append an action."""
        self.entities.append(action)

    add_entity = add_action

    def execute(self, context: LaunchContext) -> list[Action] | None:
        return list(self.entities)


class DeclareLaunchArgument(Action):
    """``arg``: a value given by the includer, or the default; checked against ``choices``."""

    def __init__(self, name: str, *, default_value: Any = None, description: str = '',
                 choices: Any = None, **_: Any) -> None:
        self.name = name
        self.default_value = None if default_value is None else normalize(default_value)
        self.description = description
        self.choices = None if choices is None else [str(c) for c in choices]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        value = context.configurations.get(self.name)
        argument = LaunchArgument(self.name, self.location, None, self.description,
                                  tuple(self.choices) if self.choices is not None else None)
        if not isinstance(value, str):
            if self.default_value is None:
                context.declare(argument)
                raise LaunchProblem('NODL506', f"required launch argument '{self.name}' was not "
                                               f'provided; pass {self.name}:=VALUE')
            value = perform(context, self.default_value)
            context.configurations[self.name] = value
        if self.default_value is not None:
            try:
                argument.default = perform(context, self.default_value)
            except LaunchProblem:
                argument.default = None
        argument.value = value
        context.declare(argument)
        if self.choices is not None and value not in self.choices:
            from nodl_schema.validation.messages import did_you_mean

            raise LaunchProblem('NODL505', f"argument '{self.name}' has value '{value}', which is "
                                           f'not one of its choices: {", ".join(self.choices)}'
                                           f'{did_you_mean(value, self.choices)}')
        return None


class SetLaunchConfiguration(Action):
    """``let``: set a launch configuration in the current scope."""

    def __init__(self, name: Any, value: Any, **_: Any) -> None:
        self.name, self.value = normalize(name), normalize(value)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.configurations[perform(context, self.name)] = perform(context, self.value)
        return None


class UnsetLaunchConfiguration(Action):
    """Remove a launch configuration."""

    def __init__(self, name: Any, **_: Any) -> None:
        self.name = normalize(name)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.configurations.pop(perform(context, self.name), None)
        return None


class _Push(Action):
    def __init__(self, forwarding: bool, keep: list[tuple[Any, Any]]) -> None:
        self.forwarding, self.keep = forwarding, keep

    def execute(self, context: LaunchContext) -> list[Action] | None:
        values = [(perform(context, k), perform(context, v)) for k, v in self.keep]
        context.push_configurations()
        context.push_environment()
        if not self.forwarding:
            context.reset_configurations({})
        for name, value in values:
            context.configurations[name] = value
        return None


class _Pop(Action):
    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.pop_environment()
        context.pop_configurations()
        return None


class GroupAction(Action):
    """``group``: its actions, scoped (by default) or not, forwarding configurations or not."""

    def __init__(self, actions: Any, *, scoped: bool = True, forwarding: bool = True,
                 launch_configurations: Any = None, **_: Any) -> None:
        self.actions = list(actions)
        self.scoped, self.forwarding = scoped, forwarding
        self.keep = [(normalize(k), normalize(v)) for k, v in dict(launch_configurations or {}).items()]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        if not self.scoped:
            sets: list[Action] = [SetLaunchConfiguration(k, v) for k, v in self.keep]
            return sets + self.actions
        return [_Push(self.forwarding, self.keep), *self.actions, _Pop()]


class IncludeLaunchDescription(Action):
    """``include``: another launch file, its arguments set in the *current* scope (not scoped)."""

    def __init__(self, launch_description_source: Any, *, launch_arguments: Any = None, **_: Any) -> None:
        location = getattr(launch_description_source, 'location', launch_description_source)
        self.path = normalize(location)
        self.launch_arguments = [(normalize(k), normalize(v)) for k, v in
                                 (launch_arguments.items() if isinstance(launch_arguments, dict)
                                  else launch_arguments or [])]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        from nodl_schema.launch.evaluate import include

        return include(context, self)


class PushRosNamespace(Action):
    """``push-ros-namespace``: relative namespaces of later nodes in scope are prefixed."""

    def __init__(self, namespace: Any, **_: Any) -> None:
        self.namespace = normalize(namespace)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        from nodl_schema.naming import namespace_error

        pushed = perform(context, self.namespace)
        previous = context.configurations.get('ros_namespace')
        namespace = make_namespace_absolute(prefix_namespace(previous, pushed))
        problem = namespace_error(namespace or '/')
        if problem:
            raise LaunchProblem('NODL519', f"the resulting namespace '{namespace}' is invalid: "
                                           f'{problem} (previous {previous!r}, pushed {pushed!r})')
        context.configurations['ros_namespace'] = namespace
        return None


class SetRemap(Action):
    """``set_remap``: a rule every later node in scope gets before its own."""

    def __init__(self, src: Any, dst: Any, **_: Any) -> None:
        self.src, self.dst = normalize(src), normalize(dst)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        rule = (perform(context, self.src), perform(context, self.dst))
        remaps = context.configurations.get('ros_remaps', [])
        remaps.append(rule)  # in place, as launch_ros does (see context.py)
        context.configurations['ros_remaps'] = remaps
        return None


class SetParameter(Action):
    """``set_parameter``: a parameter every later node in scope gets (before its own)."""

    def __init__(self, name: Any, value: Any, **_: Any) -> None:
        self.name = normalize(name)
        # As normalize_parameter_dict: text stays text, substitutions are read as YAML.
        self.value = value if isinstance(value, ParameterValue) else normalize_python_dict({'_': value})[0][1]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        name = perform(context, self.name)
        value = evaluate_value(context, self.value, name)
        params = context.configurations.get('global_params', [])
        params.append((name, value))
        context.configurations['global_params'] = params
        return None


class SetParametersFromFile(Action):
    """``set_parameters_from_file``: a parameter file every later node in scope gets."""

    def __init__(self, filename: Any, **_: Any) -> None:
        self.filename = normalize(filename)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        params = context.configurations.get('global_params', [])
        params.append(perform(context, self.filename))
        context.configurations['global_params'] = params
        return None


class SetEnvironmentVariable(Action):
    """``set_env``."""

    def __init__(self, name: Any, value: Any, **_: Any) -> None:
        self.name, self.value = normalize(name), normalize(value)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.environment[perform(context, self.name)] = perform(context, self.value)
        return None


class UnsetEnvironmentVariable(Action):
    """``unset_env``."""

    def __init__(self, name: Any, **_: Any) -> None:
        self.name = normalize(name)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.environment.pop(perform(context, self.name), None)
        return None


class AppendEnvironmentVariable(Action):
    """``append_env``."""

    def __init__(self, name: Any, value: Any, *, prepend: bool = False, separator: str = os.pathsep,
                 **_: Any) -> None:
        self.name, self.value = normalize(name), normalize(value)
        self.prepend, self.separator = prepend, separator

    def execute(self, context: LaunchContext) -> list[Action] | None:
        name, value = perform(context, self.name), perform(context, self.value)
        old = context.environment.get(name)
        if old:
            value = f'{value}{self.separator}{old}' if self.prepend else f'{old}{self.separator}{value}'
        context.environment[name] = value
        return None


class Ignored(Action):
    """An action that starts no node and changes nothing analysed (``log``, ``executable``...)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self.actions = [a for a in kwargs.get('actions', []) if isinstance(a, Action)]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        return list(self.actions)


class Unevaluated(Action):
    """Something only a running launch can evaluate (``OpaqueFunction``, an unknown action)."""

    def __init__(self, what: str) -> None:
        self.what = what

    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.warn('NODL512', f'{self.what} cannot be evaluated without running the launch; '
                                'nodes it would start are missing from the analysis', self.location)
        return None


# -- nodes -----------------------------------------------------------------------------------

def prefix_namespace(base: str | None, namespace: str | None) -> str | None:
    """launch_ros's ``prefix_namespace``: ``namespace`` under ``base`` unless it is absolute."""
    if base is None and namespace is None:
        return None
    if namespace is None:
        combined = base
    elif not base or namespace.startswith('/'):
        combined = namespace
    else:
        combined = ('' if base == '/' else base) + '/' + namespace
    assert combined is not None
    return combined if combined == '/' else combined.rstrip('/')


def make_namespace_absolute(namespace: str | None) -> str | None:
    """A leading ``/`` for a relative namespace."""
    if namespace is None:
        return None
    return namespace if namespace.startswith('/') else '/' + namespace


class ParameterFileEntry:
    """A parameter file in a node's ``parameters`` (``param from=``, a path, ``ParameterFile``)."""

    def __init__(self, param_file: Any, allow_substs: Any = False) -> None:
        self.path = normalize(param_file)
        self.allow_substs = allow_substs


def _normalize_parameters(parameters: Any) -> list[Any]:
    out: list[Any] = []
    for item in parameters or []:
        if isinstance(item, dict):
            out.append(normalize_python_dict(item))
        elif isinstance(item, ParameterFileEntry) or (isinstance(item, list) and item and
                                                       isinstance(item[0], tuple)):
            out.append(item)
        elif hasattr(item, 'nodl_parameter'):
            out.append(item)
        else:
            out.append(ParameterFileEntry(item))
    return out


def _ros_arguments(context: LaunchContext, node: Any, location: SourceLocation,
                   record: LaunchedNode) -> None:
    """Split ``arguments`` + ``--ros-args`` + ``ros_arguments`` as rcl reads a command line."""
    words = [perform(context, a) for a in node.arguments]
    if node.ros_arguments:
        words += ['--ros-args', *[perform(context, a) for a in node.ros_arguments]]
    in_ros = False
    i = 0
    while i < len(words):
        word = words[i]
        if word == '--ros-args':
            in_ros = True
        elif word == '--' and in_ros:
            in_ros = False
        elif not in_ros:
            record.arguments.append(word)
        elif word in ('-r', '--remap', '-p', '--param', '--params-file') and i + 1 < len(words):
            value = words[i + 1]
            i += 1
            if word in ('-r', '--remap'):
                if ':=' not in value:
                    raise LaunchProblem('NODL519', f"invalid remapping rule '{value}' in the node's "
                                                   'arguments; expected FROM:=TO')
                src, dst = value.split(':=', 1)
                record.remaps.append((src, dst))
            elif word in ('-p', '--param'):
                if ':=' not in value:
                    raise LaunchProblem('NODL518', f"invalid parameter rule '{value}'; expected NAME:=VALUE")
                name, text = value.split(':=', 1)
                import yaml

                try:
                    typed = yaml.safe_load(text) if text else ''
                except yaml.YAMLError:
                    typed = text
                record.parameters.append(ParameterSource('values', 'arguments', location,
                                                         values={name: typed}))
            else:
                record.parameters.append(ParameterSource('file', 'arguments', location,
                                                         path=os.path.abspath(value)))
        else:
            record.ros_arguments.append(word)
        i += 1


def _global_parameters(context: LaunchContext, location: SourceLocation) -> list[ParameterSource]:
    out = []
    for entry in context.configurations.get('global_params') or []:
        if isinstance(entry, tuple):
            out.append(ParameterSource('values', 'global', location, values={entry[0]: entry[1]}))
        else:
            out.append(ParameterSource('file', 'global', location, path=os.path.abspath(entry)))
    return out


def _own_parameters(context: LaunchContext, parameters: list[Any], location: SourceLocation,
                    node_key: str) -> list[ParameterSource]:
    out = []
    for item in parameters:
        if isinstance(item, ParameterFileEntry):
            path = perform(context, item.path)
            if not os.path.isfile(path):
                context.warn('NODL517', f"parameter file '{path}' is not a file; launch skips it", location)
                continue
            out.append(ParameterSource('file', 'node', location, path=path))
        elif hasattr(item, 'nodl_parameter'):
            name, spec = item.nodl_parameter
            pname = perform(context, name)
            out.append(ParameterSource('values', 'node', location,
                                       values={pname: evaluate_value(context, spec, pname)}))
        else:
            values: dict[str, Any] = {}
            for name, spec in item:
                pname = perform(context, name)
                values[pname] = evaluate_value(context, spec, pname)
            out.append(ParameterSource('values', 'node', location, values=values, node_key=node_key))
    return out


class Node(Action):
    """``node``: a ROS node started as a process."""

    kind = 'node'

    def __init__(self, *, executable: Any, package: Any = None, name: Any = None, namespace: Any = None,
                 parameters: Any = None, remappings: Any = None, ros_arguments: Any = None,
                 arguments: Any = None, **_: Any) -> None:
        self.executable = normalize(executable)
        self.package = None if package is None else normalize(package)
        self.name = None if name is None else normalize(name)
        self.namespace = None if namespace is None else normalize(namespace)
        self.parameters = _normalize_parameters(parameters)
        self.remappings = [(normalize(a), normalize(b)) for a, b in (remappings or [])]
        self.ros_arguments = list(ros_arguments or [])
        self.arguments = list(arguments or [])
        self.node_name: str | None = None

    def execute(self, context: LaunchContext) -> list[Action] | None:
        from nodl_schema.naming import namespace_error, node_name_error

        name = None
        if self.name is not None:
            name = perform(context, self.name)
            problem = node_name_error(name)
            if problem:
                raise LaunchProblem('NODL519', f"invalid node name '{name}': {problem}")
        given = None if self.namespace is None else perform(context, self.namespace)
        namespace = make_namespace_absolute(prefix_namespace(context.configurations.get('ros_namespace'),
                                                             given))
        if namespace is not None:
            problem = namespace_error(namespace)
            if problem:
                raise LaunchProblem('NODL519', f"invalid namespace '{namespace}': {problem}")
        record = LaunchedNode(self.kind, None if self.package is None else perform(context, self.package),
                              perform(context, self.executable), name, namespace or '/', self.location,
                              include_chain=context.include_chain, namespace_given=namespace is not None)
        _ros_arguments(context, self, self.location, record)
        fully = name is not None and namespace is not None
        fqn = ('' if namespace == '/' else (namespace or '')) + '/' + (name or '')
        self.node_name = fqn if name is not None else None
        record.parameters += _global_parameters(context, self.location)
        record.parameters += _own_parameters(context, self.parameters, self.location,
                                             fqn if fully else '/**')
        record.remaps += list(context.configurations.get('ros_remaps') or [])
        record.remaps += [(perform(context, a), perform(context, b)) for a, b in self.remappings]
        context.result.nodes.append(record)
        return self.after(context)

    def after(self, context: LaunchContext) -> list[Action] | None:
        """What follows the node (a container's composable nodes)."""
        return None


class ComposableNode:
    """``composable_node``: a node loaded into a container (not an action)."""

    def __init__(self, *, package: Any, plugin: Any, name: Any = None, namespace: Any = None,
                 parameters: Any = None, remappings: Any = None, extra_arguments: Any = None,
                 condition: Condition | None = None, **_: Any) -> None:
        self.package, self.plugin = normalize(package), normalize(plugin)
        self.name = None if name is None else normalize(name)
        self.namespace = None if namespace is None else normalize(namespace)
        self.parameters = _normalize_parameters(parameters)
        self.remappings = [(normalize(a), normalize(b)) for a, b in (remappings or [])]
        self.condition = condition
        self.location = SourceLocation('', 0, 0)


class LoadComposableNodes(Action):
    """``load_composable_node``: composable nodes loaded into a target container."""

    def __init__(self, *, composable_node_descriptions: Any, target_container: Any, **_: Any) -> None:
        self.descriptions = list(composable_node_descriptions)
        self.target = target_container

    def execute(self, context: LaunchContext) -> list[Action] | None:
        if isinstance(self.target, Node):
            container = self.target.node_name or ''
        else:
            container = perform(context, self.target)
            if container and not container.startswith('/'):
                container = '/' + container
        for description in self.descriptions:
            try:
                _load(context, description, container)
            except LaunchProblem as problem:
                context.problem(problem, description.location)
        return None


def _load(context: LaunchContext, description: ComposableNode, container: str) -> None:
    if description.condition is not None and not description.condition.evaluate(context):
        return
    name = None if description.name is None else perform(context, description.name)
    given = None if description.namespace is None else perform(context, description.namespace)
    namespace = make_namespace_absolute(prefix_namespace(context.configurations.get('ros_namespace'), given))
    record = LaunchedNode('composable', perform(context, description.package), None, name,
                          namespace or '/', description.location, plugin=perform(context, description.plugin),
                          container=container, include_chain=context.include_chain,
                          namespace_given=namespace is not None)
    record.remaps += list(context.configurations.get('ros_remaps') or [])
    record.remaps += [(perform(context, a), perform(context, b)) for a, b in description.remappings]
    record.parameters += _global_parameters(context, description.location)
    record.parameters += _own_parameters(context, description.parameters, description.location, '/**')
    context.result.nodes.append(record)


class ComposableNodeContainer(Node):
    """``node_container``: a container process, then its composable nodes."""

    kind = 'container'

    def __init__(self, *, name: Any, namespace: Any, composable_node_descriptions: Any = None,
                 **kwargs: Any) -> None:
        super().__init__(name=name, namespace=namespace, **kwargs)
        self.descriptions = list(composable_node_descriptions or [])

    def after(self, context: LaunchContext) -> list[Action] | None:
        if not self.descriptions:
            return None
        load = LoadComposableNodes(composable_node_descriptions=self.descriptions, target_container=self)
        load.location = self.location
        return [load]


Container = ComposableNodeContainer
