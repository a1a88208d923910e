"""The Python (rclpy) generator: ``nodl generate DEFINITION --language python``.

One module, ``<node>_base.py``, holding

* ``<Name>Params`` (and a class per nested group): the typed parameter snapshot;
* ``<Name>Base(Node)`` or ``<Name>Base(LifecycleNode)``: declares every
  parameter of the implementation with its descriptor, enforces required
  parameters and every validator at start-up and at set time (validation in
  the on-set callback, commit in the post-set callback), creates every
  endpoint the implementation provides with its declared QoS, and leaves the
  callbacks abstract.

The module imports rclpy and the interface packages only: no runtime
dependency on the toolkit.  Output is deterministic.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nodl.composition.entities import Entity, EntityKind, InterfaceType
from nodl.generate import GeneratedFile, GenerateOptions, GenerationError, GeneratorExtension
from nodl.generate.python_text import (
    LINE_LENGTH,
    comment,
    docstring,
    literal,
    mark_long_lines,
    python_value,
    validator_expression,
)
from nodl.plan.identifiers import PYTHON_KEYWORDS, IdentifierScope
from nodl.plan.parameter_plan import ParameterPlan, ParametersPlan, StructPlan, plan_parameters
from nodl.vocabulary import QOS_DURATIONS, QOS_ENUMS

if TYPE_CHECKING:
    from nodl.system import ResolvedNode

__all__ = ['PythonGenerator', 'generate_python', 'ATTRIBUTE_PREFIXES', 'RESERVED_MEMBERS']

#: Entity kind -> the attribute that holds its handle (``pub_<name>``).
ATTRIBUTE_PREFIXES: dict[EntityKind, str] = {
    EntityKind.PUBLISHER: 'pub_{}',
    EntityKind.SUBSCRIPTION: 'sub_{}',
    EntityKind.SERVICE_SERVER: 'srv_{}',
    EntityKind.SERVICE_CLIENT: 'cli_{}',
    EntityKind.ACTION_SERVER: 'action_server_{}',
    EntityKind.ACTION_CLIENT: 'action_client_{}',
}

#: Members of the generated base and of rclpy's lifecycle node a generated name must not take.
RESERVED_MEMBERS: frozenset[str] = frozenset({
    'params', 'is_old', 'try_update', 'on_parameters_changed', 'on_custom_validator',
    'on_configure', 'on_activate', 'on_deactivate', 'on_cleanup', 'on_shutdown', 'on_error',
})

_HANDLE_TYPES = {
    EntityKind.PUBLISHER: 'Publisher', EntityKind.SUBSCRIPTION: 'Subscription',
    EntityKind.SERVICE_SERVER: 'Service', EntityKind.SERVICE_CLIENT: 'Client',
    EntityKind.ACTION_SERVER: 'ActionServer', EntityKind.ACTION_CLIENT: 'ActionClient',
}

_PY_TYPES = {'bool': 'bool', 'int': 'int', 'double': 'float', 'string': 'str', 'none': 'Any',
             'bool_array': 'list[bool]', 'int_array': 'list[int]', 'double_array': 'list[float]',
             'string_array': 'list[str]', 'byte_array': 'bytes'}


def _type_ref(entity: Entity) -> str:
    it = entity.type
    if not isinstance(it, InterfaceType):
        raise GenerationError(f'{entity.location}: {entity.kind.word} {entity.name!r} has the type '
                              f'{entity.type_name!r}, not <package>/<namespace>/<Name>')
    return f'{it.package}.{it.namespace}.{it.name}'


def _type_args(entity: Entity) -> str:
    """The type arguments of the rclpy handle of ``entity`` (``Service[T.Request, T.Response]``)."""
    t = _type_ref(entity)
    if entity.kind.communication == 'service':
        return f'{t}.Request, {t}.Response'
    if entity.kind.communication == 'action':
        return f'{t}.Goal, {t}.Result, {t}.Feedback'
    return t


def _qos(entity: Entity) -> str | None:
    qos = entity.qos
    if qos is None:
        return None
    args: list[str] = []
    for key in QOS_ENUMS:  # every policy: an unset one is the system default
        value = getattr(qos, key)
        args.append(f'{key}={key.capitalize()}Policy.{value or "SYSTEM_DEFAULT"}')
        if key == 'history' and qos.depth is not None:
            args.append(f'depth={int(qos.depth)}')
    for key, policy in QOS_DURATIONS.items():
        value = getattr(qos, key)
        if value is not None:
            args.append(f'{policy}=Duration(nanoseconds={int(value)})')
    return 'QoSProfile(\n' + ''.join(f'    {a},\n' for a in args) + ')'


class _Module:
    """The pieces of one generated module."""

    def __init__(self, node: ResolvedNode, options: GenerateOptions) -> None:
        self.node = node
        self.options = options
        self.lifecycle = node.base is not None and node.base.value == 'lifecycle_node'
        entities = node.implementation_entities()
        self.parameters: ParametersPlan = plan_parameters(
            [e for e in entities if e.is_parameter], PYTHON_KEYWORDS)
        self.endpoints = [e for e in entities if not e.is_parameter]
        self.class_name = f'{options.class_name}Base'
        scope = IdentifierScope(RESERVED_MEMBERS, PYTHON_KEYWORDS)
        self.attributes: dict[tuple[EntityKind, str], str] = {}
        for kind, template in ATTRIBUTE_PREFIXES.items():
            names = [e.name for e in self.endpoints if e.kind is kind]
            for name, ident in scope.assign(names, template).items():
                self.attributes[(kind, name)] = ident
        self.callbacks: dict[tuple[EntityKind, str], dict[str, str]] = {}
        for kind in (EntityKind.SUBSCRIPTION, EntityKind.SERVICE_SERVER):
            names = [e.name for e in self.endpoints if e.kind is kind]
            for name, ident in scope.assign(names, 'on_{}').items():
                self.callbacks[(kind, name)] = {'callback': ident}
        servers = [e.name for e in self.endpoints if e.kind is EntityKind.ACTION_SERVER]
        goals = scope.assign(servers, 'on_{}_goal')
        cancels = scope.assign(servers, 'on_{}_cancel')
        executes = scope.assign(servers, 'execute_{}')
        for name in servers:
            self.callbacks[(EntityKind.ACTION_SERVER, name)] = {
                'goal': goals[name], 'cancel': cancels[name], 'execute': executes[name]}
        constants = IdentifierScope((), PYTHON_KEYWORDS)
        self.qos_names: dict[tuple[EntityKind, str], str] = {}
        for kind, template in ATTRIBUTE_PREFIXES.items():
            names = [e.name for e in self.endpoints if e.kind is kind and e.qos is not None]
            for name, ident in constants.assign(names, '_qos_' + template).items():
                self.qos_names[(kind, name)] = ident.upper()
        classes = IdentifierScope((self.class_name,), PYTHON_KEYWORDS)
        self.struct_classes: dict[tuple[str, ...], str] = {}
        for struct in self.parameters.root.walk():
            stem = ''.join(part.strip('_').capitalize() for part in struct.path)
            self.struct_classes[struct.path] = classes.unique(f'{options.class_name}{stem}Params')

    # -- text --------------------------------------------------------------------------------

    def text(self) -> str:
        """The module's source."""
        parts = [self.header() + self.mapping_comment() + '\n' + self.imports() + '\n\n' + _helpers(self)]
        for struct in reversed(list(self.parameters.root.walk())):
            parts.append(self.struct_class(struct))
        parts.append(self.qos_constants())
        parts.append(self.parameter_tables())
        parts.append(self.base_class())
        return mark_long_lines('\n\n\n'.join(p.rstrip('\n') for p in parts if p) + '\n')

    def header(self) -> str:
        source = self.node.file.replace('\\', '/').rsplit('/', 1)[-1]
        desc = self.node.interface.description or ''
        return (f'# Generated by `nodl generate --language python` from {source}; do not edit.\n'
                '# Regenerate it after changing the definition; implement the node in a subclass.\n'
                + docstring(f'The generated base of the {self.options.node_name} node: '
                            f'{self.class_name}.\n\n{desc}'))

    def imports(self) -> str:
        lines = ['from __future__ import annotations', '', 'import abc',
                 'from typing import Any, Callable', '']
        # the other imports are one group sorted by module, `import` and `from` mixed
        # (flake8-import-order's google style, which ament_flake8 configures)
        interface_modules = sorted({_type_ref(e).rsplit('.', 1)[0] for e in self.endpoints})
        others = [(m.lower(), f'import {m}') for m in interface_modules]
        kinds = {e.kind for e in self.endpoints}
        names: dict[str, set[str]] = {
            'rcl_interfaces.msg': {'SetParametersResult'}, 'rclpy.parameter': {'Parameter'},
            'rclpy.exceptions': {'ParameterUninitializedException'}}
        params = self.parameters.parameters
        if params:
            names['rcl_interfaces.msg'].update({'ParameterDescriptor', 'ParameterType'})
        for kind, cls in (('integer', 'IntegerRange'), ('floating_point', 'FloatingPointRange')):
            if any(p.range is not None and p.range.kind == kind for p in params):
                names['rcl_interfaces.msg'].add(cls)
        if EntityKind.ACTION_CLIENT in kinds:
            names['rclpy.action.client'] = {'ActionClient'}
        if EntityKind.ACTION_SERVER in kinds:
            names['rclpy.action.server'] = {'ActionServer', 'CancelResponse', 'GoalResponse',
                                            'ServerGoalHandle'}
        if any(e.qos is not None and getattr(e.qos, k) is not None
               for e in self.endpoints for k in QOS_DURATIONS):
            names['rclpy.duration'] = {'Duration'}
        if self.lifecycle:
            names['rclpy.lifecycle'] = {'LifecycleNode', 'LifecycleState', 'TransitionCallbackReturn'}
            if EntityKind.PUBLISHER in kinds:
                names['rclpy.lifecycle'].add('LifecyclePublisher')
        else:
            names['rclpy.node'] = {'Node'}
            if EntityKind.PUBLISHER in kinds:
                names['rclpy.publisher'] = {'Publisher'}
        if any(e.qos is not None for e in self.endpoints):
            names['rclpy.qos'] = {f'{k.capitalize()}Policy' for k in QOS_ENUMS} | {'QoSProfile'}
        for kind, module in ((EntityKind.SERVICE_SERVER, 'rclpy.service'),
                             (EntityKind.SERVICE_CLIENT, 'rclpy.client'),
                             (EntityKind.SUBSCRIPTION, 'rclpy.subscription')):
            if kind in kinds:
                names[module] = {_HANDLE_TYPES[kind]}
        for module in sorted(names):
            items = sorted(names[module], key=str.lower)
            one_line = f'from {module} import {", ".join(items)}'
            if len(one_line) <= 99:
                others.append((module.lower(), one_line))
            else:
                others.append((module.lower(), f'from {module} import (\n'
                               + ''.join(f'    {i},\n' for i in items) + ')'))
        lines += [line for _, line in sorted(others)]
        return '\n'.join(lines)

    def qos_constants(self) -> str:
        out = ''
        for e in self.endpoints:
            text = _qos(e)
            if text is not None:
                out += f'{self.qos_names[(e.kind, e.name)]} = {text}\n'
        return out

    def mapping_comment(self) -> str:
        if not self.endpoints:
            return ''
        out = '\n# Declared name -> attribute of the generated class:\n'
        for e in self.endpoints:
            line = f'#   {e.kind.word} {e.name!r} ({e.type_name}) -> self.{self.attributes[(e.kind, e.name)]}'
            if len(line) > LINE_LENGTH:
                line = line.replace(') -> self.', ')\n#     -> self.', 1)
            out += line + '\n'
        return out

    # -- parameters ----------------------------------------------------------------------

    def struct_class(self, struct: StructPlan) -> str:
        name = self.struct_classes[struct.path]
        what = f'the parameters under {struct.prefix!r}' if struct.prefix else \
            f'every parameter of {self.options.node_name}'
        out = f'class {name}:\n' + docstring(f'A snapshot of {what}.', '    ')
        slots = [m.field for m in struct.members]
        if not struct.path:
            slots.append('_nodl_stamp')
        out += '\n' + _wrap('    __slots__ = (', [literal(s) + ',' for s in slots], ')') + '\n'
        body = []
        for member in struct.members:
            if isinstance(member, StructPlan):
                body.append(f'        self.{member.field}: {self.struct_classes[member.path]} = '
                            f'{self.struct_classes[member.path]}()')
            else:
                text = member.description
                if text:
                    body.append(comment(text, '        ').rstrip('\n'))
                body.append(f'        self.{member.field}: {_PY_TYPES[member.type.base]} = '
                            f'{self._initial(member)}')
        if not struct.path:
            body.append('        self._nodl_stamp = 0')
        out += '\n    def __init__(self) -> None:\n' + ('\n'.join(body) or '        pass') + '\n'
        return out

    @staticmethod
    def _initial(p: ParameterPlan) -> str:
        if p.default is None:
            return {'bool': 'False', 'int': '0', 'double': '0.0', 'string': "''",
                    'byte_array': "b''", 'none': 'None'}.get(p.type.base, '[]')
        if p.type.base == 'byte_array':
            return literal(bytes(p.default))
        return literal(python_value(p.default, p.type.base))

    def parameter_tables(self) -> str:
        params = self.parameters.parameters
        out = ('#: Built-in validators per parameter: (predicate over the value, requirement).\n'
               '_VALIDATORS: dict[str, tuple[tuple[Callable[[Any], bool], str], ...]] = {\n')
        for p in params:
            checks = [_wrap('        (', [f'lambda v: {validator_expression(v.name, v.argument)},',
                                         f'{literal(v.requirement)},'], '),')
                      for v in p.builtin_validators]
            if p.type.size is not None:
                checks.insert(0, f'        (lambda v: len(v) <= {p.type.size}, {literal(p.size_requirement)}),')
            if checks:
                out += f'    {literal(p.name)}: (\n' + ''.join(f'{c}\n' for c in checks) + '    ),\n'
        out += '}\n\n#: Custom validators per parameter: (function name, arguments as written).\n'
        out += '_CUSTOM_VALIDATORS: dict[str, tuple[tuple[str, Any], ...]] = {\n'
        for p in params:
            if p.custom_validators:
                items = ''.join(f'({literal(v.name)}, {literal(v.raw)}), ' for v in p.custom_validators)
                out += f'    {literal(p.name)}: ({items.rstrip(" ")}),\n'
        out += '}\n'
        return out

    # -- the base class ------------------------------------------------------------------------

    def base_class(self) -> str:
        base = 'LifecycleNode' if self.lifecycle else 'Node'
        params_class = self.struct_classes[()]
        desc = self.node.interface.description or ''
        doc = (f'The generated base of the {self.options.node_name} node.\n\nSubclass it and '
               'implement the abstract callbacks.\n\n' + desc).strip()
        if self.lifecycle:
            doc += ('\n\nEndpoints are created in on_configure and destroyed in on_cleanup and '
                    'on_shutdown; publishers are lifecycle publishers that publish only while the '
                    'node is active. Override a transition hook and call super() first.')
        out = f'class {self.class_name}({base}, metaclass=abc.ABCMeta):\n' + docstring(doc, '    ') + '\n'
        out += f'    params: {params_class}\n'
        for e in self.endpoints:
            handle = 'LifecyclePublisher' if self.lifecycle and e.kind is EntityKind.PUBLISHER \
                else _HANDLE_TYPES[e.kind]
            out += _wrap(f'    {self.attributes[(e.kind, e.name)]}: {handle}[',
                         [a.strip() + ',' for a in _type_args(e).split(',')], ']') + '\n'
        out += self.constructor() + self.parameter_methods() + self.entity_methods()
        out += self.lifecycle_methods() + self.callback_methods()
        return out

    def constructor(self) -> str:
        out = (f'\n    def __init__(self, node_name: str = {literal(self.options.node_name)}, '
               '**kwargs: Any) -> None:\n'
               '        super().__init__(node_name, **kwargs)\n'
               '        self._nodl_values: dict[str, Any] = {}\n'
               f'        self.params = {self.struct_classes[()]}()\n'
               '        self._nodl_declare_parameters()\n'
               '        self.add_on_set_parameters_callback(self._nodl_validate_parameters)\n'
               '        self.add_post_set_parameters_callback(self._nodl_commit_parameters)\n')
        if not self.lifecycle:
            out += '        self._nodl_create_entities()\n'
        return out

    def parameter_methods(self) -> str:
        params = self.parameters.parameters
        out = '\n    def _nodl_declare_parameters(self) -> None:\n'
        if not params:
            out += '        pass\n'
        for p in params:
            out += f'        descriptor = ParameterDescriptor(\n            type=ParameterType.{p.ros_type},\n'
            if p.description:
                out += f'            description={literal(p.description)},\n'
            if p.constraints_text:
                line = f'            additional_constraints={literal(p.constraints_text)},\n'
                out += line if len(line) <= LINE_LENGTH + 1 else (
                    f'            additional_constraints=(\n                {literal(p.constraints_text)}\n'
                    '            ),\n')
            if p.read_only:
                out += '            read_only=True,\n'
            if p.dynamic_typing:
                out += '            dynamic_typing=True,\n'
            if p.range is not None:
                cls = 'IntegerRange' if p.range.kind == 'integer' else 'FloatingPointRange'
                out += _wrap(f'            {p.range.kind}_range=[{cls}(',
                             [f'from_value={literal(p.range.from_value)},',
                              f'to_value={literal(p.range.to_value)},', f'step={literal(p.range.step)},'],
                             ')],') + '\n'
            out += '        )\n'
            type_arg = f'Parameter.Type.{p.ros_type[len("PARAMETER_"):]}'
            if p.dynamic_typing:
                out += f'        self.declare_parameter({literal(p.name)}, None, descriptor)\n'
            elif p.required or p.default == []:
                out += f'        self.declare_parameter({literal(p.name)}, {type_arg}, descriptor)\n'
                if not p.required:
                    out += (f'        if self._nodl_initial_value({literal(p.name)}) is None:\n'
                            f'            super().set_parameters([Parameter({literal(p.name)}, {type_arg}, [])])\n')
            else:
                out += (f'        self.declare_parameter({literal(p.name)}, '
                        f'{literal(python_value(p.default, p.type.base))}, descriptor)\n')
        out += ('        values = {name: self._nodl_initial_value(name) for name in sorted(_PARAMETER_NAMES)}\n'
                '        missing = [name for name, value in values.items() if value is None\n'
                '                   and name not in _DYNAMIC]\n'
                '        if missing:\n'
                '            raise ParameterError(\'\\n\'.join(\n'
                "                f'{self.get_name()}: required parameter {name!r} ({_TYPES[name]}) is not set: '\n"
                "                f'pass it with --ros-args -p {name}:=VALUE or a parameter file'\n"
                '                for name in missing))\n'
                '        values = {name: _normalized(value) for name, value in values.items()}\n'
                '        problems = self._nodl_problems(values, values)\n'
                '        if problems:\n'
                '            raise ParameterError(\'\\n\'.join(\n'
                "                f'{self.get_name()}: invalid {problem}' for problem in problems))\n"
                '        self._nodl_commit(values)\n')
        out += '''
    def _nodl_initial_value(self, name: str) -> Any:
        try:
            return self.get_parameter(name).value
        except ParameterUninitializedException:  # a required parameter that was not given
            return None

    def _nodl_problems(self, values: dict[str, Any], changed: dict[str, Any]) -> list[str]:
        problems = []
        for name in sorted(changed):
            value = values[name]
            for predicate, requirement in _VALIDATORS.get(name, ()):
                if not predicate(value):
                    problems.append(f'parameter {name!r} = {value!r}: {requirement}')
            for function, arguments in _CUSTOM_VALIDATORS.get(name, ()):
                why = self.on_custom_validator(function, name, value, arguments)
                if why:
                    problems.append(f'parameter {name!r} = {value!r}: {why}')
        return problems

    def _nodl_validate_parameters(self, parameters: list[Parameter[Any]]) -> SetParametersResult:
        changed = {p.name: _normalized(p.value) for p in parameters if p.name in _PARAMETER_NAMES}
        problems = self._nodl_problems({**self._nodl_values, **changed}, changed)
        return SetParametersResult(successful=not problems, reason='; '.join(problems))

    def _nodl_commit_parameters(self, parameters: list[Parameter[Any]]) -> None:
        changed = {p.name: _normalized(p.value) for p in parameters if p.name in _PARAMETER_NAMES}
        if changed:
            old = self.params
            self._nodl_commit({**self._nodl_values, **changed})
            self.on_parameters_changed(old, self.params)

    def _nodl_commit(self, values: dict[str, Any]) -> None:
        self._nodl_values = values
'''
        out += f'        params = {self.struct_classes[()]}()\n'
        for p in params:
            out += f'        params.{".".join(p.path)} = values[{literal(p.name)}]\n'
        out += '''        params._nodl_stamp = self.params._nodl_stamp + 1
        self.params = params

'''
        params_class = self.struct_classes[()]
        out += f'''    def set_parameters_atomically(
            self, parameter_list: list[Parameter[Any]]) -> SetParametersResult:
        """Validate first: a rejection gives the validator's reason (then set as rclpy does)."""
        declared = [p for p in parameter_list if p.name in _PARAMETER_NAMES and p.value is not None
                    and p.type_ == self.get_parameter(p.name).type_]
        result = self._nodl_validate_parameters(declared)
        if not result.successful:
            return result
        return super().set_parameters_atomically(parameter_list)

    def set_parameters(self, parameter_list: list[Parameter[Any]]) -> list[SetParametersResult]:
        """Set them one by one as set_parameters_atomically does (a rejection gives the reason)."""
        return [self.set_parameters_atomically([parameter]) for parameter in parameter_list]

    def is_old(self, params: {params_class}) -> bool:
        """Return True if ``params`` is not the newest snapshot."""
        return params._nodl_stamp != self.params._nodl_stamp

    def try_update(self, params: {params_class}) -> {params_class}:
        """Return the newest snapshot (``params`` itself if it is the newest)."""
        return self.params if self.is_old(params) else params

    def on_parameters_changed(self, old: {params_class}, new: {params_class}) -> None:
        """Handle a change of parameters: the previous and the new snapshot."""

    def on_custom_validator(
            self, function: str, name: str, value: Any, arguments: Any) -> str | None:
        """
        Check ``value`` with the custom validator ``function``: None if valid, else why not.

        Override it when the definition uses custom validators; until then they reject.
        """
        return f'the custom validator {{function}} is not implemented (override on_custom_validator)'
'''
        return out

    def entity_methods(self) -> str:
        out = '\n    def _nodl_create_entities(self) -> None:\n'
        if not self.endpoints:
            out += '        pass\n'
        for e in self.endpoints:
            attr = self.attributes[(e.kind, e.name)]
            args = [_type_ref(e), literal(e.name)]
            qos = self.qos_names.get((e.kind, e.name))
            call = {EntityKind.PUBLISHER: 'self.create_lifecycle_publisher' if self.lifecycle
                    else 'self.create_publisher',
                    EntityKind.SUBSCRIPTION: 'self.create_subscription',
                    EntityKind.SERVICE_SERVER: 'self.create_service',
                    EntityKind.SERVICE_CLIENT: 'self.create_client',
                    EntityKind.ACTION_SERVER: 'ActionServer',
                    EntityKind.ACTION_CLIENT: 'ActionClient'}[e.kind]
            if e.kind in (EntityKind.ACTION_SERVER, EntityKind.ACTION_CLIENT):
                args.insert(0, 'self')
            if e.kind in (EntityKind.SUBSCRIPTION, EntityKind.SERVICE_SERVER):
                args.append('self.' + self.callbacks[(e.kind, e.name)]['callback'])
            if e.kind is EntityKind.ACTION_SERVER:
                cbs = self.callbacks[(e.kind, e.name)]
                args += [f'execute_callback=self.{cbs["execute"]}', f'goal_callback=self.{cbs["goal"]}',
                         f'cancel_callback=self.{cbs["cancel"]}']
            if qos is not None:
                args.append(qos if e.kind.communication == 'topic' else f'qos_profile={qos}')
            out += _wrap(f'        self.{attr} = {call}(', [a + ',' for a in args], ')') + '\n'
        if self.lifecycle:
            out += '\n    def _nodl_destroy_entities(self) -> None:\n'
            if not self.endpoints:
                out += '        pass\n'
            for e in self.endpoints:
                attr = self.attributes[(e.kind, e.name)]
                destroy = {EntityKind.PUBLISHER: 'self.destroy_lifecycle_publisher',
                           EntityKind.SUBSCRIPTION: 'self.destroy_subscription',
                           EntityKind.SERVICE_SERVER: 'self.destroy_service',
                           EntityKind.SERVICE_CLIENT: 'self.destroy_client'}.get(e.kind)
                out += f'        if hasattr(self, {literal(attr)}):\n'
                if destroy is None:
                    out += f'            self.{attr}.destroy()\n'
                else:
                    out += f'            {destroy}(self.{attr})\n'
                out += f'            del self.{attr}\n'
        return out

    def lifecycle_methods(self) -> str:
        if not self.lifecycle:
            return ''
        return '''
    def on_configure(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Create the endpoints; override it (call super() first) to acquire resources."""
        self._nodl_create_entities()
        return super().on_configure(state)

    def on_cleanup(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Destroy the endpoints; override it (call super() first) to release resources."""
        self._nodl_destroy_entities()
        return super().on_cleanup(state)

    def on_shutdown(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Destroy the endpoints; override it (call super() first)."""
        self._nodl_destroy_entities()
        return super().on_shutdown(state)
'''

    def callback_methods(self) -> str:
        out = ''
        for e in self.endpoints:
            t = _type_ref(e)
            doc = e.description or ''
            if e.kind is EntityKind.SUBSCRIPTION:
                cb = self.callbacks[(e.kind, e.name)]['callback']
                out += (f'\n    @abc.abstractmethod\n    def {cb}(self, msg: {t}) -> None:\n'
                        + docstring(f'Handle a message on {e.name}.\n\n{doc}'.strip(), '        '))
            elif e.kind is EntityKind.SERVICE_SERVER:
                cb = self.callbacks[(e.kind, e.name)]['callback']
                out += ('\n    @abc.abstractmethod\n'
                        + _wrap(f'    def {cb}(', ['self,', f'request: {t}.Request,', f'response: {t}.Response,'],
                                f') -> {t}.Response:') + '\n'
                        + docstring(f'Handle a request to {e.name}: fill and return the response.\n\n{doc}'.strip(),
                                    '        '))
            elif e.kind is EntityKind.ACTION_SERVER:
                cbs = self.callbacks[(e.kind, e.name)]
                out += ('\n    @abc.abstractmethod\n'
                        + _wrap(f'    def {cbs["goal"]}(', ['self,', f'goal: {t}.Goal,'], ') -> GoalResponse:') + '\n'
                        + docstring(f'Accept or reject a goal of {e.name}.\n\n{doc}'.strip(), '        ')
                        + '\n    @abc.abstractmethod\n'
                        + _wrap(f'    def {cbs["cancel"]}(', ['self,', _goal_handle(e)],
                                ') -> CancelResponse:') + '\n'
                        + docstring(f'Accept or reject the cancellation of a goal of {e.name}.', '        ')
                        + '\n    @abc.abstractmethod\n'
                        + _wrap(f'    def {cbs["execute"]}(', ['self,', _goal_handle(e)],
                                f') -> {t}.Result:') + '\n'
                        + docstring(f'Execute an accepted goal of {e.name}; return its result.', '        '))
        return out


def _goal_handle(entity: Entity) -> str:
    """The ``goal_handle`` parameter of an action server's callbacks (wrapped when long)."""
    args = [a.strip() + ',' for a in _type_args(entity).split(',')]
    return _wrap('goal_handle: ServerGoalHandle[', args, '],', limit=99 - 8)


def _wrap(head: str, items: list[str], tail: str, limit: int = 99) -> str:
    """``head item, item tail`` on one line if it fits, else one item per line (items end with ',')."""
    if not items:
        return head[:-1] + ')' if tail == '})' else head + tail
    joined = ' '.join(items)
    one = head + (joined if len(items) == 1 and head.endswith('(') else joined.rstrip(',')) + tail
    if len(one) <= limit and '\n' not in one:
        return one
    indent = ' ' * (len(head) - len(head.lstrip()) + 4)
    body = ''.join(indent + line for item in items for line in (item + '\n').splitlines(True))
    return head + '\n' + body + ' ' * (len(indent) - 4) + tail


def _helpers(module: _Module) -> str:
    names = [p.name for p in module.parameters.parameters]
    dynamic = [p.name for p in module.parameters.parameters if p.dynamic_typing]
    types = [f'{literal(p.name)}: {literal(p.type_name)},' for p in module.parameters.parameters
             if p.required]
    return ('#: Every parameter the implementation declares.\n'
            + _wrap('_PARAMETER_NAMES = frozenset({', [literal(n) + ',' for n in names], '})') + '\n'
            + '#: Parameters of any type (type none).\n'
            + _wrap('_DYNAMIC: frozenset[str] = frozenset({', [literal(n) + ',' for n in dynamic], '})')
            + '\n#: The type of each parameter without a default (the node does not start without it).\n'
            + (_wrap('_TYPES: dict[str, str] = {', types, '}') if types else '_TYPES: dict[str, str] = {}')
            + '\n\n\n'
            'class ParameterError(RuntimeError):\n'
            '    """The node cannot start: a parameter is not set or invalid (one line per problem)."""\n'
            '\n\n'
            'def _normalized(value: Any) -> Any:\n'
            '    """Return a parameter value as the snapshot holds it: arrays as lists, bytes as bytes."""\n'
            '    if isinstance(value, (list, tuple)) or type(value).__name__ == \'array\':\n'
            '        items = list(value)\n'
            '        if items and all(isinstance(item, bytes) for item in items):\n'
            "            return b''.join(items)\n"
            '        return items\n'
            '    return value\n')


def generate_python(node: ResolvedNode, options: GenerateOptions) -> list[GeneratedFile]:
    """The Python module implementing ``node``: ``<node_name>_base.py``."""
    return [GeneratedFile(f'{options.node_name}_base.py', _Module(node, options).text())]


class PythonGenerator(GeneratorExtension):
    """Generates an rclpy node base class (the built-in ``python`` generator)."""

    LANGUAGE = 'python'
    CLIENT_LIBRARY = 'rclpy'

    def generate(self, node: ResolvedNode, options: GenerateOptions) -> list[GeneratedFile]:
        """See :func:`generate_python`."""
        return generate_python(node, options)

