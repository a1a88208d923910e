"""The entities of a resolved node: kind, provider, parsed type, source location.

An :class:`Entity` is one parameter or endpoint of a node after composition.
It knows which layer declared it first (and so who provides it: the client
library for the base, other code for a mixin, the node's own implementation
for ``main``), which layer's declaration won, its typed QoS, its parsed
interface type and where it is written (file, line, column).
"""

from __future__ import annotations

import enum
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, NamedTuple

from nodl.location import Location
from nodl.model import QoSProfile
from nodl.model.parameter_types import TypeSpec, parse_type
from nodl.vocabulary import KIND_NAMESPACES, SECTION_BY_KEY, SECTIONS

__all__ = ['PROVIDER_OF_ROLE', 'Entity', 'EntityKind', 'InterfaceType', 'Location', 'Provider']


class EntityKind(str, enum.Enum):
    """What an entity is; the values are the section words (``service server`` -> ``service_server``)."""

    PARAMETER = 'parameter'
    PUBLISHER = 'publisher'
    SUBSCRIPTION = 'subscription'
    SERVICE_SERVER = 'service_server'
    SERVICE_CLIENT = 'service_client'
    ACTION_SERVER = 'action_server'
    ACTION_CLIENT = 'action_client'

    def __str__(self) -> str:
        return self.value

    @classmethod
    def of_section(cls, section: str) -> EntityKind:
        """The kind of the entities of a document section (``publishers`` -> PUBLISHER)."""
        if section == 'parameters':
            return cls.PARAMETER
        return cls(SECTION_BY_KEY[section].word.replace(' ', '_'))

    @property
    def section(self) -> str:
        """The document section that holds entities of this kind."""
        return _SECTION_OF[self]

    @property
    def word(self) -> str:
        """Words for messages: ``service server``."""
        return self.value.replace('_', ' ')

    @property
    def communication(self) -> str | None:
        """``topic``, ``service`` or ``action`` (None for a parameter)."""
        return _COMMUNICATION_OF[self]

    @property
    def offers(self) -> bool:
        """True for the side that offers the communication: publisher, service/action server."""
        return _OFFERS[self]


#: The parameter kind (a module constant: reaching an enum member through its class is slow,
#: and the question is asked of every entity of every node).
_PARAMETER = EntityKind.PARAMETER

# Derived from the one table of sections, once (asked for every entity of every node).
#: kind -> section.
_SECTION_OF = {EntityKind.PARAMETER: 'parameters',
               **{EntityKind(s.word.replace(' ', '_')): s.key for s in SECTIONS}}
#: kind -> topic, service or action (None for a parameter).
_COMMUNICATION_OF = {EntityKind.PARAMETER: None,
                     **{EntityKind(s.word.replace(' ', '_')): s.kind for s in SECTIONS}}
#: kind -> whether it offers the communication (publisher, service/action server).
_OFFERS = {EntityKind.PARAMETER: False,
           **{EntityKind(s.word.replace(' ', '_')): s.role in ('publisher', 'server')
              for s in SECTIONS}}


class Provider(str, enum.Enum):
    """Who brings an entity into the running node."""

    #: The client library (the base): a generator never implements it.
    CLIENT_LIBRARY = 'client_library'
    #: Other code the node uses (a mixin): a library, a component, a plug-in.
    OTHER_CODE = 'other_code'
    #: The node's own implementation (``main``): what a generator implements.
    IMPLEMENTATION = 'implementation'

    def __str__(self) -> str:
        return self.value


#: Layer role -> who provides the entities that layer declares first.
PROVIDER_OF_ROLE = {'base': Provider.CLIENT_LIBRARY, 'mixin': Provider.OTHER_CODE,
                    'main': Provider.IMPLEMENTATION}


class InterfaceType(NamedTuple):
    """A parsed interface type: ``std_msgs/msg/String`` -> (std_msgs, msg, String)."""

    package: str
    namespace: str
    name: str

    def __str__(self) -> str:
        return f'{self.package}/{self.namespace}/{self.name}'

    @classmethod
    def parse(cls, text: str, communication: str | None = None) -> InterfaceType:
        """Parse ``pkg/ns/Name``; the short form ``pkg/Name`` takes the namespace of
        ``communication`` (``topic`` -> ``msg``).  ValueError for anything else."""
        parts = text.split('/')
        if len(parts) == 3 and all(parts):
            return cls(*parts)
        if len(parts) == 2 and all(parts) and communication in KIND_NAMESPACES:
            return cls(parts[0], KIND_NAMESPACES[communication], parts[1])
        raise ValueError(f'{text!r} is not an interface type (expected <package>/<namespace>/<Name>)')


#: The parsed type of an entity: an interface type, or a parameter type.
EntityType = InterfaceType | TypeSpec | None


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class Entity:
    """One parameter or endpoint of a resolved node (compared and hashed by identity)."""

    kind: EntityKind
    #: The name as declared (``~/scan``, ``scan``, ``/scan``; a parameter's name).
    name: str
    #: The type as written (``std_msgs/msg/String``, ``double_array``).
    type_name: str
    #: The parsed type: :class:`InterfaceType` for endpoints, ``TypeSpec`` for parameters
    #: (None if it cannot be parsed).
    type: EntityType
    #: Typed QoS (topics always; services when declared; None for actions and parameters).
    qos: QoSProfile | None
    description: str | None
    #: The label of the layer whose declaration won (``base:node``, a mixin reference,
    #: ``mixins[1]``, ``main``).
    layer: str
    #: That layer's role: ``base``, ``mixin`` or ``main``.
    role: str
    #: Who provides the entity, from the layer that declared it first.
    provider: Provider
    #: Where the winning declaration is written: a :class:`Location`, or a function that
    #: computes it on first use (placing a declaration in its source is not free, and most
    #: consumers never print most locations); read it as :attr:`location`.
    _where: Location | Callable[[], Location]
    #: The labels of every layer that declares the entity, first first.
    declared_in: tuple[str, ...]
    #: The model object of the winning declaration (ParameterDefinition, TopicEndpoint, ...).
    definition: Any

    @property
    def location(self) -> Location:
        """Where the winning declaration is written (computed once, on first use)."""
        where = self._where
        if isinstance(where, Location):
            return where
        found = where()
        object.__setattr__(self, '_where', found)
        return found

    @property
    def key(self) -> tuple[EntityKind, str]:
        """``(kind, name)``: unique within a node."""
        return (self.kind, self.name)

    @property
    def section(self) -> str:
        """The document section the entity belongs to."""
        return self.kind.section

    @property
    def is_parameter(self) -> bool:
        """True for a parameter."""
        return self.kind is _PARAMETER

    @property
    def default_value(self) -> Any:
        """A parameter's default (None for endpoints and parameters without one)."""
        return getattr(self.definition, 'default_value', None)

    @property
    def read_only(self) -> bool:
        """True for a read-only parameter."""
        return bool(getattr(self.definition, 'read_only', False))

    def __str__(self) -> str:
        return f'{self.kind.word} {self.name!r} ({self.type_name}, {self.layer})'

    def __repr__(self) -> str:
        return (f'Entity({self.kind.value}, {self.name!r}, {self.type_name!r}, layer={self.layer!r}, '
                f'provider={self.provider.value})')


def parse_entity_type(kind: EntityKind, type_name: str) -> EntityType:
    """The parsed type of an entity of ``kind`` written as ``type_name`` (None if unparsable)."""
    try:
        return _parsed_type(kind, type_name)
    except TypeError:  # not hashable: not a type name either
        return _parse_entity_type(kind, type_name)


@lru_cache(maxsize=4096)  # the same types (every base's, std_msgs...) recur in every node
def _parsed_type(kind: EntityKind, type_name: str) -> EntityType:
    return _parse_entity_type(kind, type_name)


def _parse_entity_type(kind: EntityKind, type_name: str) -> EntityType:
    if kind is EntityKind.PARAMETER:
        return parse_type(type_name)
    try:
        return InterfaceType.parse(type_name, kind.communication)
    except ValueError:
        return None
