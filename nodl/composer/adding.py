"""Adding and removing nodes: where a new entry goes, and what its text looks like around it."""

from __future__ import annotations

from typing import TYPE_CHECKING

from nodl.composer.change import Change
from nodl.composer.formats import new_group
from nodl.composer.model import ComposedNode, Document, Group, Item, Kept
from nodl.diagnostics import Diagnostic, Severity
from nodl.naming import join_name, namespace_error, node_name_error, normalize_namespace
from nodl.registry import node_info, overlay

if TYPE_CHECKING:
    from nodl.composer.composition import Composition

__all__ = ['add_node', 'default_plugin', 'remove_node']


def default_plugin(composition: Composition, package: str, executable: str) -> str:
    """The plugin class of a composable node run as ``package executable``: the class its
    registration records, else ``package::PascalCase`` (the class the analysis would look up
    as ``executable``)."""
    if '::' in executable:
        return executable

    with overlay.using(composition.definitions):
        info = node_info.read_node_info(package, executable, composition.prefixes)
    if info is not None and getattr(info, 'plugin', None):
        return str(info.plugin)
    return f'{package}::' + ''.join(part.capitalize() for part in executable.split('_'))


def _problem(composition: Composition, message: str, code: str = 'NODL982') -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, file=composition.path, code=code)


def _place(items: list[Item], item: Item, indent: str, opening: str, kind: str) -> None:
    """Append ``item`` to ``items`` with the gap its neighbours have."""
    if kind == 'yaml' and not items and opening.endswith('\n'):
        item.gap = indent
    else:
        item.gap = '\n' + indent
    item.indent = indent  # type: ignore[union-attr]
    items.append(item)


def _inner_indent(doc: Document, group: Group) -> str:
    if 'inner' in group.style:
        return str(group.style['inner'])
    first = next((i for i in group.items), None)
    if isinstance(first, (ComposedNode, Group)):
        return first.indent
    if isinstance(first, Kept):
        return ' ' * first.column
    return group.indent + ('  ' if doc.format == 'xml' else '    ')


def add_node(composition: Composition, package: str, executable: str, name: str,
             namespace: str | None, container: str | None, plugin: str | None,
             group_id: str | None) -> Change:
    """:meth:`Composition.add`."""
    doc = composition.document
    if doc.style.get('opaque'):
        return Change([composition._editable(ComposedNode('', 'node', '', None))])  # type: ignore[list-item]
    for label, value in (('package', package), ('executable', executable)):
        if not value or any(c.isspace() for c in value):
            return Change([_problem(composition, f"the {label} '{value}' is not a name")])
    why = node_name_error(name)
    if why is not None:
        return Change([_problem(composition, f"'{name}' is not a node name: {why}")])
    if namespace is not None:
        why = namespace_error(normalize_namespace(namespace))
        if why is not None:
            return Change([_problem(composition, f"'{namespace}' is not a namespace: {why}")])

    wanted = join_name(namespace or '/', name)
    if any(composition.fqn(n) == wanted for n in composition.nodes):
        return Change([_problem(composition, f'a node called {wanted} is in the composition '
                                'already; give another --name')])
    target_group: Group | None = None
    if group_id is not None:
        target_group = next((g for g, _ in doc.walk() if isinstance(g, Group) and g.id == group_id),
                            None)
        if target_group is None:
            return Change([_problem(composition, f"no group '{group_id}' in the composition",
                                    'NODL970')])
    diagnostics: list[Diagnostic] = []
    if container is not None:
        plugin = plugin or default_plugin(composition, package, executable)
        node = ComposedNode(composition._next_id('n'), 'composable', package, None,
                            plugin=plugin, name=name, dirty=True)
        host = next((n for n in composition.nodes if n.kind == 'container' and
                     (n.name == container or composition.fqn(n) == container)), None)
        if host is not None:
            problem = composition._editable(host)
            if problem is not None:
                return Change([problem])
            if namespace is not None:
                node.namespace = namespace
            node.indent = host.indent + '  '
            host.children.append(node)
            host.dirty = True
            _check_definition(composition, node, diagnostics)
            return Change(diagnostics, node.id)
        host = ComposedNode(composition._next_id('n'), 'container', 'rclcpp_components',
                            'component_container', name=container, dirty=True)
        host.children.append(node)
        placed: ComposedNode = host
    else:
        node = ComposedNode(composition._next_id('n'), 'node', package, executable, name=name,
                            dirty=True)
        placed = node
    items, indent, opening = doc.items, doc.indent, doc.header
    if target_group is not None:
        items, indent, opening = target_group.items, _inner_indent(doc, target_group), \
            target_group.open_text
    if namespace is not None:
        holder = next((g for g in items if isinstance(g, Group) and g.namespace == namespace
                       and not g.conditional), None)
        if holder is None:
            holder = new_group(doc.format, composition._next_id('g'), namespace, indent)
            _place(items, holder, indent, opening, doc.format)
            target_group = holder
        items, indent, opening = holder.items, _inner_indent(doc, holder), holder.open_text
    _place(items, placed, indent, opening, doc.format)
    _check_definition(composition, node, diagnostics)
    return Change(diagnostics, node.id)


def _check_definition(composition: Composition, node: ComposedNode,
                      diagnostics: list[Diagnostic]) -> None:
    if composition.definition_of(node) is None:
        diagnostics.append(Diagnostic(
            Severity.WARNING, f'{node.label}: no definition is found (in the definitions folders '
            'given, nor in the ament index); the node is added, but its endpoints and '
            'parameters are not known or checked (source the workspace, or give --definitions)',
            file=composition.path, code='NODL985'))


def remove_node(doc: Document, node: ComposedNode, container: ComposedNode | None) -> None:
    """Take ``node`` out of the document (out of its container for a composable node)."""
    if container is not None:
        container.children.remove(node)
        container.dirty = True
        return

    def visit(items: list[Item]) -> bool:
        for index, item in enumerate(items):
            if item is node:
                del items[index]
                if index == 0 and items:
                    items[0].gap = node.gap
                return True
            if isinstance(item, Group) and visit(item.items):
                return True
        return False
    visit(doc.items)
