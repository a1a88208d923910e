"""``check``: does a running node conform to its (composed) definition?

Declared names are resolved as the node resolves them (expanded against its
name and namespace and remapped with its rules, by :mod:`nodl.naming`),
then compared with what the graph reports.  Each difference has a kind:

* ``missing`` (declared, not observed) and ``extra`` (observed, not declared);
* ``type`` (same name, another interface type);
* ``qos`` (one per policy, declared against observed);
* ``parameter_type`` and ``read_only``;
* ``value`` (a warning: the current value breaks the declared validators);
* ``unverifiable`` (listed, never failing): what the middleware cannot
  report, such as service QoS or a topic's history on some middlewares.

Each difference names the layer that declared the entity (base, mixin
reference or main).
"""

from __future__ import annotations

from typing import Any, Iterable, Mapping, Union

from nodl.composition import ComposedNode
from nodl.system.entities import Location

TYPE_CHECKING = False
if TYPE_CHECKING:
    from nodl.system.resolved import ResolvedNode
from nodl.diagnostics import Diagnostic, Severity
from nodl.live.observe import ObservedNode
from nodl.model import ENDPOINT_SECTIONS, QOS_POLICIES, Interface
from nodl.naming import InvalidNameError, NodeNames, expand
from nodl.vocabulary import SECTION_WORDS, SERVICE_SECTIONS, TOPIC_SECTIONS

__all__ = ['Difference', 'DRIFT_KINDS', 'KIND_CODES', 'compare', 'parse_remaps', 'conforms',
           'Remaps', 'final_name']

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


class Difference:
    """One difference between the declared and the observed interface."""

    __slots__ = ('kind', 'section', 'name', 'declared', 'observed', 'layer', 'message', 'location',
                 'promoted')

    def __init__(self, kind: str, section: str, name: str, message: str, *,
                 declared: Any = None, observed: Any = None, layer: str | None = None,
                 location: Location | None = None, promoted: bool = False) -> None:
        self.kind = kind
        self.section = section
        self.name = name
        self.declared = declared
        self.observed = observed
        self.layer = layer
        self.message = message
        #: Where the entity is declared (file, line, column), when checked against a
        #: resolved node; None for what is observed but not declared.
        self.location = location
        #: True when ``--error CODE`` (or a configuration) made this difference an error.
        self.promoted = promoted

    @property
    def severity(self) -> str:
        """``error`` for drift (or a promoted code), ``warning`` for a bad value, ``info`` for
        unverifiable."""
        if self.kind in DRIFT_KINDS or self.promoted:
            return 'error'
        return 'warning' if self.kind == 'value' else 'info'

    @property
    def code(self) -> str:
        """The stable diagnostic code of this kind of difference (``NODL401`` ...)."""
        return KIND_CODES[self.kind]

    def to_diagnostic(self, file: str | None = None, line: int = 0, column: int = 0) -> Diagnostic:
        """The same difference as a :class:`~nodl.diagnostics.Diagnostic`.

        ``file`` (and a position, when known) is the definition; without one,
        the difference's ``location`` (the entity's declaration) is used, else
        ``<definition>``.  The path is ``(section, name)``; the layer, if any, is
        in the message as in the text output.
        """
        if file is None:
            file, line, column = self.location if self.location is not None else (
                '<definition>', 0, 0)
        layer = f' (declared in {self.layer})' if self.layer else ''
        return Diagnostic(Severity(self.severity), f'{self.kind}: {self.message}{layer}',
                          (self.section, self.name), file, line, column, code=self.code)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping."""
        return {'kind': self.kind, 'code': self.code, 'severity': self.severity, 'section': self.section,
                'name': self.name, 'declared': self.declared, 'observed': self.observed,
                'layer': self.layer, 'message': self.message}

    def __str__(self) -> str:
        layer = f' (declared in {self.layer})' if self.layer else ''
        return f'{self.severity}: {self.kind}: {self.message}{layer} [{self.code}]'

    def __repr__(self) -> str:
        return f'Difference({self.kind!r}, {self.section!r}, {self.name!r})'


#: How a node's names are remapped: its :class:`~nodl.naming.NodeNames` (exact: what
#: rcl does, topics and services apart) or a mapping of expanded topic names FROM -> TO.
Remaps = Union[NodeNames, Mapping[str, str], None]


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


def conforms(differences: Iterable[Difference]) -> bool:
    """True if no difference is drift (an error: a drift kind, or a promoted code)."""
    return not any(d.severity == 'error' for d in differences)


def _word(section: str) -> str:
    return SECTION_WORDS[section]


def _compare_qos(section: str, name: str, declared: Any, observed: dict[str, Any] | None,
                 unobserved: list[str], layer: str | None) -> list[Difference]:
    out: list[Difference] = []
    if declared is None:
        return out
    word = _word(section)
    if observed is None:
        return [Difference('unverifiable', section, name, f"QoS of {word} '{name}' could not be "
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
            out.append(Difference('unverifiable', section, name,
                                  f"{word} '{name}' {policy}: declared {want}, {why}",
                                  declared=want, layer=layer))
            continue
        have = observed.get(policy)
        if policy.endswith('_ns') and have is None:
            have = 0  # not reported = infinite / none, which 0 means in NoDL
        if have != want:
            out.append(Difference('qos', section, name, f"{word} '{name}' {policy}: declared "
                                  f'{want}, observed {have}', declared=want, observed=have,
                                  layer=layer))
    return out


def _compare_parameters(declared: Interface, observed: ObservedNode) -> list[Difference]:
    from nodl.validation.parameters import check_parameter

    out: list[Difference] = []
    params = declared.parameters or {}
    if observed.parameters is None:
        if params:
            out.append(Difference('unverifiable', 'parameters', '*', 'parameters could not be read '
                                  'from the node, so none was checked'))
        return out
    for name, param in params.items():
        real = observed.parameters.get(name)
        if real is None:
            out.append(Difference('missing', 'parameters', name,
                                  f"parameter '{name}' is declared but the node has no such parameter",
                                  declared=param.type, layer=param.origin))
            continue
        if real.type != param.type and not (param.type_spec and real.type == param.type_spec.base):
            out.append(Difference('parameter_type', 'parameters', name,
                                  f"parameter '{name}': declared type {param.type}, observed "
                                  f'{real.type}', declared=param.type, observed=real.type,
                                  layer=param.origin))
            continue
        if bool(param.read_only) != real.read_only:
            out.append(Difference('read_only', 'parameters', name,
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
                    out.append(Difference('value', 'parameters', name, f"parameter '{name}': {message}",
                                          declared=param.validation, observed=real.value,
                                          layer=param.origin))
    for name in sorted(set(observed.parameters) - set(params)):
        if name.startswith('qos_overrides.'):
            continue
        out.append(Difference('extra', 'parameters', name,
                              f"parameter '{name}' is not declared", observed=observed.parameters[name].type))
    return out


def compare(composed: ResolvedNode | ComposedNode | Interface, observed: ObservedNode,
            remaps: Remaps = None) -> list[Difference]:
    """Every difference between a declared interface and an observed node.

    ``composed``: the resolved node (then each difference about a declared
    entity carries the ``location`` of its declaration), a composition, or a
    plain interface.  ``remaps``: the node's :class:`~nodl.naming.NodeNames`
    (its final name and rules), or a mapping of expanded topic names (see
    :func:`final_name`).
    """
    from nodl.system.resolved import ResolvedNode

    if isinstance(composed, ComposedNode):
        composed = ResolvedNode(composed)
    declared = composed.interface if isinstance(composed, ResolvedNode) else composed
    # declaration (the merged model object) -> where it is written
    where = ({id(e.definition): e.location for e in composed.entities}
             if isinstance(composed, ResolvedNode) else {})
    out: list[Difference] = []
    for section in ENDPOINT_SECTIONS:
        word = _word(section)
        wanted: dict[str, Any] = {}
        for entity in declared.endpoints(section):
            wanted[final_name(entity.name, section, observed, remaps)] = entity
        seen = {e.name: e for e in getattr(observed, section)}
        for full, entity in wanted.items():
            first = len(out)
            _compare_endpoint(section, word, full, entity, seen.get(full), out)
            for difference in out[first:]:
                difference.location = where.get(id(entity))
        for full in sorted(set(seen) - set(wanted)):
            out.append(Difference('extra', section, full, f"{word} '{full}' ({seen[full].type}) is "
                                  'observed but not declared', observed=seen[full].type))
    first = len(out)
    out += _compare_parameters(declared, observed)
    for difference in out[first:]:
        param = (declared.parameters or {}).get(difference.name)
        difference.location = where.get(id(param)) if param is not None else None
    return out


def _compare_endpoint(section: str, word: str, full: str, entity: Any, real: Any,
                      out: list[Difference]) -> None:
    """The differences between one declared endpoint and what is observed under its name."""
    if real is None:
        out.append(Difference('missing', section, full, f"{word} '{full}' ({entity.type}) is "
                              'declared but not observed', declared=entity.type,
                              layer=entity.origin))
        return
    if real.type != entity.type:
        out.append(Difference('type', section, full, f"{word} '{full}': declared type "
                              f'{entity.type}, observed {real.type}', declared=entity.type,
                              observed=real.type, layer=entity.origin))
        return
    if section in TOPIC_SECTIONS:
        out += _compare_qos(section, full, entity.qos, real.qos, real.unobserved, entity.origin)
    elif section in SERVICE_SECTIONS and entity.qos is not None:
        out.append(Difference('unverifiable', section, full, f"{word} '{full}' QoS: the "
                              'middleware does not report service QoS',
                              declared=entity.qos.to_dict(), layer=entity.origin))
