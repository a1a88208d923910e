"""A run over a launched system: launch records -> system nodes -> checks -> findings.

:func:`analyse_launch` reads a launch file (any frontend) with
:mod:`nodl.launch`; :func:`analyse_entries` takes launch records however they were
obtained; :func:`analyse_definitions` places definitions without a launch file.  Each
returns an :class:`Analysis` (the launched nodes, their system, every finding) and never
raises for a problem in the user's files: problems are findings.  Every consumer that needs
a launched system (``analyse``, ``policy``, ``doc``, ``monitor``, ``params check``, ``describe
--launch``, the composer) asks this module; ``checks={}`` builds the system without checking it.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from nodl.composition.bases import check_client_library
from nodl.diagnostics import Diagnostic, Severity
from nodl.launch import load_launch
from nodl.launch.model import LaunchedNode, LaunchRemap, LaunchResult
from nodl.launch.params import load_parameter_file, parse_parameter_text
from nodl.launch.sandbox import LaunchLimits
from nodl.location import Location
from nodl.naming import parse_remap_rules
from nodl.registry import overlay
from nodl.registry.overlay import Definitions
from nodl.registry.registrations import one_run
from nodl.reporting import plural
from nodl.system.checks import run_checks
from nodl.system.context import AnalysisContext, AnalysisSettings
from nodl.system.findings import Finding
from nodl.system.gc_tuning import batch_collection
from nodl.system.launched import SystemNode, build_node
from nodl.system.matching import DefinitionMatcher, Match
from nodl.targets.placement import Definition, place_definitions

__all__ = [
    'DEFINITIONS_KIND',
    'LAUNCH_KIND',
    'Analysis',
    'analyse_definitions',
    'analyse_entries',
    'analyse_launch',
]

#: The kind of findings that come from reading the launch files themselves.
LAUNCH_KIND = 'launch-file'
#: The kind of findings about the definitions given (folders' layouts, definitions that do
#: not resolve in ``nodl analyse DEFINITION...``).
DEFINITIONS_KIND = 'definitions'


@dataclass
class Analysis:
    """What an analysis found."""

    #: Every launched node, in launch order.
    nodes: list[SystemNode]
    #: Every finding: launch-file problems first, then the checks', by place.
    findings: list[Finding]
    #: The launch file analysed (None for entries given directly).
    launch_file: str | None = None
    #: The context the checks ran on (the system of instances).
    context: AnalysisContext | None = field(default=None, repr=False)
    #: True if the launch file could not be read or parsed at all (exit status 2).
    unreadable: bool = False
    #: What the launch reader read: the launch file, every file it includes and every
    #: parameter file it gives a node (empty for entries given directly).
    launch_files: list[str] = field(default_factory=list)

    def files(self) -> list[str]:
        """Every file the analysis read, each once: :attr:`launch_files`, then each node's
        definition with its mixins (or the registration file of one that does not resolve).

        An output of the analysis (a report, a log, a graph) must be none of them."""
        found = list(self.launch_files)
        seen: set[int] = set()
        for node in self.nodes:
            match = node.match
            if id(match) in seen:  # (matches are shared by the instances of one executable)
                continue
            seen.add(id(match))
            if match.resolved is not None:
                found += match.resolved.files
            if match.file:
                found.append(match.file)
        return list(dict.fromkeys(found))

    @property
    def errors(self) -> list[Finding]:
        """The findings of severity error."""
        return [f for f in self.findings if f.severity is Severity.ERROR]

    def summary(self) -> str:
        """``N nodes, N errors, N warnings`` (and infos when there are some)."""
        counts = self.counts()
        parts = [plural(len(self.nodes), 'node'), plural(counts['error'], 'error'),
                 plural(counts['warning'], 'warning')]
        if counts['info']:
            parts.append(f"{counts['info']} info")
        return ', '.join(parts)

    def counts(self) -> dict[str, int]:
        """``{'error': n, 'warning': n, 'info': n}``."""
        out = {'error': 0, 'warning': 0, 'info': 0}
        for f in self.findings:
            out[f.severity.value] += 1
        return out

    def apply_overrides(self, apply: Any) -> None:
        """Apply ``--ignore``/``--error`` (``apply(file, diagnostics) -> diagnostics``, as
        :meth:`nodl.cli.diagnostic_options.DiagnosticPolicy.apply`) to every finding;
        the configuration found upward from the launch file applies."""
        file = self.launch_file
        kept: list[Finding] = []
        for finding in self.findings:
            changed = apply(file, [finding.diagnostic])
            if changed:
                kept.append(finding.with_diagnostic(changed[0]))
        self.findings = kept


def _sort_key(finding: Finding) -> tuple[Any, ...]:
    d = finding.diagnostic
    return (0 if finding.kind in (LAUNCH_KIND, DEFINITIONS_KIND) else 1, d.file, d.line, d.column,
            d.code)


def analyse_entries(entries: Iterable[LaunchedNode], *, client_library: str | None = None,
                    prefixes: list[str] | None = None,
                    settings: AnalysisSettings | None = None,
                    checks: Mapping[str, object] | None = None,
                    launch_findings: Iterable[Finding] = (),
                    launch_file: str | None = None,
                    definitions: Definitions | None = None) -> Analysis:
    """Match, instantiate and check launched nodes.

    ``entries``: the launch reader's records (:class:`~nodl.launch.model.LaunchedNode`).
    ``client_library`` forces the base's client library (default: each
    package's build type; ValueError for an unknown one).  ``checks``: the
    checks to run (default: every registered ``nodl.checks`` extension).
    ``definitions``: definitions folders looked in before the index (what is wrong with
    their layout is a finding each).
    """
    return _analyse(entries, None, client_library=client_library, prefixes=prefixes,
                    settings=settings, checks=checks, launch_findings=launch_findings,
                    launch_file=launch_file, definitions=definitions)


def _analyse(entries: Iterable[LaunchedNode], matches: list[Match] | None, *,
             client_library: str | None, prefixes: list[str] | None,
             settings: AnalysisSettings | None, checks: Mapping[str, object] | None,
             launch_findings: Iterable[Finding], launch_file: str | None,
             definitions: Definitions | None) -> Analysis:
    """:func:`analyse_entries`; ``matches``: each entry's match, given (else looked up)."""
    if client_library is not None:
        check_client_library(client_library)
    entries = list(entries)
    findings: list[Finding] = (list(launch_findings) + _parameter_file_findings(entries)
                               + _rcl_refusal_findings(entries))
    findings += [Finding(d, DEFINITIONS_KIND) for d in definitions.diagnostics] \
        if definitions else []
    # The index is listed once (not looked up file by file per node), and the collector
    # does not rescan, every 700 allocations, what the analysis keeps until its end.
    with one_run(), batch_collection(), overlay.using(definitions):
        matcher = DefinitionMatcher(client_library, prefixes)
        if matches is None:
            matcher.read_ahead(entries)  # (every definition read before any is composed)
        nodes = [build_node(entry, matches[index] if matches is not None else matcher.match(entry),
                            findings) for index, entry in enumerate(entries)]
        context = AnalysisContext(nodes, settings or AnalysisSettings(), matcher.prefixes)
        findings.extend(run_checks(context, dict(checks) if checks is not None else None))
    findings.sort(key=_sort_key)
    return Analysis(nodes, findings, launch_file, context)


def _parameter_file_findings(records: Iterable[LaunchedNode]) -> list[Finding]:
    """What is wrong with the parameter files the launch gives its nodes (unreadable, not
    YAML, not a parameter file): a node given such a file fails to start, as rcl cannot
    parse it.  Each file is said once, at its own line, related to where it is given."""
    out: list[Finding] = []
    seen: set[tuple[str, str | None]] = set()
    for record in records:
        for source in record.parameters:
            path = source.path
            text = source.text  # the file substituted first (allow_substs)
            if source.kind != 'file' or not path or (path, text) in seen:
                continue
            seen.add((path, text))
            where = source.source
            given = (where.file, where.line, where.column, 'the parameter file is given here')
            loaded = load_parameter_file(path) if text is None else parse_parameter_text(path, text)
            for diagnostic in loaded.diagnostics:
                out.append(_launch_finding(diagnostic.replace(
                    related=(*diagnostic.related, given))))
    return out


def _rcl_refusal_findings(records: Iterable[LaunchedNode]) -> list[Finding]:
    """What rcl alone refuses or ignores in a parameter file given to a node started as a
    process (aliases, anchors, merge keys: ``ParameterFile.rcl_diagnostics``), once per
    file, related to where it is first given to such a node.  launch_ros reads a composable
    node's file with PyYAML, which expands aliases and merge keys: nothing to say there."""
    out: list[Finding] = []
    seen: set[str] = set()
    for record in records:
        if record.kind == 'composable':
            continue
        for source in record.parameters:
            path = source.path
            if source.kind != 'file' or not path or path in seen:
                continue
            seen.add(path)
            where = source.source
            given = (where.file, where.line, where.column,
                     'the parameter file is given here to a node rcl starts')
            for diagnostic in load_parameter_file(path).rcl_diagnostics:
                out.append(_launch_finding(diagnostic.replace(
                    related=(*diagnostic.related, given))))
    return out


def _launch_finding(diagnostic: Diagnostic) -> Finding:
    return Finding(diagnostic, LAUNCH_KIND)


def analyse_launch(launch_file: str | os.PathLike[str], arguments: Mapping[str, str] | None = None,
                   *, client_library: str | None = None, prefixes: list[str] | None = None,
                   settings: AnalysisSettings | None = None,
                   checks: Mapping[str, object] | None = None,
                   limits: LaunchLimits | None = None,
                   definitions: Definitions | None = None) -> Analysis:
    """Analyse the system a launch file (XML, YAML or Python) starts, with launch
    ``arguments`` (``name -> value``, as ``name:=value`` on the command line).

    ``limits``: whether the launch's Python code (Python launch files, ``$(eval)``) runs,
    and for how long and with how much memory (:class:`~nodl.launch.sandbox.LaunchLimits`;
    default: it runs in a forked child, 30 s, 2048 MiB).

    ``prefixes``: the ament prefixes every look-up searches (``$(find-pkg-share)``, the
    nodes' definitions and their ``nodl://`` mixins); default: ``AMENT_PREFIX_PATH``.
    ``definitions``: definitions folders (overlays) the nodes' definitions and ``nodl://``
    mixins are looked up in first (:func:`nodl.targets.resolve.gather_definitions`)."""
    path = os.fspath(launch_file)
    with batch_collection():
        result = load_launch(path, dict(arguments or {}), prefixes=prefixes, limits=limits)
    records, diagnostics, unreadable = _launch_result(result, path)
    analysis = analyse_entries(records, client_library=client_library, prefixes=prefixes,
                               settings=settings, checks=checks,
                               launch_findings=[_launch_finding(d) for d in diagnostics],
                               launch_file=path, definitions=definitions)
    analysis.unreadable = unreadable
    analysis.launch_files = list(result.files) + [
        source.path for record in records for source in record.parameters
        if source.kind == 'file' and source.path]
    return analysis


def analyse_definitions(targets: Sequence[Definition], names: Sequence[str] = (), *,
                        remaps: Sequence[str] = (), client_library: str | None = None,
                        prefixes: list[str] | None = None,
                        settings: AnalysisSettings | None = None,
                        checks: Mapping[str, object] | None = None,
                        definitions: Definitions | None = None) -> Analysis:
    """Analyse an explicit set of node definitions, without a launch file: each ``FILE`` or
    ``PACKAGE EXECUTABLE`` (:class:`~nodl.targets.placement.Definition`) placed as
    ``nodl policy`` places them (the i-th of ``names``, ``/NS/NODE``, names the i-th; by
    default the file's stem or the executable, at ``/``; ``remaps``: rules every node is
    given, ``node:from:=to`` for one node only), then checked as a launched system is.

    A definition that does not resolve is a finding (and no node).  ValueError for more
    names than definitions or a malformed name; OSError for a file that cannot be read.
    """
    parse_remap_rules(list(remaps))  # ValueError for a rule rcl would refuse
    placed, problems = place_definitions(targets, names, remaps=remaps,
                                         client_library=client_library, prefixes=prefixes,
                                         folders=definitions)
    entries: list[LaunchedNode] = []
    matches: list[Match] = []
    # a --remap rule is given to every node at once: judged once, where it is written
    given = Location('<command line>', 0, 0)
    for item in placed:
        definition, instance = item.definition, item.instance
        where = Location(item.file, 1, 1)
        package = definition.package or ''
        key = definition.executable or os.path.basename(item.file)
        pairs = [rule.rsplit(':=', 1) for rule in remaps]
        entries.append(LaunchedNode('node', package, key, instance.created_name,
                                    instance.created_namespace, where,
                                    remaps=[LaunchRemap(a, b, given) for a, b in pairs]))
        origin = f'overlay {item.provenance.folder}' if item.provenance.source == 'overlay' \
            else item.provenance.source
        matches.append(Match(package, key, item.file, instance.resolved, instance.created_name,
                             'definition', [], origin))
    analysis = _analyse(entries, matches, client_library=client_library, prefixes=prefixes,
                        settings=settings, checks=checks,
                        launch_findings=[Finding(d, DEFINITIONS_KIND) for d in problems],
                        launch_file=None, definitions=definitions)
    return analysis


#: Codes that mean the launch file itself could not be read or parsed (exit status 2):
#: reading and syntax (NODL0xx), a missing file, a Python file that does not evaluate, is
#: not run (--no-exec) or stops its sandbox (ends, crashes, runs out of time or memory).
_UNREADABLE = ('NODL515', 'NODL516', 'NODL525', 'NODL527', 'NODL528', 'NODL529')


def _launch_result(result: LaunchResult, path: str
                   ) -> tuple[list[LaunchedNode], list[Diagnostic], bool]:
    """``(records of launched nodes, diagnostics, unreadable)`` of the launch reader's result."""
    records = list(result.nodes)
    diagnostics = list(result.diagnostics)
    top = os.path.realpath(path)
    unreadable = any(
        d.severity is Severity.ERROR and (d.code.startswith('NODL0') or d.code in _UNREADABLE)
        and os.path.realpath(d.file) == top for d in diagnostics) and not records
    return records, diagnostics, unreadable
