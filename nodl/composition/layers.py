"""A layer of a composed node: one interface definition and where it came from."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from nodl.diagnostics import Diagnostic, DocPath
from nodl.model import Interface

__all__ = ['Layer', 'MAIN']

#: The label of the ``main`` layer.
MAIN = 'main'


class Layer:
    """One layer: ``base:<name>``, a mixin (its reference, or ``mixins[i]`` in place) or ``main``."""

    __slots__ = ('label', 'interface', '_place', 'prefix', 'role', 'shared', 'file')

    def __init__(self, label: str, interface: Interface,
                 place: Callable[[Diagnostic], Diagnostic] | None = None,
                 prefix: DocPath = (), role: str | None = None, file: str | None = None) -> None:
        self.label = label
        #: The file the interface was read from (None for a built-in base).
        self.file = file
        self.interface = interface
        self._place = place
        #: Where the interface sits in its document (``('main',)`` in a node file).
        self.prefix = prefix
        #: ``base``, ``mixin`` or ``main`` (by default guessed from the label; a mixin
        #: reference may look like a base or main label, e.g. a file called ``main``).
        self.role = role if role is not None else (
            'base' if label.startswith('base:') else 'main' if label == MAIN else 'mixin')
        #: For a layer shared by every node of a run (a built-in base, see
        #: :func:`nodl.composition.bases.shared_base_layer`): what is derived from its
        #: entities once for all those nodes (merged copies, resolved entities); else None.
        self.shared: dict[Any, Any] | None = None

    def place(self, diagnostic: Diagnostic) -> Diagnostic:
        """Place a diagnostic whose path is relative to this layer's interface."""
        moved = diagnostic.replace(path=self.prefix + diagnostic.path)
        return self._place(moved) if self._place is not None else moved

    @property
    def is_base(self) -> bool:
        """True for the base layer."""
        return self.role == 'base'

    def __repr__(self) -> str:
        return f'Layer({self.label!r})'

    def __eq__(self, other: Any) -> bool:
        return isinstance(other, Layer) and (self.label, self.interface) == (other.label, other.interface)
