"""Merging layers: base, then mixins in order, then main; later layers win.

Every entity of the result records its layer in ``origin``, and every layer
that declares it is traced (:class:`Declaration`), so that consumers know
where an entity was first declared (who provides it) and where it was last
refined.

The override policy: a later layer may refine an entity of an earlier layer
(its description, a parameter's default or validators) -- an info
diagnostic naming both layers.  What no real node can do is an error: a
later layer changing the interface type, the QoS or a parameter's type or
``read_only`` of an entity of the base (the client library creates those
entities, the node cannot change them).  A type change between a mixin and
a later layer is a warning (the mixin's code and the node disagree).  Each
diagnostic is placed at the overriding declaration and relates the
overridden one.
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Sequence
from typing import Any, NamedTuple

from nodl.composition.layers import Layer
from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.model import ENDPOINT_SECTIONS, Interface
from nodl.model.interface import ActionEndpoint, ServiceEndpoint, TopicEndpoint
from nodl.model.parameter import ParameterDefinition
from nodl.validation.interfaces import SECTIONS

__all__ = ['Declaration', 'MergeResult', 'merge_layers', 'merge_traced', 'PARAMETERS']

#: The pseudo-section of parameters in traced declarations.
PARAMETERS = 'parameters'

#: Override codes (see :mod:`nodl.codes`).
OVERRIDE = 'NODL304'
BASE_TYPE_CHANGED = 'NODL307'
BASE_QOS_CHANGED = 'NODL308'
BASE_READ_ONLY_CHANGED = 'NODL309'
MIXIN_TYPE_CHANGED = 'NODL310'


class Declaration(NamedTuple):
    """One layer's declaration of an entity: the layer, its path in the layer, the entity."""

    layer: Layer
    path: DocPath
    entity: Any


class MergeResult(NamedTuple):
    """The merged interface, the override diagnostics and every entity's declarations."""

    interface: Interface
    diagnostics: list[Diagnostic]
    #: (section or ``parameters``, name) -> every declaration, first layer first (read-only:
    #: the lists of a shared base's entities are shared by every node of a run).
    declarations: dict[tuple[str, str], list[Declaration]]


def _stamp(entity: Any, label: str) -> Any:
    """A shallow copy of ``entity`` whose ``origin`` is ``label``."""
    cls = type(entity)
    fields = _SLOTS.get(cls)
    if fields is None:
        stamped = copy.copy(entity)
    else:  # the model's slotted dataclasses: field by field (copy.copy goes through pickling)
        stamped = object.__new__(cls)
        for name in fields:
            object.__setattr__(stamped, name, getattr(entity, name))
    stamped.origin = label
    return stamped


def _slotted(cls: type) -> tuple[str, ...] | None:
    """The fields of a slotted dataclass of the model without a base class, else None."""
    if cls.__bases__ != (object,) or not dataclasses.is_dataclass(cls) or '__dict__' in dir(cls):
        return None
    fields = tuple(f.name for f in dataclasses.fields(cls))
    return fields if set(fields) == set(getattr(cls, '__slots__', ())) else None


#: Entity class -> its fields, for the classes a shallow copy may be made field by field.
_SLOTS: dict[type, tuple[str, ...]] = {}
for _cls in (TopicEndpoint, ServiceEndpoint, ActionEndpoint, ParameterDefinition):
    _found = _slotted(_cls)
    if _found is not None:
        _SLOTS[_cls] = _found


def _related(earlier: Declaration, anchor: str) -> tuple[str, int, int, str]:
    placed = earlier.layer.place(Diagnostic(Severity.INFO, '', earlier.path, anchor=anchor))
    return (placed.file, placed.line, placed.column, f'the declaration in {earlier.layer.label}')


def _qos(entity: Any) -> Any:
    qos = getattr(entity, 'qos', None)
    return qos.to_dict() if qos is not None else None


def _verdicts(word: str, name: str, earlier: Declaration, previous: Declaration, later: Layer,
              entity: Any, parameter: bool) -> list[tuple[Severity, str, str]]:
    """(severity, code, message) for each change ``later`` makes to ``earlier``'s entity.

    ``previous`` is the declaration ``later`` replaces (named by a plain override).
    """
    old = earlier.entity
    out: list[tuple[Severity, str, str]] = []
    was = earlier.layer.label
    if earlier.layer.role == 'base':
        if old.type != entity.type:
            out.append((Severity.ERROR, BASE_TYPE_CHANGED,
                        f"{word} '{name}' from {later.label} changes the type of the one from {was} "
                        f'({old.type} -> {entity.type}); the client library creates it, so a node '
                        'cannot change it: only its description may be refined'))
        if not parameter and _qos(entity) is not None and _qos(old) != _qos(entity):
            out.append((Severity.ERROR, BASE_QOS_CHANGED,
                        f"{word} '{name}' from {later.label} changes the QoS of the one from {was}; "
                        'the client library creates it with its own QoS: leave qos as in the base '
                        'or only refine the description'))
        if parameter and bool(old.read_only) != bool(entity.read_only):
            out.append((Severity.ERROR, BASE_READ_ONLY_CHANGED,
                        f"parameter '{name}' from {later.label} changes read_only of the one from "
                        f'{was} ({old.read_only} -> {entity.read_only}); the client library '
                        'declares it, so a node cannot change it'))
    elif old.type != entity.type:
        out.append((Severity.WARNING, MIXIN_TYPE_CHANGED,
                    f"{word} '{name}' from {later.label} changes the type of the one from {was} "
                    f'({old.type} -> {entity.type}); the code behind {was} and this node disagree'))
    if not out:
        out.append((Severity.INFO, OVERRIDE,
                    f"{word} '{name}' from {later.label} overrides the one from "
                    f'{previous.layer.label}'))
    return out


def merge_traced(layers: Sequence[Layer]) -> MergeResult:
    """Merge ``layers``; also return every entity's declarations (see :class:`MergeResult`)."""
    notes: list[Diagnostic] = []
    declarations: dict[tuple[str, str], list[Declaration]] = {}
    parameters: dict[str, Any] = {}
    sections: dict[str, dict[str, Any]] = {s: {} for s in ENDPOINT_SECTIONS}
    seed = _seed(layers[0]) if layers and layers[0].shared is not None else None
    if seed is not None:
        # A first layer every node of the run shares (a base): what merging it alone gives is
        # made once and copied (a thousand nodes would otherwise redo the same dozen entities).
        seed_declarations, seed_parameters, seed_sections = seed
        # Its one-declaration traces are shared too, until a later layer adds to one (below).
        declarations = dict(seed_declarations)
        parameters.update(seed_parameters)
        for section, merged in seed_sections:
            sections[section].update(merged)
        layers = layers[1:]

    def declare(section: str, name: str, layer: Layer, path: DocPath, entity: Any,
                merged: dict[str, Any], word: str, anchor: str) -> None:
        key = (section, name)
        trace = declarations.get(key)
        if trace is None:
            trace = declarations[key] = []
        elif seed is not None and trace is seed[0].get(key):
            trace = declarations[key] = list(trace)  # (a shared trace is never changed)
        if trace:
            # What the base declares is judged against the base, whatever refined it since.
            earlier = trace[0] if trace[0].layer.role == 'base' else trace[-1]
            for severity, code, message in _verdicts(word, name, earlier, trace[-1], layer,
                                                     entity, section == PARAMETERS):
                notes.append(layer.place(Diagnostic(
                    severity, message, path, anchor=anchor, code=code,
                    related=[_related(earlier, anchor)])))
        trace.append(Declaration(layer, path, entity))
        shared = layer.shared
        if shared is None:
            merged[name] = _stamp(entity, layer.label)
        else:  # a layer every node of the run shares: one copy for all of them
            stamped = shared.get(('stamped', id(entity)))
            if stamped is None:
                stamped = shared[('stamped', id(entity))] = _stamp(entity, layer.label)
            merged[name] = stamped

    for layer in layers:
        iface = layer.interface
        for name, param in (iface.parameters or {}).items():
            declare(PARAMETERS, name, layer, (PARAMETERS, name), param, parameters, 'parameter',
                    'key')
        for section, word in SECTIONS.items():
            for index, entity in enumerate(getattr(iface, section) or ()):
                declare(section, entity.name, layer, (section, index), entity, sections[section],
                        word, 'value')
    result = Interface(nodl_version=2)
    main = layers[-1].interface if layers else None
    result.description = main.description if main is not None else None
    if parameters:
        result.parameters = dict(parameters)
    for section, merged in sections.items():
        if merged:
            setattr(result, section, list(merged.values()))
    return MergeResult(result, notes, declarations)


#: What merging one shared layer alone gives: its declarations (key, declaration), its
#: parameters and its endpoints per section (name -> stamped entity).
_Seed = tuple[dict[tuple[str, str], list[Declaration]], dict[str, Any],
              tuple[tuple[str, dict[str, Any]], ...]]


def _seed(layer: Layer) -> _Seed:
    """Merge a shared layer (a built-in base) alone, once per layer (kept in
    :attr:`Layer.shared`).  Its entities' names are unique (the built-in bases are valid), so
    it has no overrides of its own."""
    shared = layer.shared
    assert shared is not None
    found: _Seed | None = shared.get('merge seed')
    if found is None:
        traced: dict[tuple[str, str], list[Declaration]] = {}
        parameters: dict[str, Any] = {}
        for name, param in (layer.interface.parameters or {}).items():
            traced[(PARAMETERS, name)] = [Declaration(layer, (PARAMETERS, name), param)]
            parameters[name] = _stamp(param, layer.label)
        sections = []
        for section in SECTIONS:
            merged: dict[str, Any] = {}
            for index, entity in enumerate(getattr(layer.interface, section) or ()):
                traced[(section, entity.name)] = [Declaration(layer, (section, index), entity)]
                merged[entity.name] = _stamp(entity, layer.label)
            sections.append((section, merged))
        found = shared['merge seed'] = (traced, parameters, tuple(sections))
    return found


def seeded_copies(layer: Layer) -> frozenset[int]:
    """The ids of the merged copies a shared layer gives every node it is the first layer of
    (see :attr:`Layer.shared`; they live as long as the layer): a node's merged entity that is
    one of them is declared by that layer alone."""
    shared = layer.shared
    assert shared is not None
    found: frozenset[int] | None = shared.get('seeded copies')
    if found is None:
        _, parameters, sections = _seed(layer)
        found = shared['seeded copies'] = frozenset(
            [id(p) for p in parameters.values()]
            + [id(e) for _, merged in sections for e in merged.values()])
    return found


def merge_layers(layers: Sequence[Layer]) -> tuple[Interface, list[Diagnostic]]:
    """The merged interface of ``layers`` and the override diagnostics."""
    merged = merge_traced(layers)
    return merged.interface, merged.diagnostics
