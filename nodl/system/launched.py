"""One launched node of a system: its launch record, its definition, its names, its instance.

The launch reader (:mod:`nodl.launch`) records each node a launch starts as a
:class:`~nodl.launch.model.LaunchedNode`, with where it is written.  That record is the
launched node's one description all the way to its instance: :func:`build_node` adds, in a
:class:`SystemNode`, the definition it matched, the name it runs under (``name=``, else
the name its registration records, else its executable's name, with a warning), its
remapping rules parsed as rcl parses them, the parameter values it receives (its parameter
sources resolved against its final name, a later value winning) and, when it has a
definition, its :class:`~nodl.composition.instance.NodeInstance` with every endpoint's final
name.  Every location is the record's own (:class:`~nodl.location.Location`): nothing is
copied or rebuilt on the way.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from nodl.composition.instance import NodeInstance
from nodl.launch.model import LaunchedNode, remap_source
from nodl.launch.parameter_values import parameter_overrides
from nodl.launch.params import RuntimeValue
from nodl.location import Location
from nodl.naming import (
    InvalidNameError,
    NodeNames,
    RemapRule,
    join_name,
    parse_remap_rule,
)
from nodl.system.findings import Finding, make_finding
from nodl.system.matching import Match
from nodl.targets.resolve import Provenance

__all__ = ['ParameterSetting', 'SystemNode', 'build_node', 'node_provenance']


@dataclass(frozen=True, slots=True)  # (no __dict__: one object less per setting)
class ParameterSetting:
    """One parameter value given to a node, where it is written, and how."""

    #: The parameter's name (dotted for nested values).
    name: str
    #: The value, typed as launch types it.
    value: Any
    #: Where it is written (a launch entry, or the line of a parameter file).
    location: Location
    #: ``inline`` (``param``, ``parameters=``), ``file`` (a parameter file), ``global``
    #: (``set_parameter``), ``argument`` (``--ros-args -p``).
    origin: str = 'inline'


#: The launch reader's parameter origins -> the words of :attr:`ParameterSetting.origin`.
_ORIGINS = {'arguments': 'argument', 'global': 'global', 'node': 'inline'}


class SystemNode:
    """One launched node of a system (see the module docstring)."""

    # Every launched node lives until the analysis ends: slots spare each one a __dict__
    # (an object more for the garbage collector to walk).
    __slots__ = (
        'created_name',
        'entry',
        'instance',
        'match',
        'name_assumed',
        'names',
        'rule_locations',
        'rules',
        'settings',
    )

    def __init__(self, entry: LaunchedNode, match: Match, name: str, names: NodeNames | None,
                 rules: list[RemapRule], settings: list[ParameterSetting],
                 instance: NodeInstance | None) -> None:
        #: The launch record: what the launch file says of the node, and where.
        self.entry = entry
        #: Its definition (``match.resolved`` is None without one).
        self.match = match
        #: The name it is created with (before ``__node`` rules).
        self.created_name = name
        #: Its final name and namespace (None if rcl would refuse them).
        self.names = names
        #: Its remapping rules, parsed, in rcl's order (malformed ones left out).
        self.rules = rules
        #: Where each of :attr:`rules` is written (set by :func:`build_node`).
        self.rule_locations: list[Location] = []
        #: Every parameter setting it receives, in the order they are applied.
        self.settings = settings
        #: Its instance (None without a usable definition).
        self.instance = instance
        #: True when its name is the analysis's guess: launched without ``name=``, its
        #: registration records no ``NODE_NAME`` and no ``__node`` rule renames it, so
        #: the executable's name is assumed (the program may name itself otherwise).
        self.name_assumed = False

    @property
    def fqn(self) -> str:
        """The final fully qualified name (as created, if the name is invalid)."""
        if self.names is not None:
            return self.names.fqn
        return join_name(self.entry.namespace or '/', self.created_name)

    @property
    def location(self) -> Location:
        """Where the node is launched (the launch record's place)."""
        return self.entry.source

    @property
    def package(self) -> str:
        """The package it runs (empty when the launch entry gives none)."""
        return self.entry.package or ''

    def rule_location(self, rule: RemapRule) -> Location:
        """Where ``rule`` (one of :attr:`rules` or of its names' rules) is written: the
        ``remap`` entry, ``set_remap``, the ``args`` with ``-r``; else the node's entry."""
        index = next((i for i, own in enumerate(self.rules) if own is rule),
                     next((i for i, own in enumerate(self.rules) if own == rule), -1))
        return self.rule_locations[index] if 0 <= index < len(self.rule_locations) else self.location

    @property
    def parameters(self) -> dict[str, ParameterSetting]:
        """The final setting of each parameter it receives (a later setting wins)."""
        out: dict[str, ParameterSetting] = {}
        for setting in self.settings:
            out[setting.name] = setting
        return out

    def parameter_values(self) -> dict[str, Any]:
        """The final values it receives, by name."""
        return {name: s.value for name, s in self.parameters.items()}

    @property
    def executable_label(self) -> str:
        """``package executable`` or ``package plugin``: how the launch names what it runs."""
        return f'{self.package} {self.entry.executable or self.entry.plugin or "?"}'

    def provenance(self) -> Provenance:
        """Where its definition came from (``none`` without one)."""
        return self.match.provenance()

    def to_dict(self) -> dict[str, Any]:
        """The node as JSON: final name, what it runs, its definition and where that came
        from, where it is launched, its remapping rules and the parameter values it receives
        (with what only the running launch knows), and its endpoints' final names
        (the ``nodes`` of ``nodl analyse --format json``, :mod:`nodl.analysis.report`)."""
        endpoints: dict[str, list[list[str]]] = {}
        if self.instance is not None:
            for bound in self.instance.endpoints:
                endpoints.setdefault(bound.entity.section, []).append(
                    [bound.entity.name, bound.name])
        entry = self.entry
        parameters: dict[str, Any] = {}
        unknown: list[dict[str, Any]] = [
            {'part': part, 'file': where.file, 'line': where.line, 'column': where.column}
            for part, where in entry.run_time]
        for name, setting in self.parameters.items():
            if isinstance(setting.value, RuntimeValue):  # no value, and no text standing for one
                parameters[name] = None
                where = setting.location
                unknown.append({'part': 'parameter', 'parameter': name, 'file': where.file,
                                'line': where.line, 'column': where.column})
            else:
                parameters[name] = setting.value
        complete = not entry.run_time or entry.parameters_complete
        provenance = self.provenance()
        return {
            'name': self.fqn,
            'package': self.package,
            'executable': entry.executable if entry.executable is not None else entry.plugin,
            'definition': self.match.file,
            'definition_source': provenance.source if provenance.source != 'none' else None,
            'definition_folder': provenance.folder,
            'definition_provenance': provenance.made_by,
            'source': {'file': entry.source.file, 'line': entry.source.line},
            'remaps': [[source, target] for source, target in entry.remaps],
            'remaps_complete': not entry.run_time or entry.remaps_complete,
            'parameters': parameters,
            'parameters_complete': complete and len(unknown) == len(entry.run_time),
            'run_time': unknown,
            'endpoints': endpoints,
        }

    def __repr__(self) -> str:
        return f'SystemNode({self.fqn!r}, {self.executable_label!r})'


def node_provenance(node: SystemNode) -> Provenance:
    """Where the definition of ``node`` came from (``none`` without one)."""
    return node.provenance()


def _label(entry: LaunchedNode) -> str:
    """How findings name what an entry runs: ``package executable`` (or plugin)."""
    return f'{entry.package or ""} {entry.executable or entry.plugin}'


def _settings(entry: LaunchedNode, fqn: str) -> list[ParameterSetting]:
    """The values a launched node receives, given its final name: which parameter-file keys
    apply and which value wins as rcl (processes) or launch_ros (composable nodes) decide it
    (:func:`nodl.launch.parameter_values.parameter_overrides`), at the place each is written."""
    return [ParameterSetting(o.name, o.value, Location(o.file, o.line, o.column),
                             'file' if o.kind == 'file' else _ORIGINS.get(o.origin, 'inline'))
            for o in parameter_overrides(entry, fqn).values()]


def build_node(entry: LaunchedNode, match: Match, findings: list[Finding]) -> SystemNode:
    """The system node of one launch record; problems are appended to ``findings``."""
    where = entry.source
    namespace = entry.namespace or '/'
    name = entry.name or match.node_name
    if not name:
        name = entry.executable or match.key
        if match.resolved is not None:
            findings.append(make_finding(
                'unnamed-node',
                f"{_label(entry)} is launched without a name and its registration records none: "
                f"assuming the node is called '{name}' (set name= in the launch file, or record "
                f'it: ament_nodl_register_node({match.key} FILE ... NODE_NAME <name>))', where,
                ()))
    rules: list[RemapRule] = []
    rule_locations: list[Location] = []
    for pair in entry.remaps:
        source, target = pair
        place = remap_source(pair, where)
        try:
            rules.append(parse_remap_rule(f'{source}:={target}'))
            rule_locations.append(place)
        except ValueError as exc:
            findings.append(make_finding('not-analysable', f'{_label(entry)}: {exc}', place, ()))
    names: NodeNames | None
    try:
        names = NodeNames.create(name, namespace, rules)
    except InvalidNameError as exc:
        names = None
        findings.append(make_finding('not-analysable', f'{_label(entry)}: {exc}', where, ()))
    fqn = names.fqn if names is not None else join_name(namespace, name)
    # all sources at once: rcl merges them into one table
    settings = _settings(entry, fqn) if entry.parameters else []
    node = SystemNode(entry, match, name, names, rules, settings, None)
    node.rule_locations = rule_locations
    if not entry.name and not match.node_name:
        node.name_assumed = names is None or names.name == name and not any(
            rule.kind == 'node' and rule.applies_to(name) for rule in names.rules)
    if match.resolved is None or names is None:
        if match.file is not None and match.resolved is None:
            first = match.problems[0] if match.problems else None
            why = f': {first}' if first is not None else ''
            findings.append(make_finding(
                'not-analysable', f'{_label(entry)}: its definition {match.file} does not '
                f'resolve{why}', where, (fqn,)))
        return node
    try:
        # the final values, a later setting winning (as SystemNode.parameter_values)
        values = {setting.name: setting.value for setting in settings}
        node.instance = NodeInstance(match.resolved, name, namespace, rules, values, where,
                                     names=names)
    except ValueError as exc:
        findings.append(make_finding('not-analysable', f'{fqn}: {exc}', where, (fqn,)))
    return node
