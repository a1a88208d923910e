"""Naming a node and its remapping rules: ``name=``/``namespace=`` of an entry, and the
entry's own ``remap`` rules.

Both operations edit only the node's own entry, and only when it is editable (a read-only
node is refused as :meth:`~nodl.composer.Composition.remove` refuses it, NODL983):

* :func:`rename` checks the name and the namespace as rcl checks them
  (:mod:`nodl.naming`), and refuses a final name another node of the composition has
  (NODL982, as ``add`` does);
* :func:`set_remaps` replaces the entry's editable rules with the rules given, each parsed
  as rcl parses ``-r FROM:=TO`` (NODL988 for one it would refuse); rules kept as written
  (substitutions, rules computed by code) keep their place, and the new rules take the
  place of the first editable one (after the kept ones when there was none).  A rule whose
  ``FROM`` an earlier rule of the entry has already never applies: a warning (NODL989).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from nodl.composer.change import Change
from nodl.composer.model import ComposedNode, Kept, Remap
from nodl.diagnostics import Diagnostic, Severity
from nodl.naming import (
    InvalidRemapRuleError,
    join_name,
    namespace_error,
    node_name_error,
    normalize_namespace,
    parse_remap_rule,
)

if TYPE_CHECKING:
    from nodl.composer.composition import Composition

__all__ = ['RuleText', 'rename', 'rule_pairs', 'set_remaps']

#: A remapping rule as given: ``(FROM, TO)``, or the text ``FROM:=TO``.
RuleText = tuple[str, str] | str


def _error(composition: Composition, node: ComposedNode, message: str, code: str,
           severity: Severity = Severity.ERROR) -> Diagnostic:
    """A diagnostic placed at the node's entry (as read; no place for a node not saved yet)."""
    return Diagnostic(severity, message, file=composition.path, line=node.line,
                      column=len(node.indent) + 1 if node.line else 0, code=code)


def rename(composition: Composition, ref: ComposedNode | str, name: str | None,
           namespace: str | None) -> Change:
    """:meth:`Composition.rename`."""
    node = composition._node_to_edit(ref)
    if isinstance(node, Change):
        return node
    name = name.strip() if name else None
    namespace = namespace.strip() if namespace else None
    problems = []
    if name is not None:
        why = node_name_error(name)
        if why is not None:
            problems.append(_error(composition, node, f"'{name}' is not a node name: {why}",
                                   'NODL982'))
    if namespace is not None:
        why = namespace_error(normalize_namespace(namespace))
        if why is not None:
            problems.append(_error(composition, node, f"'{namespace}' is not a namespace: {why}",
                                   'NODL982'))
    if problems:
        return Change(problems, node.id)
    if (name, namespace) == (node.name, node.namespace):
        return Change([], node.id)
    before = (node.name, node.namespace)
    final_before = composition.fqn(node)
    if '?' in final_before:  # a namespace only the launch knows: the analysis's final name
        composition.analyse()
        final_before = composition.fqn(node)
    node.name, node.namespace = name, namespace
    wanted = _final_name(composition, node, final_before, before)
    taken = next((other for other in composition.nodes
                  if other is not node and composition.fqn(other) == wanted), None)
    if taken is not None:
        node.name, node.namespace = before
        return Change([_error(composition, node, f'{taken.label} is called {wanted} already; '
                              'choose another name or namespace', 'NODL982')], node.id)
    composition._changed(node)
    return Change([], node.id)


def _final_name(composition: Composition, node: ComposedNode, final_before: str,
                before: tuple[str | None, str | None]) -> str:
    """The node's final name with its new ``name``/``namespace`` (already set): as written
    when the text gives it, else from its final name before the change (the groups'
    namespace the analysis found, e.g. a namespace given by a launch argument)."""
    written = composition._written_fqn(node)
    old_name, old_namespace = before
    if '?' not in written or '?' in final_before or (old_namespace or '').startswith('/'):
        return written
    groups, _, name_before = final_before.rpartition('/')
    if old_namespace:  # the entry's own relative namespace came after the groups'
        suffix = join_name('/', old_namespace.strip('/'))
        if not groups.endswith(suffix):
            return written
        groups = groups[:-len(suffix)]
    namespace = join_name(groups or '/', node.namespace) if node.namespace else groups or '/'
    name = node.name or (name_before if old_name is None else written.rsplit('/', 1)[-1])
    return join_name(namespace, name)


def rule_pairs(rules: Sequence[RuleText]) -> tuple[list[tuple[str, str]], list[str]]:
    """The rules as ``(FROM, TO)`` pairs (a text split at its first ``:=``), and why each one
    rcl would refuse is refused (``rule N 'TEXT': why``)."""
    pairs: list[tuple[str, str]] = []
    problems: list[str] = []
    for number, given in enumerate(rules, 1):
        if isinstance(given, str):
            source, sep, target = given.partition(':=')
            if not sep:
                problems.append(f"rule {number} '{given}' is not FROM:=TO")
                continue
        else:
            source, target = given
        text = f'{source}:={target}'
        try:
            parse_remap_rule(text)
        except InvalidRemapRuleError as exc:
            problems.append(f"rule {number} '{text}': {exc.reason}")
            continue
        pairs.append((source, target))
    return pairs, problems


def set_remaps(composition: Composition, ref: ComposedNode | str,
               rules: Sequence[RuleText]) -> Change:
    """:meth:`Composition.set_remaps`."""
    node = composition._node_to_edit(ref)
    if isinstance(node, Change):
        return node
    if node.style.get('remaps_computed'):
        return Change([_error(composition, node, f'{composition.fqn(node)} ({node.label}): its '
                              'remapping rules are computed by code, kept as written; edit the '
                              'launch file itself', 'NODL976')], node.id)
    pairs, problems = rule_pairs(rules)
    if problems:
        return Change([_error(composition, node, f'{composition.fqn(node)}: {why}; a rule is '
                              'FROM:=TO with ROS names (rcl refuses it otherwise)', 'NODL988')
                       for why in problems], node.id)
    diagnostics: list[Diagnostic] = []
    seen: set[str] = set()
    for source, target in pairs:
        if source in seen:
            diagnostics.append(_error(
                composition, node, f'{composition.fqn(node)}: the rule {source}:={target} never '
                f'applies: an earlier rule of the entry remaps {source} (rcl applies the first '
                'rule that matches)', 'NODL989', Severity.WARNING))
        seen.add(source)
    old = [r for r in node.remaps if isinstance(r, Remap)]
    if [(r.source, r.target) for r in old] == pairs:
        return Change(diagnostics, node.id)
    reused: dict[tuple[str, str], Remap] = {(r.source, r.target): r for r in old}
    new: list[Remap | Kept] = []
    for source, target in pairs:  # a rule the entry had keeps its text as written
        same = reused.pop((source, target), None)
        new.append(same if same is not None else Remap(source, target))
    first = next((i for i, r in enumerate(node.remaps) if isinstance(r, Remap)), None)
    kept = [r for r in node.remaps if isinstance(r, Kept)]
    if first is None:
        node.remaps = [*kept, *new]
    else:
        before = [r for r in node.remaps[:first] if isinstance(r, Kept)]
        after = [r for r in node.remaps[first:] if isinstance(r, Kept)]
        node.remaps = [*before, *new, *after]
    composition._changed(node)
    old_pairs = [(r.source, r.target) for r in old]
    return Change(diagnostics, node.id,
                  remaps=[{'node': node.id, 'from': s, 'to': t} for s, t in pairs
                          if (s, t) not in old_pairs],
                  removed=[{'node': node.id, 'from': s, 'to': t} for s, t in old_pairs
                           if (s, t) not in pairs])
