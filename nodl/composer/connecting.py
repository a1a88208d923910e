"""Joining and parting ports: the remapping rule that makes two final names meet.

The rule goes into the using side's own entry (a subscription's, a client's node): its
``from`` is the name the definition declares, its ``to`` the offering side's final name,
written relative to the node's namespace when that resolves the same.  It is put first among
the entry's rules (rcl applies the first rule that matches), replacing a rule of the entry
with the same ``from``.  Rules the entry does not own (``set_remap``, ``SetRemap`` in scope,
``-r`` in its arguments) come first in rcl's order; when one of them still decides the name,
nothing is written and the refusal says which rule would make the names meet.  Whether the
names meet is computed with the node's own rules as rcl would apply them
(:class:`nodl.composition.instance.NodeInstance`), not guessed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nodl.composer.change import Change
from nodl.composer.model import ComposedNode, Kept, Remap
from nodl.composer.ports import Port, find_port, ports_of, verdict
from nodl.composition.instance import NodeInstance
from nodl.diagnostics import Diagnostic, Severity
from nodl.naming import parse_remap_rule, relative_to_namespace

if TYPE_CHECKING:
    from nodl.composer.composition import Composition

__all__ = ['connect', 'disconnect', 'resolve_ports']


def _error(composition: Composition, message: str, code: str) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, file=composition.path, code=code)


def _port(composition: Composition, ref: str) -> tuple[Port | None, Diagnostic | None]:
    node_ref, sep, endpoint = ref.partition(':')
    if not sep or not node_ref or not endpoint:
        return None, _error(composition, f"'{ref}' is not NODE:ENDPOINT (e.g. /rover/lidar:scan)",
                            'NODL971')
    node, problem = composition.find(node_ref)
    if node is None:
        return None, problem
    launched = composition.analyse().node(node.id)
    if launched is None or launched.instance is None:
        why = 'it is not launched (a condition is false)' if launched is None else \
            'it has no definition'
        return None, _error(composition, f'{composition.fqn(node)}: its endpoints are not known: '
                            f'{why}', 'NODL971')
    ports = ports_of(node.id, launched)
    found = find_port(ports, endpoint)
    if len(found) == 1:
        return found[0], None
    if found:
        kinds = ', '.join(f'{p.kind}/{p.name}' for p in found)
        return None, _error(composition, f"{composition.fqn(node)}: '{endpoint}' names several "
                            f'endpoints ({kinds}); write KIND/NAME', 'NODL971')
    names = ', '.join(f'{p.name} ({p.kind.replace("_", " ")})' for p in ports) or 'none'
    return None, _error(composition, f"{composition.fqn(node)} has no endpoint '{endpoint}' "
                        f'(it has: {names})', 'NODL971')


def resolve_ports(composition: Composition, first: str, second: str
                  ) -> tuple[tuple[Port, Port], Diagnostic | None]:
    """The two ports named ``NODE:ENDPOINT``, or the problem with the first that is wrong."""
    a, problem = _port(composition, first)
    if a is None:
        return (None, None), problem  # type: ignore[return-value]
    b, problem = _port(composition, second)
    if b is None:
        return (None, None), problem  # type: ignore[return-value]
    return (a, b), None


def _final_with(composition: Composition, node: ComposedNode, port: Port,
                remaps: list[Remap | Kept]) -> str | None:
    """The port's final name if the node's own rules were ``remaps`` (None: not computable,
    e.g. a kept rule is among them)."""
    launched = composition.analyse().node(node.id)
    if launched is None or launched.match.resolved is None or \
            any(isinstance(r, Kept) for r in (*remaps, *node.remaps)):
        return None
    # rcl's order: the arguments' rules and the scope's, then the entry's own (last)
    outer = list(launched.rules[:max(len(launched.rules) - len(node.remaps), 0)])
    try:
        rules = outer + [parse_remap_rule(f'{r.source}:={r.target}') for r in remaps
                         if isinstance(r, Remap)]
        instance = NodeInstance(launched.match.resolved, launched.created_name,
                                launched.entry.namespace or '/', rules)
        return str(instance.final_name(port.entity.entity))
    except (ValueError, KeyError):
        return None


def _target(composition: Composition, node: ComposedNode, using: Port, final: str) -> str:
    """``final`` written relative to the node's namespace when that resolves the same."""
    launched = composition.analyse().node(node.id)
    namespace = launched.names.namespace if launched is not None and launched.names else '/'
    return relative_to_namespace(final, namespace)


def _rule_for(composition: Composition, node: ComposedNode, port: Port, final: str
              ) -> tuple[list[Remap | Kept], Remap] | None:
    """The node's own rules with one more making ``port`` resolve to ``final``, or None."""
    if any(isinstance(r, Kept) for r in node.remaps) or node.style.get('remaps_computed'):
        return None
    for target in (_target(composition, node, port, final), final):
        rule = Remap(port.name, target)
        rules: list[Remap | Kept] = [rule]
        rules += [r for r in node.remaps if not (
            isinstance(r, Remap) and r.source == port.name)]
        if _final_with(composition, node, port, rules) == final:
            return rules, rule
    return None


def connect(composition: Composition, first: str, second: str) -> Change:
    """:meth:`Composition.connect`."""
    (a, b), problem = resolve_ports(composition, first, second)
    if problem is not None:
        return Change([problem])
    judged = verdict(a, b)
    offering, using = (a, b) if a.offers else (b, a)
    suggestion = f'the rule that would make the names meet: {using.name}:={offering.final_name} ' \
        f'on {composition.fqn(composition.node(using.node))}'  # type: ignore[arg-type]
    if judged.verdict == 'error':
        return Change([_error(composition, f'{offering.final_name} and {using.final_name} are not '
                              f'joined: {judged.reason}' +
                              ('' if judged.connected or judged.code == 'NODL972'
                               else f' ({suggestion})'), judged.code)])
    diagnostics: list[Diagnostic] = []
    if judged.verdict == 'warning':
        diagnostics.append(Diagnostic(Severity.WARNING, f'{offering.final_name}: {judged.reason}',
                                      file=composition.path, code=judged.code))
    if judged.connected:
        diagnostics.append(Diagnostic(Severity.INFO, f'{offering.final_name}: already joined '
                                      '(the final names meet); nothing to change',
                                      file=composition.path, code='NODL986'))
        return Change(diagnostics, using.node)
    for side, other in ((using, offering), (offering, using)):
        node = composition.node(side.node)
        assert node is not None
        if composition._editable(node) is not None:
            continue
        made = _rule_for(composition, node, side, other.final_name)
        if made is None:
            continue
        rules, rule = made
        node.remaps = rules
        composition._changed(node)
        return Change(diagnostics, node.id, remaps=[
            {'node': node.id, 'from': rule.source, 'to': rule.target}])
    return Change([_error(composition, f'{offering.final_name} and {using.final_name} cannot be '
                          'joined here: the rules that decide these names are read-only (kept '
                          f'as written, or rules of the scope that come first); {suggestion}',
                          'NODL976')])


def disconnect(composition: Composition, first: str, second: str) -> Change:
    """:meth:`Composition.disconnect`."""
    (a, b), problem = resolve_ports(composition, first, second)
    if problem is not None:
        return Change([problem])
    if a.final_name != b.final_name:
        return Change([Diagnostic(Severity.INFO, f'{a.final_name} and {b.final_name} are not '
                                  'joined; nothing to change', file=composition.path,
                                  code='NODL986')])
    removed = []
    for side in (a, b):
        node = composition.node(side.node)
        assert node is not None
        if composition._editable(node) is not None:
            continue
        kept = [r for r in node.remaps if not (isinstance(r, Remap) and r.source == side.name)]
        if len(kept) == len(node.remaps):
            continue
        before = _final_with(composition, node, side, kept)
        other = b if side is a else a
        if before is not None and before != other.final_name:
            gone = [r for r in node.remaps if r not in kept]
            node.remaps = kept
            composition._changed(node)
            removed += [{'node': node.id, 'from': r.source, 'to': r.target} for r in gone
                        if isinstance(r, Remap)]
            return Change([], node.id, removed=removed)
    return Change([_error(composition, f'{a.final_name}: the two ends meet without a rule of '
                          "either node's own entry (the names are the same as declared, or a "
                          'read-only rule makes them meet); rename one side with a remapping '
                          'rule instead', 'NODL987')])
