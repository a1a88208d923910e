"""The QoS profile model (policies as rmw names them, durations in nanoseconds)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from nodl.vocabulary import QOS_KEYS

__all__ = ['QoSProfile', 'QOS_POLICIES']


@dataclass(slots=True)
class QoSProfile:
    """A QoS profile as written in a NoDL file."""

    history: str
    reliability: str
    depth: int | None = None
    durability: str | None = None
    deadline_ns: int | None = None
    lifespan_ns: int | None = None
    liveliness: str | None = None
    liveliness_lease_duration_ns: int | None = None

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> QoSProfile:
        """Build from a validated mapping."""
        return cls(**data)

    def to_dict(self) -> dict[str, Any]:
        """The mapping a NoDL file holds (unset policies left out)."""
        out: dict[str, Any] = {}
        for name in QOS_POLICIES:
            value = getattr(self, name)
            if value is not None:
                out[name] = value
        return out


#: Field names in file order (the vocabulary's QoS keys; a test keeps the fields in agreement).
QOS_POLICIES = QOS_KEYS
