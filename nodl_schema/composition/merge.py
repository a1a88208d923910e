"""Merging layers: base, then mixins in order, then main; later layers win.

Every entity of the result records its layer in ``origin``.  An entity that
replaces one of an earlier layer is reported as an info diagnostic naming
both layers, placed where the winning entity is declared.
"""

from __future__ import annotations

import copy
from typing import Any, Sequence

from nodl_schema.diagnostics import Diagnostic, Severity
from nodl_schema.composition.layers import Layer
from nodl_schema.model import ENDPOINT_SECTIONS, Interface
from nodl_schema.validation.interfaces import SECTIONS

__all__ = ['merge_layers']


def _stamp(entity: Any, label: str) -> Any:
    stamped = copy.copy(entity)
    stamped.origin = label
    return stamped


def merge_layers(layers: Sequence[Layer]) -> tuple[Interface, list[Diagnostic]]:
    """The merged interface of ``layers`` and the override diagnostics."""
    notes: list[Diagnostic] = []
    parameters: dict[str, tuple[Any, Layer]] = {}
    sections: dict[str, dict[str, tuple[Any, Layer]]] = {s: {} for s in ENDPOINT_SECTIONS}
    for layer in layers:
        iface = layer.interface
        for name, param in (iface.parameters or {}).items():
            if name in parameters:
                notes.append(layer.place(Diagnostic(
                    Severity.INFO, f"parameter '{name}' from {layer.label} overrides the one from "
                    f'{parameters[name][1].label}', ('parameters', name), anchor='key')))
            parameters[name] = (_stamp(param, layer.label), layer)
        for section, word in SECTIONS.items():
            merged = sections[section]
            for index, entity in enumerate(getattr(iface, section) or ()):
                if entity.name in merged:
                    notes.append(layer.place(Diagnostic(
                        Severity.INFO, f"{word} '{entity.name}' from {layer.label} overrides the one "
                        f'from {merged[entity.name][1].label}', (section, index))))
                merged[entity.name] = (_stamp(entity, layer.label), layer)
    result = Interface(nodl_version=2)
    main = layers[-1].interface if layers else None
    result.description = main.description if main is not None else None
    if parameters:
        result.parameters = {name: entity for name, (entity, _) in parameters.items()}
    for section, merged in sections.items():
        if merged:
            setattr(result, section, [entity for entity, _ in merged.values()])
    return result, notes
