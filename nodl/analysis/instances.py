"""Launched nodes as node instances: final name, namespace, remaps and parameters.

:func:`analyse_entries` (in :mod:`nodl.analysis.system`) builds one
:class:`AnalysedNode` per launch entry: the definition it matched, the name it
runs under (``name=``, else the name its registration records, else its
executable's name, with a warning), its remapping rules parsed as rcl parses
them, the parameter values it receives (files matched against its final name,
a later value winning) and, when it has a definition, its
:class:`~nodl.system.NodeInstance` with every endpoint's final name.
"""

from __future__ import annotations

from typing import Any

from nodl.analysis.entries import LaunchEntry, ParameterFile, ParameterSetting
from nodl.analysis.findings import Finding, make_finding
from nodl.analysis.matching import Match
from nodl.naming import InvalidNameError, NodeNames, RemapRule, join_name, parse_remap_rule
from nodl.system.entities import Location
from nodl.system.instance import NodeInstance

__all__ = ['AnalysedNode', 'build_node']


class AnalysedNode:
    """One launched node after matching and naming (see the module docstring)."""

    # Every launched node lives until the analysis ends: slots spare each one a __dict__
    # (an object more for the garbage collector to walk).
    __slots__ = ('entry', 'match', 'created_name', 'names', 'rules', 'rule_locations', 'settings',
                 'instance', 'name_assumed')

    def __init__(self, entry: LaunchEntry, match: Match, name: str, names: NodeNames | None,
                 rules: list[RemapRule], settings: list[ParameterSetting],
                 instance: NodeInstance | None) -> None:
        #: The launch entry.
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
        return join_name(self.entry.namespace, self.created_name)

    @property
    def location(self) -> Location:
        """Where the node is launched."""
        return self.entry.location

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
        return f'{self.entry.package} {self.entry.executable or self.entry.plugin or "?"}'

    def __repr__(self) -> str:
        return f'AnalysedNode({self.fqn!r}, {self.executable_label!r})'


def _label(entry: LaunchEntry) -> str:
    """How findings name what an entry runs: ``package executable`` (or plugin)."""
    return f'{entry.package} {entry.executable or entry.plugin}'


def build_node(entry: LaunchEntry, match: Match, findings: list[Finding]) -> AnalysedNode:
    """The analysed node of one entry; problems are appended to ``findings``."""
    where = entry.location
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
    for index, (source, target) in enumerate(entry.remaps):
        try:
            rules.append(parse_remap_rule(f'{source}:={target}'))
            rule_locations.append(entry.remap_location(index))
        except ValueError as exc:
            findings.append(make_finding('not-analysable', f'{_label(entry)}: {exc}',
                                         entry.remap_location(index), ()))
    names: NodeNames | None
    try:
        names = NodeNames.create(name, entry.namespace or '/', rules)
    except InvalidNameError as exc:
        names = None
        findings.append(make_finding('not-analysable', f'{_label(entry)}: {exc}', where, ()))
    fqn = names.fqn if names is not None else join_name(entry.namespace, name)
    settings: list[ParameterSetting] = []
    for item in entry.parameters:
        if isinstance(item, ParameterFile):
            settings.extend(item.settings(fqn))
        else:
            settings.append(item)
    node = AnalysedNode(entry, match, name, names, rules, settings, None)
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
        # the final values, a later setting winning (as AnalysedNode.parameter_values)
        values = {setting.name: setting.value for setting in settings}
        node.instance = NodeInstance(match.resolved, name, entry.namespace or '/', rules,
                                     values, where, names=names)
    except ValueError as exc:
        findings.append(make_finding('not-analysable', f'{fqn}: {exc}', where, (fqn,)))
    return node
