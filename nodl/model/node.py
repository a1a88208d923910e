"""The node definition model: base + mixins + main."""

from __future__ import annotations

import copy
import enum
from dataclasses import dataclass, field
from typing import Any

from nodl.model.interface import Interface

__all__ = ['Base', 'Mixin', 'Node']


class Base(str, enum.Enum):
    """The built-in ROS 2 node types a node definition can inherit from."""

    NODE = 'node'
    LIFECYCLE_NODE = 'lifecycle_node'

    def __str__(self) -> str:
        return self.value


#: A mixin is a reference (``nodl://pkg/name`` or a relative path) or an
#: in-place interface definition.
Mixin = str | Interface


@dataclass(slots=True)
class Node:
    """A node definition."""

    main: Interface = field(default_factory=Interface)
    nodl_version: int = 2
    base: Base | None = None
    mixins: list[Mixin] | None = None
    #: Settings for code generators, keyed by tool, kept as written and never interpreted
    #: (the reference implementation's ``codegen``; an include-dialect file's lands here).
    codegen: dict[str, dict[str, Any]] | None = None

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Node:
        """Build from a validated mapping."""
        base = data.get('base')
        mixins = data.get('mixins')
        return cls(
            Interface.from_dict(data['main']),
            data.get('nodl_version', 2),
            Base(base) if base is not None else None,
            [m if isinstance(m, str) else Interface.from_dict(m) for m in mixins]
            if mixins is not None else None,
            copy.deepcopy(data['codegen']) if data.get('codegen') is not None else None,
        )

    def to_dict(self) -> dict[str, Any]:
        """The mapping a NoDL file holds."""
        out: dict[str, Any] = {'nodl_version': self.nodl_version}
        if self.base is not None:
            out['base'] = Base(self.base).value
        if self.mixins is not None:
            out['mixins'] = [m if isinstance(m, str) else m.to_dict() for m in self.mixins]
        if self.codegen is not None:
            out['codegen'] = copy.deepcopy(self.codegen)
        out['main'] = self.main.to_dict()
        return out
