"""The expected system: which nodes should run, under which final names, with which definitions.

It is computed once, through the same analysis as ``nodl analyse`` (a launch file with its
arguments, or definitions placed by name as ``nodl policy DEFINITION... --name`` places
them), with the definitions folders (overlays) in force.  No analysis check runs: the
monitor only needs each node's final name, executable, resolved definition and naming
rules.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from nodl.composition.entities import Location
from nodl.diagnostics import Diagnostic, Severity

if TYPE_CHECKING:
    from nodl.composition.resolved import ResolvedNode
    from nodl.launch.sandbox import LaunchLimits
    from nodl.naming import NodeNames
    from nodl.registry.overlay import Definitions
    from nodl.system.launched import SystemNode
    from nodl.system.run import Analysis
    from nodl.targets.placement import Definition

__all__ = ['DeadlineTopic', 'ExpectedNode', 'ExpectedSystem', 'expected_from_launch',
           'expected_from_definitions', 'expected_from_analysis']


@dataclass(frozen=True)
class DeadlineTopic:
    """A topic a node publishes whose definition declares a deadline."""

    #: The final topic name.
    topic: str
    #: The interface type (``pkg/msg/Name``).
    type: str
    deadline_ns: int
    #: Where the publisher is declared.
    location: Location

    @property
    def expected_rate(self) -> float:
        """The rate the deadline asks for, in Hz (1 / deadline)."""
        return 1e9 / self.deadline_ns


@dataclass
class ExpectedNode:
    """One node the system should run."""

    #: Its final fully qualified name.
    fqn: str
    #: ``<package>/<executable>`` (or the plugin, or the definition file's name).
    hardware_id: str
    #: Where it is launched (the launch entry) or the definition placed.
    location: Location
    #: Its resolved definition (None: monitored for presence only).
    resolved: ResolvedNode | None = None
    #: Its final name, namespace and remapping rules (how declared names resolve).
    names: NodeNames | None = None
    #: Why it has no definition, when it has none.
    no_definition: str = ''
    #: Publishers with a declared deadline.
    deadlines: list[DeadlineTopic] = field(default_factory=list)

    @property
    def definition_file(self) -> str | None:
        """The definition's main file, if any."""
        return self.resolved.file if self.resolved is not None else None


@dataclass
class ExpectedSystem:
    """The expected nodes, by final name, and what the analysis said."""

    #: The launch file, or the definitions given.
    source: str
    nodes: dict[str, ExpectedNode] = field(default_factory=dict)
    #: Problems of the launch file or definitions (the analysis's reading findings).
    diagnostics: list[Diagnostic] = field(default_factory=list)
    #: True when the launch file or definitions could not be read at all.
    unreadable: bool = False


def _deadlines(resolved: ResolvedNode, names: NodeNames) -> list[DeadlineTopic]:
    from nodl.naming import InvalidNameError

    where = {id(e.definition): e.location for e in resolved.entities}
    out: list[DeadlineTopic] = []
    for publisher in resolved.interface.endpoints('publishers'):
        qos = publisher.qos
        if qos is None or not qos.deadline_ns:
            continue
        try:
            topic = names.resolve(publisher.name)
        except InvalidNameError:
            continue
        location = where.get(id(publisher)) or Location(resolved.file, 1, 1)
        out.append(DeadlineTopic(topic, str(publisher.type), int(qos.deadline_ns), location))
    return out


def _hardware_id(node: SystemNode) -> str:
    entry = node.entry
    what = entry.executable or entry.plugin or '?'
    if not entry.package:
        return os.path.basename(what)
    return f'{entry.package}/{what}'


def expected_from_analysis(analysis: Analysis, source: str) -> ExpectedSystem:
    """The expected system of an analysis (:func:`~nodl.system.run.analyse_launch` or
    :func:`~nodl.system.run.analyse_definitions`).

    A node whose final name cannot be computed cannot be found in the graph: it is left
    out with a warning (NODL566's wording is the analysis's; the warning here says what
    the monitor does).  Two launched nodes with one final name are expected once.
    """
    from nodl.system.run import DEFINITIONS_KIND, LAUNCH_KIND

    system = ExpectedSystem(source)
    system.diagnostics.extend(f.diagnostic for f in analysis.findings
                              if f.kind in (LAUNCH_KIND, DEFINITIONS_KIND))
    system.unreadable = bool(analysis.unreadable)
    for node in analysis.nodes:
        location = node.location
        if node.names is None:
            system.diagnostics.append(Diagnostic(
                Severity.WARNING, f'{node.executable_label}: its final name cannot be computed '
                '(see nodl analyse), so it cannot be monitored', (), str(location.file),
                int(location.line), int(location.column), code='NODL440'))
            continue
        fqn = node.fqn
        if fqn in system.nodes:
            continue
        resolved = node.match.resolved
        expected = ExpectedNode(fqn, _hardware_id(node), Location(str(location.file),
                                int(location.line), int(location.column)),
                                resolved, node.names)
        if resolved is None:
            why = ('its definition does not resolve' if node.match.problems
                   else 'no definition is registered for it')
            expected.no_definition = f'{why}: monitored for presence only'
        else:
            expected.deadlines = _deadlines(resolved, node.names)
        system.nodes[fqn] = expected
    return system


def expected_from_launch(launch_file: str, arguments: Mapping[str, str] | None = None, *,
                         client_library: str | None = None, limits: LaunchLimits | None = None,
                         definitions: Definitions | None = None,
                         prefixes: list[str] | None = None, settings: Any = None) -> ExpectedSystem:
    """The expected system of the launch file ``launch_file`` with launch ``arguments``."""
    from nodl.system.run import analyse_launch

    analysis = analyse_launch(launch_file, arguments, client_library=client_library,
                              prefixes=prefixes, settings=settings, checks={}, limits=limits,
                              definitions=definitions)
    return expected_from_analysis(analysis, launch_file)


def expected_from_definitions(targets: Sequence[Definition], names: Sequence[str] = (), *,
                              remaps: Sequence[str] = (), client_library: str | None = None,
                              definitions: Definitions | None = None,
                              prefixes: list[str] | None = None,
                              settings: Any = None) -> ExpectedSystem:
    """The expected system of definitions placed by name (the i-th of ``names`` places the
    i-th definition; by default its file's stem or executable, at ``/``).

    ValueError for more names than definitions or a malformed name or rule; OSError for
    a file that cannot be read.
    """
    from nodl.system.run import analyse_definitions

    analysis = analyse_definitions(targets, names, remaps=remaps, client_library=client_library,
                                   prefixes=prefixes, settings=settings, checks={},
                                   definitions=definitions)
    expected = expected_from_analysis(analysis, ' '.join(str(t) for t in targets))
    for node, target in zip(analysis.nodes, targets, strict=False):
        if node.fqn in expected.nodes and target.file is not None and not target.package:
            expected.nodes[node.fqn].hardware_id = os.path.basename(target.file)
    return expected
