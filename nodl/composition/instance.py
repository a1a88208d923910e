"""A node instance: a resolved node given a name, a namespace, remappings and parameters.

Every endpoint's final name is computed exactly as rcl does
(:mod:`nodl.naming`): expansion of ``~``, ``{node}`` and relative
names against the node's final name and namespace (after ``__node`` and
``__ns`` rules), then the first matching remapping rule.  Parameters take
their default, overridden by the instance's overrides.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from typing import Any, NamedTuple

from nodl.composition.entities import Entity, EntityKind, Location, Provider
from nodl.composition.resolved import ResolvedNode
from nodl.naming import (
    NodeNames,
    RemapArgs,
    RemapRule,
    normalize_namespace,
    parse_remap_rules,
)

__all__ = ['InstanceEntity', 'NodeInstance']


class InstanceEntity(NamedTuple):
    """An entity of a node instance with its final (fully qualified, remapped) name."""

    instance: NodeInstance
    entity: Entity
    #: The final name (parameters keep their name).
    name: str

    @property
    def kind(self) -> EntityKind:
        """The entity's kind."""
        return self.entity.kind

    @property
    def provider(self) -> Provider:
        """Who provides the entity (client library, other code, the implementation)."""
        return self.entity.provider

    def __str__(self) -> str:
        return f'{self.instance.fqn}: {self.entity.kind.word} {self.name} ({self.entity.type_name})'

    def __repr__(self) -> str:
        return f'InstanceEntity({self.instance.fqn!r}, {self.entity.kind.value}, {self.name!r})'


class NodeInstance:
    """A resolved node running as ``namespace/name`` with remappings and parameter overrides.

    ``name`` and ``namespace`` are those the node is created with; the
    remapping rules (``from:=to``, ``node:from:=to``, ``__ns:=``, ``__node:=``,
    or a whole ``--ros-args`` command line) may change both, as in rcl.
    Raises ``ValueError`` (:class:`~nodl.naming.InvalidNameError` or
    :class:`~nodl.naming.InvalidRemapRuleError`) for a name or rule
    rcl would reject.  ``names``: the node's :class:`~nodl.naming.NodeNames` if
    the caller has already made them (``NodeNames.create(name, namespace, remap_rules)``).
    """

    def __init__(self, resolved: ResolvedNode, name: str, namespace: str = '/',
                 remap_rules: RemapArgs = None,
                 parameter_overrides: Mapping[str, Any] | None = None,
                 location: Location | None = None, *, names: NodeNames | None = None) -> None:
        #: The resolved node this is an instance of.
        self.resolved = resolved
        #: The rules, parsed (in order: the first matching one wins).
        self.remap_rules: list[RemapRule] = parse_remap_rules(remap_rules)
        #: The name and namespace the node is created with (before ``__node``/``__ns``).
        self.created_name = name
        self.created_namespace = normalize_namespace(namespace)
        #: The node's final name and namespace with its rules (resolves names as the node does).
        self.names = names if names is not None else NodeNames.create(name, namespace,
                                                                      self.remap_rules)
        #: The node's final name, namespace and fully qualified name.
        self.name = self.names.name
        self.namespace = self.names.namespace
        self.fqn = self.names.fqn
        #: The parameter values given to the instance (declared or not).
        self.parameter_overrides: dict[str, Any] = dict(parameter_overrides or {})
        #: Where the instance is declared (a launch file entry), if known.
        self.location = location
        resolve = self.names.resolve
        self._set_bound(resolved.entities, tuple([
            name if service is None else resolve(name, service=service)
            for name, service in resolved.naming_plan]), resolved.endpoint_indices)

    # The instance keeps (entity, final name) pairs and makes its InstanceEntity objects when
    # asked: an InstanceEntity refers to its instance, so an instance holding them would form a
    # reference cycle, and a whole analysis hanging off a thousand cycles is freed only by the
    # garbage collector (slowly) instead of as soon as it is let go.  They compare equal (and
    # hash alike) however many times they are made.  (Two tuples, not one pair per entity:
    # fewer objects for the collector to walk while a large analysis is being built.)

    def _set_bound(self, entities: tuple[Entity, ...], names: tuple[str, ...],
                   endpoint_indices: tuple[int, ...] | None = None) -> None:
        self._entities, self._names = entities, names
        self._endpoint_indices = endpoint_indices if endpoint_indices is not None else \
            tuple(i for i, e in enumerate(entities) if not e.is_parameter)

    @property
    def _bound(self) -> Iterator[tuple[Entity, str]]:
        return zip(self._entities, self._names, strict=True)

    @property
    def entities(self) -> tuple[InstanceEntity, ...]:
        """Every entity with its final name, in the resolved node's order."""
        new, instance = tuple.__new__, self
        return tuple([new(InstanceEntity, (instance, entity, name))
                      for entity, name in zip(self._entities, self._names, strict=True)])

    @entities.setter
    def entities(self, entities: Iterable[InstanceEntity]) -> None:
        given = tuple(entities)
        self._set_bound(tuple(b.entity for b in given), tuple(b.name for b in given))

    @property
    def endpoints(self) -> list[InstanceEntity]:
        """The endpoints (no parameters) with their final names."""
        new, instance, entities, names = tuple.__new__, self, self._entities, self._names
        return [new(InstanceEntity, (instance, entities[i], names[i]))
                for i in self._endpoint_indices]

    def of_kind(self, kind: EntityKind | str) -> list[InstanceEntity]:
        """The entities of one kind."""
        wanted = EntityKind(kind)
        return [InstanceEntity(self, e, n) for e, n in self._bound if e.kind is wanted]

    def final_name(self, entity: Entity | tuple[EntityKind | str, str]) -> str:
        """The final name of an entity of the resolved node (or of ``(kind, declared name)``)."""
        if not isinstance(entity, Entity):
            entity = self.resolved.entity(*entity)
        for bound, name in self._bound:
            if bound is entity:
                return name
        raise KeyError(f'{entity} is not an entity of {self.resolved.file}')

    def find(self, kind: EntityKind | str, final_name: str) -> InstanceEntity | None:
        """The entity of ``kind`` whose final name is ``final_name``, or None."""
        wanted = EntityKind(kind)
        return next((InstanceEntity(self, e, n) for e, n in self._bound
                     if e.kind is wanted and n == final_name), None)

    def parameter_values(self) -> dict[str, Any]:
        """Each declared parameter's value: its default, overridden by the instance's value
        (None for a parameter without a default that is not given)."""
        return {name: self.parameter_overrides.get(name, e.default_value)
                for e, name in self._bound if e.is_parameter}

    def undeclared_overrides(self) -> list[str]:
        """Overrides of parameters the node does not declare (sorted)."""
        declared = {e.name for e in self.resolved.parameters}
        return sorted(name for name in self.parameter_overrides if name not in declared)

    def __repr__(self) -> str:
        return f'NodeInstance({self.fqn!r}, {self.resolved.file!r})'


def instances_named(instances: Iterable[NodeInstance]) -> dict[str, list[NodeInstance]]:
    """Instances grouped by fully qualified name (more than one is a name clash)."""
    out: dict[str, list[NodeInstance]] = {}
    for instance in instances:
        out.setdefault(instance.fqn, []).append(instance)
    return out
