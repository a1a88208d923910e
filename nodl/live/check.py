"""Checking a running node against its definition: load, compose, observe, compare."""

from __future__ import annotations

import copy
import os
from collections.abc import Iterable

from nodl.composition import ComposedNode
from nodl.composition.client_library import ClientLibraryChoice
from nodl.composition.resolved import ResolvedNode
from nodl.diagnostics import Severity, ValidationError
from nodl.live.conformance import LiveDiagnostic, Remaps, compare, conforms, place
from nodl.live.observe import DISCOVERY_WINDOW, ObservedNode, observe_node, recount
from nodl.live.session import DuplicateNode
from nodl.model import ENDPOINT_SECTIONS
from nodl.naming import NodeNames
from nodl.overrides import Overrides

__all__ = ['CheckResult', 'load_definition', 'check_node', 'base_mismatch', 'RECHECK']

#: Seconds to wait before looking again when declared endpoints are missing (within the timeout).
RECHECK = 1.0


class CheckResult:
    """The outcome of one check: the node's differences from its definition, as diagnostics."""

    def __init__(self, fqn: str, definition: str, differences: list[LiveDiagnostic],
                 resolved: ResolvedNode, observed: ObservedNode, remaps: Remaps = None) -> None:
        #: The declared node, resolved (entities with their layers, providers and locations).
        self.resolved = resolved
        composed = resolved.composed
        self.fqn = fqn
        #: The topic remappings the node was checked with (expanded FROM -> TO).
        self.remaps: dict[str, str] = (remaps.topic_remaps() if isinstance(remaps, NodeNames)
                                       else dict(remaps or {}))
        #: The node's final name, namespace and rules, when checked with them: how every
        #: declared name was resolved (topics and services apart, as rcl does).
        self.names: NodeNames | None = remaps if isinstance(remaps, NodeNames) else None
        #: The definition's file.
        self.definition = definition
        #: Every (not ignored) difference: a coded diagnostic placed at the declaration of
        #: its entity (see :func:`nodl.live.conformance.place`).
        self.differences = differences
        self.composed = composed
        self.observed = observed
        #: One line when the node's base is not the declared one (``use `base: lifecycle_node```),
        #: and the differences that mismatch explains (the other base's own entities).
        self.base_hint, self.base_differences = base_mismatch(composed, observed, differences)
        #: The ``--ignore`` / ``--error`` codes applied (see :meth:`with_overrides`).
        self.overrides = Overrides()
        #: The differences the overrides silenced (not in :attr:`differences`).
        self.ignored: list[LiveDiagnostic] = []
        #: Seconds of discovery namesakes were watched for (none was seen meanwhile).
        self.watched: float | None = observed.watched

    @property
    def client_library(self) -> ClientLibraryChoice | None:
        """The client library whose base was checked, and why (None for a node without base)."""
        if self.resolved.base is None:
            return None
        return ClientLibraryChoice(self.resolved.client_library,
                                   self.resolved.client_library_reason)

    @property
    def diagnostics(self) -> list[LiveDiagnostic]:
        """Every (not ignored) difference, in order: :attr:`differences`, which are diagnostics."""
        return list(self.differences)

    @property
    def conforms(self) -> bool:
        """True if no difference is drift (decided after the overrides, if any were applied)."""
        return conforms(self.differences)

    @property
    def drift(self) -> list[LiveDiagnostic]:
        """Only the differences that are drift (errors: drift kinds and promoted codes)."""
        return [d for d in self.differences if d.severity is Severity.ERROR]

    def with_overrides(self, overrides: Overrides) -> CheckResult:
        """This result with codes silenced or promoted (``--ignore`` / ``--error``).

        The differences of an ignored code move to :attr:`ignored`; those of a
        promoted code become errors (drift), so a ``value`` warning or an
        ``unverifiable`` note can fail the check.  Conformance is decided on
        what remains.  The base hint goes when every difference it explained
        is ignored.
        """
        kept: list[LiveDiagnostic] = []
        ignored = list(self.ignored)
        of_base = {id(d) for d in self.base_differences}
        base_kept: list[LiveDiagnostic] = []
        for d in self.differences:
            if d.code in overrides.ignore:
                ignored.append(d)
                continue
            new = d
            if d.code in overrides.error and d.severity is not Severity.ERROR:
                new = d.replace(severity=Severity.ERROR)
            kept.append(new)
            if id(d) in of_base:
                base_kept.append(new)
        out = copy.copy(self)
        out.differences = kept
        out.ignored = ignored
        out.overrides = self.overrides.then(overrides)
        out.base_differences = base_kept
        if self.base_differences and not base_kept:
            out.base_hint = None
        return out


def base_mismatch(composed: ComposedNode, observed: ObservedNode,
                  differences: list[LiveDiagnostic]) -> tuple[str | None, list[LiveDiagnostic]]:
    """The one-line summary of a base mismatch, and the differences it accounts for.

    A node that serves the lifecycle services but is declared ``base: node``
    (or the reverse) differs by every entity of the lifecycle base; the
    summary says what to write instead.  ``(None, [])`` when the bases agree.
    """
    from nodl.composition.bases import base_layer
    from nodl.live.describe import deduce_base
    from nodl.naming import expand

    declared = composed.node.base
    declared_name = getattr(declared, 'value', declared)
    seen = deduce_base(observed)
    if declared_name is None or declared_name == seen:
        return None, []
    if seen == 'lifecycle_node':
        hint = 'the node serves the lifecycle services: use `base: lifecycle_node`'
    else:
        hint = 'the node does not serve the lifecycle services: use `base: node`'
    name, namespace = observed.name, observed.namespace
    entities: set[tuple[str, str]] = set()
    for base, sign in (('lifecycle_node', 1), ('node', -1)):
        interface = base_layer(base, composed.client_library).interface
        names = {(section, expand(e.name, name, namespace))
                 for section in ENDPOINT_SECTIONS for e in interface.endpoints(section)}
        names |= {('parameters', p) for p in interface.parameters or {}}
        entities = entities | names if sign > 0 else entities - names
    return hint, [d for d in differences if (d.section, d.name) in entities]


def load_definition(definition: str | os.PathLike[str] | tuple[str, str],
                    client_library: str | None = None) -> ResolvedNode:
    """Resolve a node definition given as a file or ``(package, executable)``.

    ``client_library`` (``rclpy`` or ``rclcpp``) chooses the base; by default
    the one of the package's build type for a registered node, else rclpy.
    Raises :class:`~nodl.diagnostics.ValidationError` with every
    diagnostic if it cannot be found, read or composed (OSError for an
    unreadable file, ValueError for an unknown client library).
    """
    from nodl.targets.resolve import resolve_target

    # (package, executable) is looked up in the definitions folders in force, then the index
    found = resolve_target(list(definition) if isinstance(definition, tuple)
                           else os.fspath(definition), client_library=client_library)
    if found.node is None:
        raise ValidationError(found.diagnostics)
    return found.node


def check_node(fqn: str, definition: str | os.PathLike[str] | tuple[str, str], *,
               timeout: float = 5.0, remaps: Iterable[str] = (),
               parameters: bool = True, client_library: str | None = None,
               overrides: Overrides | None = None, types: bool = True,
               watch: float = DISCOVERY_WINDOW) -> CheckResult:
    """Check the running node ``fqn`` against ``definition`` (a file or ``(package, executable)``).

    ``types``: each topic endpoint's type hash is also compared with the installed
    definition's (version skew, NODL420; see :mod:`nodl.live.type_skew`).

    ``overrides`` (codes to ignore or to report as errors) are applied to the
    result before conformance is decided (see :meth:`CheckResult.with_overrides`;
    :func:`nodl.config.overrides_for` reads a project's configuration).

    Raises ValidationError for a bad definition, LiveError when the node
    cannot be observed (NodeNotFound if it never appears within ``timeout``,
    DuplicateNode if several nodes share its name), and ValueError for a
    malformed remapping rule or an unknown ``client_library`` (whose base is
    checked: see :func:`load_definition`).  Declared endpoints that are missing are
    looked for once more when the node's endpoints next change, within ``RECHECK``
    seconds (if the timeout leaves that much), as discovery may only be late.
    Namesakes are watched for while all this goes on, and at least until discovery
    has run ``watch`` seconds (within ``timeout``): the check refuses a name several
    nodes share (:attr:`CheckResult.watched` says how long it watched).
    """
    import time

    from nodl.live.session import ros_session
    from nodl.naming import parse_remap_rules

    composed = load_definition(definition, client_library)
    # The rules as the node was given them; ``fqn`` is its final name (what ``__node`` and
    # ``__ns`` rules made it), against which node-scoped rules are matched, as rcl does.
    rules = tuple(parse_remap_rules(list(remaps)))
    start = time.monotonic()
    from nodl.live.graph_events import follower

    with ros_session() as session:
        # namesakes are counted last (recount): watched while the node is read and compared
        observed = observe_node(fqn, timeout=timeout, parameters=parameters, session=session,
                                watch=0.0)
        _refuse_namesakes(observed)
        names = NodeNames(observed.name, observed.namespace, rules)
        differences = compare(composed, observed, names)
        late = max(0.0, min(RECHECK, timeout - (time.monotonic() - start)))
        if late and any(d.kind == 'missing' and d.section != 'parameters' for d in differences):
            # Declared endpoints not seen yet may only be late in discovery: look again when
            # the node's endpoints change (within RECHECK seconds).
            graph = follower(session)
            before = graph.part(observed.fully_qualified_name)
            if graph.wait(lambda: graph.part(observed.fully_qualified_name) != before,
                          time.monotonic() + late):
                observed = observe_node(fqn, timeout=max(1.0, timeout - (time.monotonic() - start)),
                                        parameters=parameters, session=session, watch=0.0)
                differences = compare(composed, observed, names)
        if types:
            differences += _type_skew(session, composed, observed, names)
        recount(session, observed, watch, start + timeout)
        _refuse_namesakes(observed)
    result = CheckResult(observed.fully_qualified_name, composed.file, differences, composed,
                         observed, names)
    return result.with_overrides(overrides) if overrides else result


def _refuse_namesakes(observed: ObservedNode) -> None:
    if observed.instances > 1:
        raise DuplicateNode(f'{observed.instances} nodes in the graph are named '
                            f'{observed.fully_qualified_name}: their endpoints cannot be told '
                            'apart, so none is checked; give each a unique name (e.g. '
                            '--ros-args -r __node:=other_name) and check again')


def _type_skew(session: object, composed: ResolvedNode, observed: ObservedNode,
               names: NodeNames) -> list[LiveDiagnostic]:
    """The version-skew differences of the observed endpoints (one index per run), placed."""
    from nodl.interface_types import interface_index
    from nodl.live.type_skew import declared_locations, type_skew

    return place(type_skew(session, observed, interface_index(),
                           declared_locations(composed, observed, names)), composed)
