"""The interface definition model: parameters and endpoints."""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Any

from nodl.model.parameter import ParameterDefinition
from nodl.model.qos import QoSProfile
from nodl.vocabulary import SECTIONS

__all__ = ['TopicEndpoint', 'ServiceEndpoint', 'ActionEndpoint', 'Endpoint', 'Interface',
           'ENDPOINT_SECTIONS']


@dataclass(slots=True)
class TopicEndpoint:
    """A publisher or a subscription (the section says which)."""

    name: str
    type: str
    qos: QoSProfile
    description: str | None = None
    origin: str | None = field(default=None, compare=False, repr=False)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> TopicEndpoint:
        """Build from a validated mapping."""
        return cls(data['name'], data['type'], QoSProfile.from_dict(data['qos']),
                   data.get('description'))

    def to_dict(self) -> dict[str, Any]:
        """The mapping a NoDL file holds."""
        out: dict[str, Any] = {'name': self.name, 'type': self.type}
        if self.description is not None:
            out['description'] = self.description
        out['qos'] = self.qos.to_dict()
        return out


@dataclass(slots=True)
class ServiceEndpoint:
    """A service server or client (the section says which)."""

    name: str
    type: str
    qos: QoSProfile | None = None
    description: str | None = None
    origin: str | None = field(default=None, compare=False, repr=False)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ServiceEndpoint:
        """Build from a validated mapping."""
        qos = data.get('qos')
        return cls(data['name'], data['type'], QoSProfile.from_dict(qos) if qos else None,
                   data.get('description'))

    def to_dict(self) -> dict[str, Any]:
        """The mapping a NoDL file holds."""
        out: dict[str, Any] = {'name': self.name, 'type': self.type}
        if self.description is not None:
            out['description'] = self.description
        if self.qos is not None:
            out['qos'] = self.qos.to_dict()
        return out


@dataclass(slots=True)
class ActionEndpoint:
    """An action server or client (the section says which)."""

    name: str
    type: str
    description: str | None = None
    origin: str | None = field(default=None, compare=False, repr=False)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ActionEndpoint:
        """Build from a validated mapping."""
        return cls(data['name'], data['type'], data.get('description'))

    def to_dict(self) -> dict[str, Any]:
        """The mapping a NoDL file holds."""
        out: dict[str, Any] = {'name': self.name, 'type': self.type}
        if self.description is not None:
            out['description'] = self.description
        return out


Endpoint = TopicEndpoint | ServiceEndpoint | ActionEndpoint

_ENDPOINT_CLASSES = {'topic': TopicEndpoint, 'service': ServiceEndpoint, 'action': ActionEndpoint}
#: Section name -> endpoint class, in file order (derived from :mod:`nodl.vocabulary`).
ENDPOINT_SECTIONS: dict[str, Any] = {s.key: _ENDPOINT_CLASSES[s.kind] for s in SECTIONS}


@dataclass(slots=True)
class Interface:
    """An interface definition: a (possibly partial) node interface.

    ``Interface(nodl_version=2)`` is an empty one.  Sections that are absent
    are ``None`` (as in the reference implementation).
    """

    nodl_version: int = 2
    description: str | None = None
    parameters: dict[str, ParameterDefinition] | None = None
    publishers: list[TopicEndpoint] | None = None
    subscriptions: list[TopicEndpoint] | None = None
    service_servers: list[ServiceEndpoint] | None = None
    service_clients: list[ServiceEndpoint] | None = None
    action_servers: list[ActionEndpoint] | None = None
    action_clients: list[ActionEndpoint] | None = None
    #: Settings for code generators, keyed by tool (``cpp``, ``python``...), kept as written
    #: and never interpreted (the reference implementation's ``codegen``).
    codegen: dict[str, dict[str, Any]] | None = None

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Interface:
        """Build from a validated mapping."""
        iface = cls(data.get('nodl_version', 2), data.get('description'))
        codegen = data.get('codegen')
        if codegen is not None:
            iface.codegen = copy.deepcopy(codegen)
        params = data.get('parameters')
        if params is not None:
            iface.parameters = {name: ParameterDefinition.from_dict(p) for name, p in params.items()}
        for section, endpoint in ENDPOINT_SECTIONS.items():
            entries = data.get(section)
            if entries is not None:
                setattr(iface, section, [endpoint.from_dict(e) for e in entries])
        return iface

    def to_dict(self) -> dict[str, Any]:
        """The mapping a NoDL file holds (absent sections left out)."""
        out: dict[str, Any] = {'nodl_version': self.nodl_version}
        if self.description is not None:
            out['description'] = self.description
        if self.codegen is not None:
            out['codegen'] = copy.deepcopy(self.codegen)
        if self.parameters is not None:
            out['parameters'] = {name: p.to_dict() for name, p in self.parameters.items()}
        for section in ENDPOINT_SECTIONS:
            entries = getattr(self, section)
            if entries is not None:
                out[section] = [e.to_dict() for e in entries]
        return out

    def endpoints(self, section: str) -> list[Any]:
        """The entries of ``section`` (empty when absent)."""
        if section not in ENDPOINT_SECTIONS:
            raise KeyError(f'unknown section {section!r}; expected one of {list(ENDPOINT_SECTIONS)}')
        return getattr(self, section) or []
