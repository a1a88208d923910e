"""``check``: does a running node conform to its resolved definition?

Declared names are resolved as the node resolves them (expanded against its
name and namespace and remapped with its rules, by :mod:`nodl.naming`),
then compared with what the graph reports.  Every difference is a coded
:class:`~nodl.diagnostics.Diagnostic` (a :class:`LiveDiagnostic`), placed at
the declaration of its entity, and has a kind:

* ``missing`` (declared, not observed; NODL401) and ``extra`` (observed, not
  declared; NODL402);
* ``type`` (same name, another interface type; NODL403);
* ``qos`` (one per policy, declared against observed; NODL404);
* ``parameter_type`` and ``read_only`` (NODL405, NODL406);
* ``value`` (a warning: the current value breaks the declared validators; NODL407);
* ``unverifiable`` (an info, never failing): what the middleware cannot
  report, such as service QoS or a topic's history on some middlewares (NODL408).

Each difference names the layer that declared the entity (base, mixin
reference or main) and is located where that layer declares it, the other
layers that declare it being its related locations; what is observed but not
declared points at the section of ``main`` it would belong in.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from nodl.composition.entities import Entity
from nodl.composition.resolved import ResolvedNode
from nodl.diagnostics import Diagnostic, Severity
from nodl.live.observe import ObservedNode
from nodl.location import Location
from nodl.model import ENDPOINT_SECTIONS, QOS_POLICIES, Interface
from nodl.naming import InvalidNameError, NodeNames, expand
from nodl.vocabulary import SECTION_WORDS, SERVICE_SECTIONS, TOPIC_SECTIONS

__all__ = ['LiveDiagnostic', 'DRIFT_KINDS', 'KIND_CODES', 'UNPLACED', 'compare', 'place',
           'parse_remaps', 'conforms', 'Remaps', 'final_name']

#: Kinds that make a node non-conforming.
DRIFT_KINDS = ('missing', 'extra', 'type', 'qos', 'parameter_type', 'read_only', 'version_skew')

#: The diagnostic code of each kind of difference (see :mod:`nodl.codes`).
KIND_CODES = {
    'missing': 'NODL401', 'extra': 'NODL402', 'type': 'NODL403', 'qos': 'NODL404',
    'parameter_type': 'NODL405', 'read_only': 'NODL406', 'value': 'NODL407',
    'unverifiable': 'NODL408',
    # nodl.live.type_skew: the endpoint's type hash against the installed definition's
    'version_skew': 'NODL420', 'skew_unverifiable': 'NODL421', 'services_unverifiable': 'NODL422',
}

#: Where a difference points before it is placed (:func:`place`).
UNPLACED = '<definition>'


def _severity_of(kind: str) -> Severity:
    if kind in DRIFT_KINDS:
        return Severity.ERROR
    return Severity.WARNING if kind == 'value' else Severity.INFO


class LiveDiagnostic(Diagnostic):
    """One difference between a running node and its definition: a coded diagnostic.

    Its ``path`` is ``(section, name)`` (the entity's final name, as observed),
    its ``code`` that of its ``kind`` (:data:`KIND_CODES`), its ``message``
    the difference in words; besides, it keeps the ``declared`` and ``observed``
    values, the ``layer`` that declared the entity and the entity's declaration
    (``location``; None for what is not declared).  Where it points (``file``,
    ``line``, ``column``, ``related``) is set by :func:`place`.  Severity:
    error for drift, warning for a bad value, info for what cannot be verified
    (``promoted``: an error because ``--error CODE`` said so).
    """

    __slots__ = ('kind', 'declared', 'observed', 'layer', 'location')
    _FIELDS: tuple[str, ...] = (*Diagnostic._FIELDS, *__slots__)  # type: ignore[assignment]

    kind: str
    declared: Any
    observed: Any
    layer: str | None
    location: Location | None

    def __init__(self, kind: str, section: str, name: str, message: str, *,
                 declared: Any = None, observed: Any = None, layer: str | None = None,
                 location: Location | None = None, promoted: bool = False,
                 at: Location | None = None,
                 related: Iterable[tuple[str, int, int, str]] = ()) -> None:
        # where it points: ``at`` (a place of its own), else the declaration, else not yet placed
        file, line, column = at or location or (UNPLACED, 0, 0)
        super().__init__(Severity.ERROR if promoted else _severity_of(kind), message,
                         (section, name), file, line, column, code=KIND_CODES[kind],
                         related=related)
        set_ = object.__setattr__
        set_(self, 'kind', kind)
        set_(self, 'declared', declared)
        set_(self, 'observed', observed)
        set_(self, 'layer', layer)
        set_(self, 'location', location)

    def replace(self, **changes: Any) -> LiveDiagnostic:
        """A copy with some fields changed (a promoted severity, a place)."""
        new = object.__new__(type(self))
        for field in self._FIELDS:
            value = changes.pop(field, getattr(self, field))
            if field == 'severity':
                value = Severity(value)
            elif field in ('path', 'related'):
                value = tuple(value)
            object.__setattr__(new, field, value)
        if changes:
            raise TypeError(f'unknown fields: {", ".join(sorted(changes))}')
        return new

    def __reduce__(self) -> tuple[Any, ...]:
        return (_rebuild, (type(self), {f: getattr(self, f) for f in self._FIELDS}))

    def __hash__(self) -> int:  # the declared and observed values may not be hashable
        return hash(tuple(getattr(self, f) for f in Diagnostic._FIELDS))

    def placed(self, location: Location | None, at: Location | None,
               related: tuple[tuple[str, int, int, str], ...] = ()) -> LiveDiagnostic:
        """A copy about the entity declared at ``location`` (None: not declared), pointing
        at ``at`` (else at ``location``), with ``related`` locations."""
        file, line, column = at or location or (UNPLACED, 0, 0)
        new = object.__new__(type(self))
        for field in self._FIELDS:
            object.__setattr__(new, field, getattr(self, field))
        for field, value in (('location', location), ('file', file), ('line', line),
                             ('column', column), ('related', related)):
            object.__setattr__(new, field, value)
        return new

    @property
    def section(self) -> str:
        """The section of the entity (``publishers``, ``parameters``, ...)."""
        return str(self.path[0])

    @property
    def name(self) -> str:
        """The entity's name as the node uses it (final, for endpoints)."""
        return str(self.path[1])

    @property
    def promoted(self) -> bool:
        """True when ``--error CODE`` (or a configuration) made this difference an error."""
        return self.severity is Severity.ERROR and _severity_of(self.kind) is not Severity.ERROR

    def headline(self) -> str:
        """``kind: message (declared in LAYER)``: the difference in one phrase."""
        layer = f' (declared in {self.layer})' if self.layer else ''
        return f'{self.kind}: {self.message}{layer}'

    def brief(self) -> str:
        """``severity: kind: message (declared in LAYER) [CODE]``: the line ``nodl check`` prints
        after the node's name."""
        return f'{self.severity}: {self.headline()} [{self.code}]'

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping: the kind, code, severity, section, name, declared and observed
        values, layer and message, then where it points (file, line, column, related)."""
        return {'kind': self.kind, 'code': self.code, 'severity': self.severity.value,
                'section': self.section, 'name': self.name, 'declared': self.declared,
                'observed': self.observed, 'layer': self.layer, 'message': self.message,
                'file': self.file, 'line': self.line, 'column': self.column,
                'related': [{'file': f, 'line': li, 'column': c, 'message': m}
                            for f, li, c, m in self.related]}

    def __repr__(self) -> str:
        return f'LiveDiagnostic({self.kind!r}, {self.section!r}, {self.name!r})'


def _rebuild(cls: type[LiveDiagnostic], fields: dict[str, Any]) -> LiveDiagnostic:
    new = object.__new__(cls)
    for field, value in fields.items():
        object.__setattr__(new, field, value)
    return new


#: How a node's names are remapped: its :class:`~nodl.naming.NodeNames` (exact: what
#: rcl does, topics and services apart) or a mapping of expanded topic names FROM -> TO.
Remaps = NodeNames | Mapping[str, str] | None


def parse_remaps(rules: Iterable[str], node_name: str, namespace: str) -> dict[str, str]:
    """The topic remappings that ``rules`` (as given to ``--ros-args -r``) make for a node.

    The node is created as ``node_name`` in ``namespace``; ``__ns``,
    ``__node`` and ``__name`` rules change its own name (they are not topic
    remaps).  The result maps each expanded match side to its expanded
    replacement, for the rules that apply to topics and to the node (by its
    final name), the first rule winning.  Rules for services only
    (``rosservice://``) have no entry: use :class:`~nodl.naming.NodeNames`
    to resolve topics and services exactly.  Raises ``ValueError`` for a
    malformed rule or an invalid node name.
    """
    return NodeNames.create(node_name, namespace, list(rules)).topic_remaps()


def final_name(name: str, section: str, observed: ObservedNode, remaps: Remaps = None) -> str:
    """The name the observed node uses for the declared endpoint ``name`` of ``section``.

    With :class:`~nodl.naming.NodeNames`, exactly as rcl resolves it
    (service sections as services; topics and actions as topics); with a
    mapping, expanded then looked up.  A declared name rcl would refuse once
    expanded (``/{ns}`` in a namespace) stays as expanded, so it is reported
    missing rather than failing the check.
    """
    if isinstance(remaps, NodeNames):
        try:
            return remaps.resolve(name, service=section in SERVICE_SECTIONS)
        except InvalidNameError:
            return expand(name, remaps.name, remaps.namespace)
    full = expand(name, observed.name, observed.namespace)
    return remaps.get(full, full) if remaps else full


def conforms(differences: Iterable[LiveDiagnostic]) -> bool:
    """True if no difference is drift (an error: a drift kind, or a promoted code)."""
    return not any(d.severity == 'error' for d in differences)


def _word(section: str) -> str:
    return SECTION_WORDS[section]


def _compare_qos(section: str, name: str, declared: Any, observed: dict[str, Any] | None,
                 unobserved: list[str], layer: str | None) -> list[LiveDiagnostic]:
    out: list[LiveDiagnostic] = []
    if declared is None:
        return out
    word = _word(section)
    if observed is None:
        return [LiveDiagnostic('unverifiable', section, name, f"QoS of {word} '{name}' could not be "
                           'read from the graph', declared=declared.to_dict(), layer=layer)]
    for policy in QOS_POLICIES:
        want = getattr(declared, policy)
        if want is None:
            continue
        if policy == 'depth' and declared.history != 'KEEP_LAST':
            continue
        if policy in unobserved or want in ('SYSTEM_DEFAULT', 'BEST_AVAILABLE'):
            why = ('the middleware does not report it' if policy in unobserved
                   else f'{want} is resolved by the middleware')
            out.append(LiveDiagnostic('unverifiable', section, name,
                                  f"{word} '{name}' {policy}: declared {want}, {why}",
                                  declared=want, layer=layer))
            continue
        have = observed.get(policy)
        if policy.endswith('_ns') and have is None:
            have = 0  # not reported = infinite / none, which 0 means in NoDL
        if have != want:
            out.append(LiveDiagnostic('qos', section, name, f"{word} '{name}' {policy}: declared "
                                  f'{want}, observed {have}', declared=want, observed=have,
                                  layer=layer))
    return out


def _compare_parameters(declared: Interface, observed: ObservedNode) -> list[LiveDiagnostic]:
    from nodl.validation.parameters import check_parameter

    out: list[LiveDiagnostic] = []
    params = declared.parameters or {}
    if observed.parameters is None:
        if params:
            out.append(LiveDiagnostic('unverifiable', 'parameters', '*', 'parameters could not be read '
                                  'from the node, so none was checked'))
        return out
    for name, param in params.items():
        real = observed.parameters.get(name)
        if real is None:
            out.append(LiveDiagnostic('missing', 'parameters', name,
                                  f"parameter '{name}' is declared but the node has no such parameter",
                                  declared=param.type, layer=param.origin))
            continue
        if real.type != param.type and not (param.type_spec and real.type == param.type_spec.base):
            out.append(LiveDiagnostic('parameter_type', 'parameters', name,
                                  f"parameter '{name}': declared type {param.type}, observed "
                                  f'{real.type}', declared=param.type, observed=real.type,
                                  layer=param.origin))
            continue
        if bool(param.read_only) != real.read_only:
            out.append(LiveDiagnostic('read_only', 'parameters', name,
                                  f"parameter '{name}': declared read_only {param.read_only}, "
                                  f'observed {real.read_only}', declared=param.read_only,
                                  observed=real.read_only, layer=param.origin))
        if param.validation and real.value is not None:
            problems: list[Any] = []
            check_parameter({'type': param.type, 'default_value': real.value,
                             'validation': param.validation}, (), problems)
            for problem in problems:
                if problem.path == ('default_value',):
                    message = problem.message.replace('default_value', 'current value', 1)
                    out.append(LiveDiagnostic('value', 'parameters', name, f"parameter '{name}': {message}",
                                          declared=param.validation, observed=real.value,
                                          layer=param.origin))
    for name in sorted(set(observed.parameters) - set(params)):
        if name.startswith('qos_overrides.'):
            continue
        out.append(LiveDiagnostic('extra', 'parameters', name,
                              f"parameter '{name}' is not declared", observed=observed.parameters[name].type))
    return out


def compare(resolved: ResolvedNode, observed: ObservedNode,
            remaps: Remaps = None) -> list[LiveDiagnostic]:
    """Every difference between a resolved node and an observed node, placed (see :func:`place`).

    ``remaps``: the node's :class:`~nodl.naming.NodeNames` (its final name and
    rules), or a mapping of expanded topic names (see :func:`final_name`).
    """
    declared = resolved.interface
    # declaration (the merged model object) -> its entity (where it is written, which layers)
    entities = {id(e.definition): e for e in resolved.entities}
    places = _Places(resolved)
    out: list[LiveDiagnostic] = []
    for section in ENDPOINT_SECTIONS:
        word = _word(section)
        wanted: dict[str, Any] = {}
        for endpoint in declared.endpoints(section):
            wanted[final_name(endpoint.name, section, observed, remaps)] = endpoint
        seen = {e.name: e for e in getattr(observed, section)}
        for full, endpoint in wanted.items():
            found = _compare_endpoint(section, word, full, endpoint, seen.get(full))
            if found:
                entity = entities.get(id(endpoint))
                out += [places.place(d, entity) for d in found]
        extra = sorted(set(seen) - set(wanted))
        if extra:  # pointing at the section of main they would belong in
            at = places.section(section)
            out += [LiveDiagnostic('extra', section, full, f"{word} '{full}' ({seen[full].type}) "
                                   'is observed but not declared', observed=seen[full].type, at=at)
                    for full in extra]
    parameters = declared.parameters or {}
    for difference in _compare_parameters(declared, observed):
        param = parameters.get(difference.name)
        out.append(places.place(difference,
                                entities.get(id(param)) if param is not None else None))
    return out


def place(differences: Iterable[LiveDiagnostic], resolved: ResolvedNode) -> list[LiveDiagnostic]:
    """Each difference placed in ``resolved``'s files: at the declaration of its entity (its
    ``location``), the other layers that declare the entity (those it overrides) as related
    locations; for what is not declared, at the section of ``main`` it would belong in (else
    ``main``, else line 1 of the definition).  For differences found outside :func:`compare`
    (the version skew of :mod:`nodl.live.type_skew`)."""
    places = _Places(resolved)
    return [places.place(d) for d in differences]


class _Places:
    """Where the differences about one resolved node point (each section placed once)."""

    def __init__(self, resolved: ResolvedNode) -> None:
        self.resolved = resolved
        self._sections: dict[str, Location] = {}
        self._by_location: dict[Location, Entity] | None = None

    def place(self, difference: LiveDiagnostic, entity: Entity | None = None) -> LiveDiagnostic:
        if entity is not None:
            location: Location | None = entity.location
        else:
            location = difference.location
            if location is not None:
                if self._by_location is None:
                    self._by_location = {e.location: e for e in self.resolved.entities}
                entity = self._by_location.get(location)
        if location is None:
            return difference.placed(None, self.section(difference.section))
        return difference.placed(location, None, self._related(entity))

    def section(self, section: str) -> Location:
        """Where ``section`` of ``main`` is written (else ``main``, else the definition's line 1)."""
        found = self._sections.get(section)
        if found is None:
            found = Location(self.resolved.file, 1, 1)
            main = next((layer for layer in reversed(self.resolved.layers)
                         if layer.role == 'main'), None)
            if main is not None:
                placed = main.place(Diagnostic(Severity.INFO, '', (section,), anchor='key'))
                if placed.line and not placed.file.startswith('<'):
                    found = Location(placed.file, placed.line, placed.column)
            self._sections[section] = found
        return found

    def _related(self, entity: Entity | None) -> tuple[tuple[str, int, int, str], ...]:
        """The other layers that declare ``entity`` (those it overrides), as
        ``(file, line, column, message)``."""
        if entity is None or len(entity.declared_in) < 2:
            return ()
        trace = self.resolved.composed.declarations.get((entity.section, entity.name), [])
        anchor = 'key' if entity.is_parameter else 'value'
        out = []
        for declaration in trace[:-1]:
            placed = declaration.layer.place(Diagnostic(Severity.INFO, '', declaration.path,
                                                        anchor=anchor))
            out.append((placed.file, placed.line, placed.column,
                        f'overrides the declaration in {declaration.layer.label}'))
        return tuple(out)


def _compare_endpoint(section: str, word: str, full: str, entity: Any,
                      real: Any) -> list[LiveDiagnostic]:
    """The differences between one declared endpoint and what is observed under its name."""
    if real is None:
        return [LiveDiagnostic('missing', section, full, f"{word} '{full}' ({entity.type}) is "
                               'declared but not observed', declared=entity.type,
                               layer=entity.origin)]
    if real.type != entity.type:
        return [LiveDiagnostic('type', section, full, f"{word} '{full}': declared type "
                               f'{entity.type}, observed {real.type}', declared=entity.type,
                               observed=real.type, layer=entity.origin)]
    if section in TOPIC_SECTIONS:
        return _compare_qos(section, full, entity.qos, real.qos, real.unobserved, entity.origin)
    if section in SERVICE_SECTIONS and entity.qos is not None:
        return [LiveDiagnostic('unverifiable', section, full, f"{word} '{full}' QoS: the "
                               'middleware does not report service QoS',
                               declared=entity.qos.to_dict(), layer=entity.origin)]
    return []
