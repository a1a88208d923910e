"""The resolved node: a composed node definition as typed entities.

:func:`resolve_node` composes a node definition (base of a client library,
mixins, main) and turns every parameter and endpoint into an
:class:`~nodl.composition.entities.Entity` that knows its kind, the layer
that declared it first (and so its provider), the layer whose declaration
won, its typed QoS, its parsed type and its source location.  Consumers
(show, check, generators, policies, launch analysis) ask this model instead
of walking documents.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Sequence
from functools import partial
from typing import Any

from nodl.composition.client_library import ClientLibraryChoice, choose_client_library
from nodl.composition.compose import ComposedNode, compose_report
from nodl.composition.entities import (
    PROVIDER_OF_ROLE,
    Entity,
    EntityKind,
    Location,
    Provider,
    parse_entity_type,
)
from nodl.composition.layers import Layer
from nodl.composition.merge import PARAMETERS, Declaration, seeded_copies
from nodl.composition.resolvers import Resolver
from nodl.diagnostics import Diagnostic, Severity, ValidationError
from nodl.frontends.source import Source
from nodl.loading import CheckedSource, check_source
from nodl.model import ENDPOINT_SECTIONS, Base, Interface, Node
from nodl.validation.kinds import Kind

__all__ = ['ResolvedNode', 'resolve_node', 'resolve_report']


def _location(declaration: Declaration, parameter: bool) -> Location:
    placed = declaration.layer.place(Diagnostic(Severity.INFO, '', declaration.path,
                                                anchor='key' if parameter else 'value'))
    return Location(placed.file, placed.line, placed.column)


_PARAMETER = EntityKind.PARAMETER


def _entity(kind: EntityKind, name: str, merged: object,
            trace: Sequence[Declaration], layers: Sequence[Layer]) -> Entity:
    shared = trace[0].layer.shared if len(trace) == 1 else None
    if shared is None:
        return _new_entity(kind, name, merged, trace, layers)
    # Declared by a layer every node of the run shares (a base) and by no other layer:
    # the same entity for every node.
    key = ('entity', kind, name, id(merged))
    found: Entity | None = shared.get(key)
    if found is None:
        found = shared[key] = _new_entity(kind, name, merged, trace, layers)
    return found


def _new_entity(kind: EntityKind, name: str, merged: Any,
                trace: Sequence[Declaration], layers: Sequence[Layer]) -> Entity:
    parameter = kind is _PARAMETER
    location: Location | Callable[[], Location]
    if trace:
        first, last = trace[0].layer, trace[-1]
        location = partial(_location, last, parameter)  # placed on first use (see Entity.location)
        labels = (first.label,) if len(trace) == 1 else tuple(d.layer.label for d in trace)
        layer = last.layer
    else:  # a ComposedNode built by hand, without traced declarations
        label = getattr(merged, 'origin', None) or ''
        layer = next((each for each in layers if each.label == label), Layer(label or 'main', Interface()))
        first, location, labels = layer, Location(layer.label, 0, 0), (layer.label,)
    type_name: str = merged.type
    description = getattr(merged, 'description', None)
    return Entity(kind, name, type_name, parse_entity_type(kind, type_name),
                  getattr(merged, 'qos', None), description if description != '' else None,
                  layer.label, layer.role, PROVIDER_OF_ROLE.get(first.role, Provider.IMPLEMENTATION),
                  location, labels, merged)


#: The endpoint sections in file order, with their entity kinds and whether their names
#: resolve as a service's.
_SECTION_KINDS = tuple((section, kind, kind.communication == 'service')
                       for section, kind in ((s, EntityKind.of_section(s)) for s in ENDPOINT_SECTIONS))


class ResolvedNode:
    """A node definition resolved into typed entities (see the module docstring)."""

    def __init__(self, composed: ComposedNode, client_library_reason: str = '') -> None:
        #: The composition this node is built on.
        self.composed = composed
        #: Why the client library was chosen (``as requested``, from the package build type, ...).
        self.client_library_reason = client_library_reason or 'as given'
        entities: list[Entity] = []
        iface = composed.interface
        declarations, layers = composed.declarations, composed.layers
        # A shared base's entity that no later layer redeclares is the same Entity for every
        # node of the run: its merged copy is then the one the base's own merge made.
        shared = layers[0].shared if layers else None
        seeded = seeded_copies(layers[0]) if shared is not None else frozenset()
        known: dict[int, Entity] = shared.setdefault('entities by merged copy', {}) \
            if shared is not None else {}
        # What each instance of the node needs to name its entities, worked out with them (a
        # launched system may run a node many times): per entity, its declared name and None
        # for a parameter (which keeps its name), else whether it resolves as a service.
        plan: list[tuple[str, bool | None]] = []
        endpoints: list[int] = []
        for name, param in (iface.parameters or {}).items():
            found = known.get(id(param))
            if found is None:
                found = _entity(EntityKind.PARAMETER, name, param,
                                declarations.get((PARAMETERS, name), ()), layers)
                if id(param) in seeded:
                    known[id(param)] = found
            entities.append(found)
            plan.append((found.name, None))
        for section, kind, service in _SECTION_KINDS:
            for endpoint in iface.endpoints(section):
                found = known.get(id(endpoint))
                if found is None:
                    found = _entity(kind, endpoint.name, endpoint,
                                    declarations.get((section, endpoint.name), ()), layers)
                    if id(endpoint) in seeded:
                        known[id(endpoint)] = found
                endpoints.append(len(entities))
                entities.append(found)
                plan.append((found.name, service))
        #: Every entity: parameters first, then the endpoint sections in file order.
        self.entities: tuple[Entity, ...] = tuple(entities)
        #: What each instance of the node needs to name its entities (see above).
        self.naming_plan: tuple[tuple[str, bool | None], ...] = tuple(plan)
        #: The positions of the endpoints (not parameters) in :attr:`entities`.
        self.endpoint_indices: tuple[int, ...] = tuple(endpoints)
        self._by_key: dict[tuple[EntityKind, str], Entity] | None = None  # made when first asked

    # -- what the node is -------------------------------------------------------------------

    @property
    def file(self) -> str:
        """The node definition's file."""
        return self.composed.file

    @property
    def files(self) -> list[str]:
        """Every file the definition was read from: its own, then its mixins' (nested ones too)."""
        return self.composed.files

    @property
    def node(self) -> Node:
        """The node definition as written."""
        return self.composed.node

    @property
    def base(self) -> Base | None:
        """The built-in base (None for a node without one)."""
        return self.composed.node.base

    @property
    def client_library(self) -> str:
        """The client library whose base the node inherits (``rclpy`` or ``rclcpp``)."""
        return self.composed.client_library

    @property
    def layers(self) -> list[Layer]:
        """base, mixins in order, main."""
        return self.composed.layers

    @property
    def interface(self) -> Interface:
        """The merged interface (an interface definition; each entity's ``origin`` is its layer)."""
        return self.composed.interface

    @property
    def diagnostics(self) -> list[Diagnostic]:
        """What composing found: overrides (info) and warnings."""
        return self.composed.diagnostics

    # -- asking for entities ----------------------------------------------------------------

    def __iter__(self) -> Iterator[Entity]:
        return iter(self.entities)

    def __len__(self) -> int:
        return len(self.entities)

    def of_kind(self, kind: EntityKind | str) -> list[Entity]:
        """The entities of one kind, in declaration order."""
        wanted = EntityKind(kind)
        return [e for e in self.entities if e.kind is wanted]

    @property
    def parameters(self) -> list[Entity]:
        """The parameters."""
        return self.of_kind(EntityKind.PARAMETER)

    @property
    def endpoints(self) -> list[Entity]:
        """Every publisher, subscription, service and action server and client."""
        return [e for e in self.entities if not e.is_parameter]

    def get(self, kind: EntityKind | str, name: str) -> Entity | None:
        """The entity of ``kind`` called ``name`` (as declared), or None."""
        by_key = self._by_key
        if by_key is None:
            by_key = self._by_key = {e.key: e for e in self.entities}
        return by_key.get((EntityKind(kind), name))

    def entity(self, kind: EntityKind | str, name: str) -> Entity:
        """The entity of ``kind`` called ``name`` (KeyError if there is none)."""
        found = self.get(kind, name)
        if found is None:
            raise KeyError(f'no {EntityKind(kind).word} {name!r} in {self.file}')
        return found

    def provided_by(self, *providers: Provider | str) -> list[Entity]:
        """The entities the given providers bring (client_library, other_code, implementation)."""
        wanted = {Provider(p) for p in providers}
        return [e for e in self.entities if e.provider in wanted]

    def implementation_entities(self) -> list[Entity]:
        """What the node's own code must implement: the entities ``main`` declares first
        (never the base, which the client library provides, nor a mixin's)."""
        return self.provided_by(Provider.IMPLEMENTATION)

    def interface_of(self, entities: Sequence[Entity]) -> Interface:
        """An interface definition holding just ``entities`` (e.g. the implementation's)."""
        out = Interface(nodl_version=2, description=self.interface.description)
        for entity in entities:
            if entity.is_parameter:
                if out.parameters is None:
                    out.parameters = {}
                out.parameters[entity.name] = entity.definition
                continue
            entries = getattr(out, entity.section)
            if entries is None:
                entries = []
                setattr(out, entity.section, entries)
            entries.append(entity.definition)
        return out

    def __repr__(self) -> str:
        return (f'ResolvedNode({self.file!r}, base={self.base and self.base.value!r}, '
                f'client_library={self.client_library!r}, {len(self.entities)} entities)')


def resolve_report(report: CheckedSource, *, client_library: str | ClientLibraryChoice | None = None,
                   resolvers: dict[str, Resolver] | None = None,
                   prefixes: list[str] | None = None
                   ) -> tuple[ResolvedNode | None, list[Diagnostic]]:
    """Resolve a checked node definition (a :class:`~nodl.loading.CheckedSource`).

    Returns the resolved node (None on errors) and every diagnostic.
    ``prefixes``: where ``nodl://`` mixins are looked up (default ``AMENT_PREFIX_PATH``).
    ValueError for an unknown client library.
    """
    choice = client_library if isinstance(client_library, ClientLibraryChoice) \
        else choose_client_library(client_library)
    composed, diagnostics = compose_report(report, resolvers, client_library=choice.name,
                                           prefixes=prefixes)
    if composed is None:
        return None, diagnostics
    return ResolvedNode(composed, choice.reason), diagnostics


def resolve_node(source: ComposedNode | Source, *, file: str | None = None,
                 client_library: str | ClientLibraryChoice | None = None,
                 resolvers: dict[str, Resolver] | None = None,
                 prefixes: list[str] | None = None) -> ResolvedNode:
    """The resolved node of a node definition (YAML/JSON text, bytes, a path) or a composition.

    ``client_library``: ``rclpy`` or ``rclcpp`` (default rclpy) picks the base's
    variant; ``nodl://`` mixins are looked up in ``prefixes`` (default
    ``AMENT_PREFIX_PATH``).  Raises :class:`~nodl.diagnostics.ValidationError` with every
    diagnostic if the definition or a mixin is invalid, cannot be resolved, or
    overrides what its base forbids; ValueError for an unknown client library.
    """
    if isinstance(source, ComposedNode):
        reason = client_library.reason if isinstance(client_library, ClientLibraryChoice) else ''
        return ResolvedNode(source, reason or f'{source.client_library}, as composed')
    if file is None and isinstance(source, os.PathLike):
        file = os.fspath(source)
    resolved, diagnostics = resolve_report(check_source(source, kind=Kind.NODE, file=file),
                                           client_library=client_library, resolvers=resolvers,
                                           prefixes=prefixes)
    if resolved is None:
        raise ValidationError(diagnostics)
    return resolved
