"""Checks on node names and remapping rules: ``duplicate-node``, ``unused-remap``."""

from __future__ import annotations

from typing import Any, Iterator

from nodl_schema.analysis.checks import CheckExtension
from nodl_schema.analysis.context import AnalysisContext
from nodl_schema.analysis.findings import Finding, make_finding
from nodl_schema.analysis.instances import AnalysedNode

__all__ = ['DuplicateNodeCheck', 'UnusedRemapCheck']

#: What a rule of each kind can remap (rostopic:// and rosservice:// rules are limited).
_WHAT = {'topic': 'topic or action', 'service': 'service'}
#: The names rcl gives an action's parts under ``<action>/_action/`` (rcl_action's names.c):
#: part -> its communication.  rcl remaps an action as a whole by its name (a topic rule,
#: before the parts are named); a rule for a part renames only that part.
_ACTION_PARTS = {'send_goal': 'service', 'cancel_goal': 'service', 'get_result': 'service',
                 'feedback': 'topic', 'status': 'topic'}


def _action_part(node: Any, match: str, kind: str) -> tuple[str, str] | None:
    """``(action, part's communication)`` when a rule of ``kind`` matching the expanded name
    ``match`` would rename one internal part of one of the node's actions."""
    action, sep, part = match.rpartition('/_action/')
    communication = _ACTION_PARTS.get(part) if sep else None
    if communication is None or kind not in ('name', communication):
        return None
    for bound in node.instance.endpoints:
        if bound.entity.kind.communication == 'action' and bound.name == action:
            return action, communication
    return None


class DuplicateNodeCheck(CheckExtension):
    """Two launched nodes with the same final name (rcl lets them start; the graph cannot
    tell them apart, and their parameters and services collide)."""

    kinds = ('duplicate-node',)

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per node launched under a name an earlier node already has."""
        # context.by_fqn's groups, made only for the names launched more than once (few)
        first_of: dict[str, AnalysedNode] = {}
        groups: dict[str, list[AnalysedNode]] = {}
        for node in context.nodes:
            first = first_of.setdefault(node.fqn, node)
            if first is not node:
                groups.setdefault(node.fqn, [first]).append(node)
        # in context.by_fqn's order: that of each name's first launch
        for fqn in (name for name in first_of if name in groups) if groups else ():
            group = groups[fqn]
            first = group[0]
            for other in group[1:]:
                yield make_finding(
                    'duplicate-node',
                    f'{fqn} is launched twice ({other.executable_label} here, '
                    f'{first.executable_label} at {first.location}); give one a different '
                    'name or namespace',
                    other.location, [n.fqn for n in group],
                    related=[(first.location.file, first.location.line, first.location.column,
                              f'{fqn} is first launched here')])


class UnusedRemapCheck(CheckExtension):
    """A remapping rule given to a node that matches none of the node's topics, services
    or actions (usually a typo, or a name the node does not use)."""

    kinds = ('unused-remap',)

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per unused rule of every node with a definition.

        A node-scoped rule (``other:chatter:=x``) for another node is not this node's to use
        (``set_remap`` gives it to every node in scope; rcl applies it to the node of that
        name only): it is a finding only when no launched node has that name (a typo)."""
        # the base names of every launched node, made if a rule for another node is found
        launched_names: set[str] | None = None
        for node in context.analysed():
            names = node.names
            assert node.instance is not None and names is not None
            if not names.rules:
                continue  # nothing to be unused (and nothing to expand every name for)
            used: set[int] = set()
            for bound in node.instance.endpoints:
                rule = names.rule_for(bound.entity.name,
                                      service=bound.entity.kind.communication == 'service')
                if rule is not None:
                    used.add(id(rule))
            for rule in names.rules:
                if rule.kind in ('node', 'namespace') or id(rule) in used:
                    continue
                verdict = 'is never used'
                if not rule.applies_to(names.name):
                    if launched_names is None:
                        launched_names = {n.fqn.rpartition('/')[2] for n in context.nodes}
                    if rule.node in launched_names:
                        continue  # the rule of the node of that name (checked there)
                    why = (f'it is for the node {rule.node!r}, and no launched node has that name '
                           f'(this node is {names.name!r})')
                else:
                    what = _WHAT.get(rule.kind, 'topic, service or action')
                    expanded = names.expand(rule.match or '')
                    why = f'the node has no {what} {expanded!r}'
                    part = _action_part(node, expanded, rule.kind)
                    if part is not None:
                        verdict = 'renames no action'
                        why = (f'it renames only the internal {part[1]} {expanded!r} of the action '
                               f'{part[0]!r}, which splits the action (rcl remaps an action as a '
                               f'whole by its name: remap {part[0]!r})')
                where = node.rule_location(rule)
                related = [] if where == node.location else [
                    (node.location.file, node.location.line, node.location.column,
                     f'{node.fqn} is launched here')]
                yield make_finding(
                    'unused-remap', f'{node.fqn}: the remapping rule {str(rule)!r} {verdict}: {why}'
                    f' (see nodl show {node.executable_label})',
                    where, [node.fqn], endpoint=names.expand(rule.match or '')
                    if rule.applies_to(names.name) else None, related=related)
