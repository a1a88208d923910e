"""NodlNode and NodlLifecycleNode: a definition's main entities on a real rclpy node."""

from __future__ import annotations

import importlib
import os
from collections.abc import Callable, Mapping
from typing import Any

from rcl_interfaces.msg import SetParametersResult
from rclpy.exceptions import ParameterUninitializedException
from rclpy.lifecycle import LifecycleNode, LifecycleState, TransitionCallbackReturn
from rclpy.node import Node
from rclpy.parameter import Parameter

from nodl.files import describe_os_error
from nodl.generate import default_node_name
from nodl.plan.parameter_plan import ParametersPlan, plan_parameters
from nodl.runtime.binding import ActionCallbacks, collect_callbacks, missing_callbacks
from nodl.runtime.errors import RuntimeDefinitionError
from nodl.runtime.parameter_behaviour import (
    CustomValidator,
    ParameterSnapshot,
    build_snapshot,
    check_required,
    custom_validator_problems,
    descriptor_of,
    normalized,
    problems_of,
    python_default,
)
from nodl.system import Entity, EntityKind, InterfaceType, ResolvedNode
from nodl.targets import resolve_target
from nodl.vocabulary import QOS_DURATIONS

__all__ = ['NodlNode', 'NodlLifecycleNode', 'Definition']

#: A definition: a file path, ``(package, executable)``, or a resolved node.
Definition = Any

_NEEDS_CALLBACK = (EntityKind.SUBSCRIPTION, EntityKind.SERVICE_SERVER, EntityKind.ACTION_SERVER)


def _resolve(definition: Definition) -> ResolvedNode:
    if isinstance(definition, ResolvedNode):
        return definition
    target = list(definition) if isinstance(definition, tuple) else [os.fspath(definition)]
    try:
        node, diagnostics, _, _ = resolve_target(target, client_library='rclpy')
    except OSError as exc:
        why = describe_os_error(exc)
        raise RuntimeDefinitionError(f'{exc.filename}: {why}' if exc.filename else why) from None
    except ValueError as exc:
        raise RuntimeDefinitionError(str(exc)) from None
    if node is None:
        raise RuntimeDefinitionError('\n'.join(str(d) for d in diagnostics if d.severity.value == 'error'))
    return node


def _import_type(entity: Entity) -> Any:
    it = entity.type
    if not isinstance(it, InterfaceType):
        raise RuntimeDefinitionError(f'{entity.location}: {entity} has no interface type')
    try:
        module = importlib.import_module(f'{it.package}.{it.namespace}')
        return getattr(module, it.name)
    except (ImportError, AttributeError):
        raise RuntimeDefinitionError(
            f'{entity.location}: the type {it} of {entity.kind.word} {entity.name!r} is not installed '
            f"(no {it.name} in the Python module {it.package}.{it.namespace}); install the package "
            f'{it.package} (from a ROS distribution, or pip install ros-{it.package.replace("_", "-")})'
        ) from None


def _qos(entity: Entity) -> Any:
    from rclpy.duration import Duration
    from rclpy.qos import (
        DurabilityPolicy,
        HistoryPolicy,
        LivelinessPolicy,
        QoSProfile,
        ReliabilityPolicy,
    )

    qos = entity.qos
    if qos is None:
        return None
    kwargs: dict[str, Any] = {
        'history': HistoryPolicy[qos.history or 'SYSTEM_DEFAULT'],
        'reliability': ReliabilityPolicy[qos.reliability or 'SYSTEM_DEFAULT'],
        'durability': DurabilityPolicy[qos.durability or 'SYSTEM_DEFAULT'],
        'liveliness': LivelinessPolicy[qos.liveliness or 'SYSTEM_DEFAULT']}
    if qos.depth is not None:
        kwargs['depth'] = qos.depth
    for key, policy in QOS_DURATIONS.items():
        value = getattr(qos, key)
        if value is not None:
            kwargs[policy] = Duration(nanoseconds=value)
    return QoSProfile(**kwargs)


class _Prepared:
    """Everything checked before the rclpy node exists."""

    def __init__(self, owner: Any, definition: Definition, callbacks: Mapping[str, Any] | None,
                 custom_validators: Mapping[str, CustomValidator] | None) -> None:
        self.resolved = _resolve(definition)
        entities = self.resolved.implementation_entities()
        self.plan: ParametersPlan = plan_parameters([e for e in entities if e.is_parameter])
        self.endpoints = [e for e in entities if not e.is_parameter]
        problems = []
        self.types: dict[tuple[EntityKind, str], Any] = {}
        for entity in self.endpoints:
            try:
                self.types[entity.key] = _import_type(entity)
            except RuntimeDefinitionError as exc:
                problems.append(str(exc))
        needed = {(e.kind, e.name): e.kind.word for e in self.endpoints if e.kind in _NEEDS_CALLBACK}
        try:
            self.callbacks = collect_callbacks(owner, callbacks, needed)
        except RuntimeDefinitionError as exc:
            problems.append(str(exc))
            self.callbacks = {}
        else:
            problems += missing_callbacks(needed, self.callbacks)
        self.custom = dict(custom_validators or {})
        problems += custom_validator_problems(self.plan, self.custom)
        if problems:
            raise RuntimeDefinitionError('\n'.join(problems))


class _NodlMixin:
    """The shared behaviour of NodlNode and NodlLifecycleNode."""

    _nodl: _Prepared
    params: ParameterSnapshot

    def _nodl_setup(self, prepared: _Prepared, on_parameters_changed: Callable[..., Any] | None) -> None:
        self._nodl = prepared
        self._nodl_values: dict[str, Any] = {}
        self._nodl_on_change = on_parameters_changed
        #: Every handle, by kind and declared name.
        self.nodl_handles: dict[tuple[EntityKind, str], Any] = {}
        node: Any = self
        plan = prepared.plan
        for parameter in plan.parameters:
            descriptor = descriptor_of(parameter)
            if parameter.dynamic_typing:
                node.declare_parameter(parameter.name, None, descriptor)
            elif parameter.required or parameter.default == []:
                kind = getattr(Parameter.Type, parameter.ros_type[len('PARAMETER_'):])
                node.declare_parameter(parameter.name, kind, descriptor)
                if not parameter.required and self._nodl_initial(parameter.name) is None:
                    super().set_parameters([Parameter(parameter.name, kind, [])])  # type: ignore[misc]
            else:
                node.declare_parameter(parameter.name, python_default(parameter), descriptor)
        values = {p.name: self._nodl_initial(p.name) for p in plan.parameters}
        check_required(node.get_name(), [(p.name, p.type_name) for p in plan.parameters
                                         if values[p.name] is None and not p.dynamic_typing])
        values = {n: normalized(v) for n, v in values.items()}
        problems = problems_of(plan, values, values, prepared.custom)
        if problems:
            raise RuntimeDefinitionError(f'{node.get_name()}: invalid parameter value(s): ' + '; '.join(problems))
        self.params = build_snapshot(plan, values, 0)
        self._nodl_values = values
        node.add_on_set_parameters_callback(self._nodl_validate)
        node.add_post_set_parameters_callback(self._nodl_commit)

    def _nodl_initial(self, name: str) -> Any:
        try:
            return self.get_parameter(name).value  # type: ignore[attr-defined]
        except ParameterUninitializedException:
            return None

    def _nodl_changed(self, parameters: list[Parameter[Any]]) -> dict[str, Any]:
        return {p.name: normalized(p.value) for p in parameters if self._nodl.plan.get(p.name) is not None}

    def _nodl_validate(self, parameters: list[Parameter[Any]]) -> SetParametersResult:
        changed = self._nodl_changed(parameters)
        problems = problems_of(self._nodl.plan, {**self._nodl_values, **changed}, changed, self._nodl.custom)
        return SetParametersResult(successful=not problems, reason='; '.join(problems))

    def _nodl_commit(self, parameters: list[Parameter[Any]]) -> None:
        changed = self._nodl_changed(parameters)
        if not changed:
            return
        old = self.params
        self._nodl_values = {**self._nodl_values, **changed}
        self.params = build_snapshot(self._nodl.plan, self._nodl_values, getattr(old, '_nodl_stamp', 0) + 1)
        self.on_parameters_changed(old, self.params)

    def set_parameters_atomically(self, parameter_list: list[Parameter[Any]]) -> SetParametersResult:
        """Validate first, so that a rejection gives the validator's reason (then set as rclpy does)."""
        node: Any = self
        declared = [p for p in parameter_list if self._nodl.plan.get(p.name) is not None
                    and p.value is not None and p.type_ == node.get_parameter(p.name).type_]
        result = self._nodl_validate(declared)
        if not result.successful:
            return result
        answer: SetParametersResult = super().set_parameters_atomically(parameter_list)  # type: ignore[misc]
        return answer

    def set_parameters(self, parameter_list: list[Parameter[Any]]) -> list[SetParametersResult]:
        """One at a time, each as :meth:`set_parameters_atomically`: a rejection gives the validator's reason."""
        return [self.set_parameters_atomically([parameter]) for parameter in parameter_list]

    def is_old(self, params: ParameterSnapshot) -> bool:
        """True if ``params`` is not the newest snapshot."""
        return bool(getattr(params, '_nodl_stamp', -1) != getattr(self.params, '_nodl_stamp', -2))

    def try_update(self, params: ParameterSnapshot) -> ParameterSnapshot:
        """The newest snapshot (``params`` itself if it is the newest)."""
        return self.params if self.is_old(params) else params

    def on_parameters_changed(self, old: ParameterSnapshot, new: ParameterSnapshot) -> None:
        """Called after parameters were set (override it, or pass ``on_parameters_changed=``)."""
        if self._nodl_on_change is not None:
            self._nodl_on_change(old, new)

    # -- entities ---------------------------------------------------------------------------

    @property
    def definition(self) -> ResolvedNode:
        """The resolved definition the node was built from."""
        return self._nodl.resolved

    def endpoint(self, name: str, kind: EntityKind | str | None = None) -> Any:
        """The handle of the entity declared as ``name`` (give ``kind`` if two kinds share the name)."""
        found = [(k, h) for (k, n), h in self.nodl_handles.items() if n == name
                 and (kind is None or k is EntityKind(kind))]
        if len(found) != 1:
            declared = ', '.join(sorted({n for _, n in self.nodl_handles}))
            what = 'no entity' if not found else 'more than one entity (give kind=)'
            raise KeyError(f'{what} declared as {name!r}; declared: {declared}')
        return found[0][1]

    def _nodl_create_entities(self, lifecycle: bool) -> None:
        node: Any = self
        for entity in self._nodl.endpoints:
            msg_type = self._nodl.types[entity.key]
            qos = _qos(entity)
            bound = self._nodl.callbacks.get((entity.kind, entity.name))
            kind = entity.kind
            if kind is EntityKind.PUBLISHER:
                create = node.create_lifecycle_publisher if lifecycle else node.create_publisher
                handle = create(msg_type, entity.name, qos)
            elif kind is EntityKind.SUBSCRIPTION:
                handle = node.create_subscription(msg_type, entity.name, bound, qos)
            elif kind is EntityKind.SERVICE_SERVER:
                handle = node.create_service(msg_type, entity.name, bound, **({'qos_profile': qos} if qos else {}))
            elif kind is EntityKind.SERVICE_CLIENT:
                handle = node.create_client(msg_type, entity.name, **({'qos_profile': qos} if qos else {}))
            elif kind is EntityKind.ACTION_SERVER:
                from rclpy.action.server import ActionServer

                assert isinstance(bound, ActionCallbacks)
                extra: dict[str, Any] = {k: v for k, v in (('goal_callback', bound.goal),
                                                           ('cancel_callback', bound.cancel)) if v is not None}
                handle = ActionServer(node, msg_type, entity.name, execute_callback=bound.execute, **extra)
            else:
                from rclpy.action.client import ActionClient

                handle = ActionClient(node, msg_type, entity.name)
            self.nodl_handles[entity.key] = handle

    def _nodl_destroy_entities(self) -> None:
        node: Any = self
        for (kind, _), handle in list(self.nodl_handles.items()):
            if kind is EntityKind.PUBLISHER:
                node.destroy_lifecycle_publisher(handle)
            elif kind is EntityKind.SUBSCRIPTION:
                node.destroy_subscription(handle)
            elif kind is EntityKind.SERVICE_SERVER:
                node.destroy_service(handle)
            elif kind is EntityKind.SERVICE_CLIENT:
                node.destroy_client(handle)
            else:
                handle.destroy()
        self.nodl_handles.clear()


def _node_name(prepared: _Prepared, node_name: str | None) -> str:
    if node_name:
        return node_name
    return default_node_name(prepared.resolved.file)


class NodlNode(_NodlMixin, Node):
    """An rclpy node built from a definition (see :mod:`nodl.runtime`).

    ``callbacks``: declared name -> callable, or ``(kind, name)`` -> callable when
    entities of two kinds share the name (``('service_server', '~/x')``; a name that is
    ambiguous is an error that says so); an action server takes a callable for
    ``execute`` or :class:`~nodl.runtime.ActionCallbacks`;
    ``custom_validators``: custom validator name (``ns::fn``) -> ``fn(value,
    arguments) -> None | why``; ``on_parameters_changed(old, new)``; other
    keyword arguments go to rclpy's Node.  Raises
    :class:`~nodl.runtime.RuntimeDefinitionError` before the node is
    created for a definition that cannot run, and after declaring parameters
    for required or invalid ones.
    """

    def __init__(self, definition: Definition, node_name: str | None = None, *,
                 callbacks: Mapping[str, Any] | None = None,
                 custom_validators: Mapping[str, CustomValidator] | None = None,
                 on_parameters_changed: Callable[[ParameterSnapshot, ParameterSnapshot], None] | None = None,
                 **kwargs: Any) -> None:
        prepared = _Prepared(self, definition, callbacks, custom_validators)
        if prepared.resolved.base is not None and prepared.resolved.base.value == 'lifecycle_node':
            raise RuntimeDefinitionError(f'{prepared.resolved.file} declares base: lifecycle_node; '
                                         'build it with NodlLifecycleNode')
        Node.__init__(self, _node_name(prepared, node_name), **kwargs)
        try:
            self._nodl_setup(prepared, on_parameters_changed)
            self._nodl_create_entities(lifecycle=False)
        except BaseException:
            self.destroy_node()
            raise


class NodlLifecycleNode(_NodlMixin, LifecycleNode):
    """A lifecycle node built from a definition: parameters declared at construction, endpoints
    created in ``on_configure`` (publishers as lifecycle publishers: they publish only while
    active) and destroyed in ``on_cleanup``/``on_shutdown``.  Override a transition and call
    ``super()`` first.  Arguments as :class:`NodlNode`."""

    def __init__(self, definition: Definition, node_name: str | None = None, *,
                 callbacks: Mapping[str, Any] | None = None,
                 custom_validators: Mapping[str, CustomValidator] | None = None,
                 on_parameters_changed: Callable[[ParameterSnapshot, ParameterSnapshot], None] | None = None,
                 **kwargs: Any) -> None:
        prepared = _Prepared(self, definition, callbacks, custom_validators)
        LifecycleNode.__init__(self, _node_name(prepared, node_name), **kwargs)
        try:
            self._nodl_setup(prepared, on_parameters_changed)
        except BaseException:
            self.destroy_node()
            raise

    def on_configure(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Creates the endpoints."""
        self._nodl_create_entities(lifecycle=True)
        result: TransitionCallbackReturn = super().on_configure(state)
        return result

    def on_cleanup(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Destroys the endpoints."""
        self._nodl_destroy_entities()
        result: TransitionCallbackReturn = super().on_cleanup(state)
        return result

    def on_shutdown(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Destroys the endpoints."""
        self._nodl_destroy_entities()
        result: TransitionCallbackReturn = super().on_shutdown(state)
        return result
