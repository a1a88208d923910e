"""Checks on node names and remapping rules: ``duplicate-node``, ``unused-remap``."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from nodl.composition.entities import Location
from nodl.naming import NodeNames, RemapRule
from nodl.system.checks import CheckExtension
from nodl.system.context import AnalysisContext
from nodl.system.findings import Finding, make_finding
from nodl.system.launched import SystemNode

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
    tell them apart, and their parameters and services collide).  When one of the names is
    assumed (:attr:`SystemNode.name_assumed`) it is a warning that says so
    (``assumed-duplicate-node``), not an error."""

    kinds = ('duplicate-node', 'assumed-duplicate-node')

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per node launched under a name an earlier node already has."""
        # context.by_fqn's groups, made only for the names launched more than once (few)
        first_of: dict[str, SystemNode] = {}
        groups: dict[str, list[SystemNode]] = {}
        for node in context.nodes:
            first = first_of.setdefault(node.fqn, node)
            if first is not node:
                groups.setdefault(node.fqn, [first]).append(node)
        # in context.by_fqn's order: that of each name's first launch
        for fqn in (name for name in first_of if name in groups) if groups else ():
            group = groups[fqn]
            first = group[0]
            for other in group[1:]:
                if first.name_assumed or other.name_assumed:
                    yield _assumed_duplicate(fqn, first, other)
                    continue
                yield make_finding(
                    'duplicate-node',
                    f'{fqn} is launched twice ({other.executable_label} here, '
                    f'{first.executable_label} at {first.location}); give one a different '
                    'name or namespace',
                    other.location, [n.fqn for n in group],
                    related=[(first.location.file, first.location.line, first.location.column,
                              f'{fqn} is first launched here')])


def _assumed_duplicate(fqn: str, first: SystemNode, other: SystemNode) -> Finding:
    """The warning for two nodes whose shared final name rests on a name the analysis
    assumed (a program launched without a name may name its node itself at run time:
    two ``controller_manager spawner`` processes, for one)."""
    assumed = [n for n in (other, first) if n.name_assumed]
    which = ' and '.join(dict.fromkeys(f'{n.executable_label}' for n in assumed))
    return make_finding(
        'assumed-duplicate-node',
        f'{fqn} may be launched twice ({other.executable_label} here, {first.executable_label} '
        f'at {first.location}): {which} is launched without name= and no NODE_NAME is recorded '
        f'for it, so the analysis assumed the name {fqn.rpartition("/")[2]!r}; if the program '
        'names its node itself at run time this is no problem (--ignore NODL530), else give one '
        'a name= (or record NODE_NAME in its registration)', other.location, [fqn],
        related=[(first.location.file, first.location.line, first.location.column,
                  f'{fqn} is first launched here')])


class UnusedRemapCheck(CheckExtension):
    """A remapping rule that matches none of the topics, services or actions of the nodes it
    is given to (usually a typo, or a name no node uses).

    A rule is judged where it is written: a rule given to many nodes at once (``set_remap``,
    in a group or at the top; a node entry included or looped more than once) is one finding
    at the rule, and only when no node in its scope uses it.  A node in its scope without a
    definition may use it (its endpoints are unknown): the rule is then not reported."""

    kinds = ('unused-remap',)

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per rule (by where it is written and what it says) that no node given
        it uses.  A node-scoped rule (``other:chatter:=x``) is for the node of that name only
        (rcl applies it to that node alone): the other nodes given it are not its users."""
        # (where, rule text) -> the nodes given it, each with the rule as parsed for it
        scopes: dict[tuple[Location, str], list[tuple[SystemNode, RemapRule]]] = {}
        used: set[tuple[Location, str]] = set()
        for node in context.nodes:
            names = node.names
            if names is None or not names.rules:
                continue  # nothing to be unused (or a node the analysis cannot name)
            own: set[int] = set()
            if node.instance is not None:
                for bound in node.instance.endpoints:
                    rule = names.rule_for(bound.entity.name,
                                          service=bound.entity.kind.communication == 'service')
                    if rule is not None:
                        own.add(id(rule))
            for rule in names.rules:
                if rule.kind in ('node', 'namespace'):
                    continue
                key = (node.rule_location(rule), str(rule))
                scopes.setdefault(key, []).append((node, rule))
                if id(rule) in own or (node.instance is None and _may_use(node, names, rule)):
                    used.add(key)  # used, or given to a node whose endpoints are unknown
        if len(used) == len(scopes):
            return
        launched: dict[str, SystemNode] | None = None  # base name -> a node (made if needed)
        for key, given in scopes.items():
            if key in used:
                continue
            if launched is None:
                launched = {}
                for other in context.nodes:
                    launched.setdefault(other.fqn.rpartition('/')[2], other)
            yield _unused(key[0], given, launched, context)


#: What a container of composable nodes without a definition has besides its private
#: names (rclcpp_components' ``~/_container/...`` services, the parameter services): rcl's
#: log and parameter-event topics.
_CONTAINER_GLOBALS = ('/rosout', '/parameter_events')


def _may_use(node: SystemNode, names: Any, rule: RemapRule) -> bool:
    """True when ``node``, whose definition is unknown, may use ``rule``: any rule for it,
    except that a container's own interface is rclcpp_components' (its private services
    and rcl's topics), so a container uses only a rule for one of those."""
    if not rule.applies_to(names.name):
        return False
    if node.entry.role != 'container':
        return True
    try:
        expanded = names.expand(rule.match or '')
    except ValueError:
        return True
    return expanded.startswith(names.fqn.rstrip('/') + '/') or expanded in _CONTAINER_GLOBALS


def _listed(names: list[str], most: int = 3) -> str:
    """``a, b, c and 13 more``: a few names of a long list."""
    if len(names) <= most:
        return ', '.join(names)
    return f'{", ".join(names[:most])} and {len(names) - most} more'


def _left_out(given: list[tuple[SystemNode, RemapRule]], context: AnalysisContext) -> list[str]:
    """The composable nodes that would use a rule given on their container's command line
    but do not get it: rclcpp_components loads a node without its process's global
    arguments unless ``forward_global_arguments`` is true (these have not)."""
    hosts = {n.fqn for n, _ in given if n.entry.role == 'container'}
    if not hosts:
        return []
    have = {id(n) for n, _ in given}
    rule = given[0][1]
    out = []
    for other in context.nodes:
        if other.entry.container not in hosts or id(other) in have or other.instance is None \
                or other.names is None or not rule.applies_to(other.names.name):
            continue
        try:
            alone = NodeNames.create(other.names.name, other.names.namespace, [str(rule)])
            if any(alone.rule_for(b.entity.name, service=b.entity.kind.communication == 'service')
                   for b in other.instance.endpoints):
                out.append(other.fqn)
        except ValueError:
            continue
    return out


def _unused(where: Location, given: list[tuple[SystemNode, RemapRule]],
            launched: dict[str, SystemNode], context: AnalysisContext) -> Finding:
    """The finding for a rule written at ``where`` that none of the nodes ``given`` it uses."""
    node, rule = given[0]
    text = str(rule)
    fqns = list(dict.fromkeys(n.fqn for n, _ in given))
    applying = [(n, r) for n, r in given if n.names is not None and r.applies_to(n.names.name)]
    verdict = 'is never used'
    endpoint: str | None = None
    if not applying:
        other = launched.get(rule.node or '')
        if other is None:
            elsewhere = 'no launched node has that name'
        else:
            elsewhere = (f'{other.fqn}, launched at {other.location}, is outside its scope '
                         '(move the rule to where that node is launched)')
        if len(fqns) == 1:
            assert node.names is not None
            why = (f'it is for the node {rule.node!r}, and {elsewhere} '
                   f'(this node is {node.names.name!r})')
        else:
            why = (f'it is for the node {rule.node!r}, and none of the {len(fqns)} nodes it is '
                   f'given to ({_listed(fqns)}) has that name; {elsewhere}')
    else:
        what = _WHAT.get(rule.kind, 'topic, service or action')
        expanded = list(dict.fromkeys(
            n.names.expand(r.match or '') for n, r in applying if n.names is not None))
        endpoint = expanded[0] if len(expanded) == 1 else None
        shown = ' or '.join(repr(e) for e in expanded[:3]) + (
            f' (or {len(expanded) - 3} more)' if len(expanded) > 3 else '')
        users = list(dict.fromkeys(n.fqn for n, _ in applying))
        if len(fqns) == 1:
            why = f'the node has no {what} {shown}'
        elif len(users) == 1:
            why = f'it applies only to {users[0]}, which has no {what} {shown}'
        else:
            why = (f'none of the {len(users)} nodes it applies to ({_listed(users)}) has a '
                   f'{what} {shown}')
        for n, r in applying:
            full = n.names.expand(r.match or '') if n.names is not None else ''
            part = _action_part(n, full, r.kind)
            if part is not None:
                verdict = 'renames no action'
                why = (f'it renames only the internal {part[1]} {full!r} '
                       f'of the action {part[0]!r}, which splits the action (rcl remaps an action '
                       f'as a whole by its name: remap {part[0]!r})')
                break
    left_out = _left_out(given, context) if verdict == 'is never used' else []
    if left_out:
        why += (f'; {_listed(left_out)}, loaded into the container, would use it, but rules on a '
                "container's command line do not reach the composable nodes loaded into it "
                '(rclcpp_components loads them without the global arguments): give the rule to '
                'the composable node (its remappings), or load it with the extra argument '
                'forward_global_arguments: true')
    if len(fqns) == 1:
        message = (f'{node.fqn}: the remapping rule {text!r} {verdict}: {why}'
                   f' (see nodl show {node.executable_label})')
    else:
        message = (f'the remapping rule {text!r}, given to {len(fqns)} nodes, {verdict}: {why}; '
                   'remove it, or correct its name')
    related = []
    for n in dict.fromkeys(n for n, _ in given):
        if n.location != where:
            related.append((n.location.file, n.location.line, n.location.column,
                            f'{n.fqn} is launched here'))
    return make_finding('unused-remap', message, where, fqns, endpoint=endpoint, related=related)
