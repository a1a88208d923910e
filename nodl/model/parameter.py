"""The parameter definition model."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from nodl.model.parameter_types import TypeSpec, parse_type

__all__ = ['ParameterDefinition']


@dataclass(slots=True)
class ParameterDefinition:
    """One ROS 2 parameter (the generate_parameter_library shape)."""

    type: str
    #: The initial value; ``None`` when the parameter has no default (it must
    #: then be given when the node starts).
    default_value: Any = None
    description: str = ''
    read_only: bool = False
    additional_constraints: str = ''
    #: Validator name (as written, e.g. ``bounds<>``) -> arguments.
    validation: dict[str, Any] | None = None
    #: Where this entity came from after composition (base, mixin, main).
    origin: str | None = field(default=None, compare=False, repr=False)

    @property
    def type_spec(self) -> TypeSpec | None:
        """The parsed type (None if the type is not a known parameter type)."""
        return parse_type(self.type)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ParameterDefinition:
        """Build from a validated mapping."""
        return cls(
            data['type'],
            data.get('default_value'),
            data.get('description', ''),
            data.get('read_only', False),
            data.get('additional_constraints', ''),
            dict(data['validation']) if data.get('validation') is not None else None,
        )

    def to_dict(self) -> dict[str, Any]:
        """The mapping a NoDL file holds (defaults left out)."""
        out: dict[str, Any] = {'type': self.type}
        if self.default_value is not None:
            out['default_value'] = self.default_value
        if self.description:
            out['description'] = self.description
        if self.read_only:
            out['read_only'] = True
        if self.additional_constraints:
            out['additional_constraints'] = self.additional_constraints
        if self.validation is not None:
            out['validation'] = self.validation
        return out
