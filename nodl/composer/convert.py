"""The same composition in another launch format (its declarative part).

Nodes, containers, names, namespaces (the groups pushing literal namespaces), parameter
values and remapping rules are written anew in the other format; pieces kept verbatim
(and read-only nodes, whose conditions or substitutions they are) belong to the source
format's language and are left out: :func:`left_out` lists them (with their lines in the
source), and the converted file says so in a comment at its top.  A group's condition, and
a namespace only the running launch knows, are not carried over either: their nodes are
written unconditionally and without that namespace, and the comment says so too.
"""

from __future__ import annotations

import copy
import re

from nodl.composer.formats import new_document, new_group
from nodl.composer.model import ComposedNode, Document, Group, Item, Kept

__all__ = ['convert_document', 'left_out']

_PUSH = re.compile(r'push[-_]?ros[-_]?namespace', re.IGNORECASE)


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
    out.children = [_fresh(child) for child in node.children if child.editable]  # as left_out says
    return out


def left_out(doc: Document) -> list[str]:
    """What a conversion of ``doc`` leaves out, one line each (``line 4: <arg>``)."""
    out: list[str] = []

    def node_pieces(node: ComposedNode) -> None:
        if not node.editable:
            out.append(f'line {node.line}: {node.label} (read-only: {node.read_only_reason})')
            return
        for name, value in node.style.get('attrs', []):
            out.append(f'line {node.line}: {name}={value!r} of {node.label}')
        for piece in (*node.params, *node.remaps, *node.extra):
            if isinstance(piece, Kept):
                out.append(f'line {piece.line or node.line}: {piece.what} of {node.label}')
        for child in node.children:
            node_pieces(child)

    def visit(items: list[Item]) -> None:
        for item in items:
            if isinstance(item, Kept):
                out.append(f'line {item.line}: {item.what}')
            elif isinstance(item, ComposedNode):
                node_pieces(item)
            elif isinstance(item, Group):
                if item.conditional:
                    out.append(f'line {item.line}: the condition of a group (its nodes are '
                               'written unconditionally)')
                if item.namespace_unknown:
                    out.append(f'line {item.line}: a namespace only the running launch knows '
                               '(its nodes are written without it)')
                visit([i for i in item.items if not (isinstance(i, Kept) and _PUSH.search(i.text))])
    visit(doc.items)
    return out


def _comment(kind: str, lines: list[str]) -> str:
    """``lines`` as a comment of ``kind``'s language (one line each, nothing that ends it)."""
    said = ['Converted by nodl system from another launch format; left out (the source '
            "format's, not converted):"]
    said += ['  ' + ' '.join(line.split()) for line in lines]
    if kind == 'xml':
        return '\n  <!--\n' + ''.join(f'    {line.replace("--", "- -")}\n' for line in said) + \
            '  -->'
    return ''.join(f'# {line}\n' for line in said)


def convert_document(doc: Document, kind: str) -> Document:
    """A new document of ``kind`` holding ``doc``'s nodes and namespace groups; what it leaves
    out (:func:`left_out`) is listed in a comment at its top."""
    out = new_document(kind)
    missing = left_out(doc)
    if missing:
        comment = _comment(kind, missing)
        out.header = out.header + comment if kind == 'xml' else comment + out.header
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
