"""The same composition in another launch format (its declarative part).

Nodes, containers, names, namespaces (the groups pushing literal namespaces), parameter
values and remapping rules are written anew in the other format; pieces kept verbatim
(and read-only nodes, whose conditions or substitutions they are) belong to the source
format's language and are left out.
"""

from __future__ import annotations

import copy

from nodl.composer.formats import new_document, new_group
from nodl.composer.model import ComposedNode, Document, Group, Item, Kept

__all__ = ['convert_document']


def _fresh(node: ComposedNode) -> ComposedNode:
    out = copy.copy(node)
    out.original, out.dirty, out.gap = None, True, ''
    out.params = [copy.copy(p) for p in node.params if not isinstance(p, Kept)]
    out.remaps = [copy.copy(r) for r in node.remaps if not isinstance(r, Kept)]
    for value in out.params:
        if not isinstance(value, Kept):
            value.original, value.gap = None, ''
    for rule in out.remaps:
        if not isinstance(rule, Kept):
            rule.original, rule.gap = None, ''
    out.extra = []
    out.style = {}
    out.children = [_fresh(child) for child in node.children]
    return out


def convert_document(doc: Document, kind: str) -> Document:
    """A new document of ``kind`` holding ``doc``'s nodes and namespace groups."""
    out = new_document(kind)
    counter = [0]

    def place(items: list[Item], target: list[Item], indent: str, first_bare: bool) -> None:
        for item in items:
            if isinstance(item, ComposedNode):
                if not item.editable:
                    continue  # its condition or substitutions are the source format's
                node = _fresh(item)
                node.indent = indent
                node.gap = indent if first_bare and not target else '\n' + indent
                target.append(node)
            elif isinstance(item, Group):
                if item.namespace is None:
                    place(item.items, target, indent, first_bare)
                    continue
                counter[0] += 1
                group = new_group(kind, f'g{counter[0]}', item.namespace, indent)
                group.gap = indent if first_bare and not target else '\n' + indent
                target.append(group)
                place(item.items, group.items, str(group.style['inner']), False)
    place(doc.items, out.items, out.indent, False)
    return out
