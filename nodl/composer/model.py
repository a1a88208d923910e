"""The composition model: the items of a launch file, editable or kept verbatim.

A launch file read by the composer is a tree of items in file order:

* :class:`ComposedNode`: a node, a container of composable nodes, or a composable node, whose
  declarative part (package, executable or plugin, name, namespace, remapping rules and
  parameter values) is editable; what else its entry holds (a parameter file, ``args``, an
  ``output`` attribute, a Python keyword computed by code) is a :class:`Kept` piece inside it,
  written back verbatim;
* :class:`Group`: a ``group`` / ``GroupAction`` whose children are items too (its namespace
  known when it pushes a literal one);
* :class:`Kept`: anything else (an ``include``, an ``arg``, a condition, Python code,
  substitutions, an unknown action), kept verbatim, shown read-only.

Every item keeps the text it was read from (:attr:`Item.original`): an item that is not
edited is written back byte for byte; an edited one is written anew by its format's writer.
The text between items (:attr:`Item.gap`: white space, comments) is kept as it is.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

__all__ = [
    'NODE_KINDS',
    'ComposedNode',
    'Document',
    'Group',
    'Item',
    'Kept',
    'Param',
    'Remap',
    'pushes_group_namespace',
]

#: ``node`` (a process), ``container`` (a process hosting composable nodes), ``composable``.
NODE_KINDS = ('node', 'container', 'composable')


@dataclass
class Kept:
    """Content the composer does not edit, written back verbatim, shown read-only."""

    #: The text as read (the whole element, entry, keyword argument or statement).
    text: str
    #: What it is, in a few words (``<include>``, ``condition``, ``Python code``).
    what: str
    #: The line it starts on in the file as read (0 for none).
    line: int = 0
    #: The text before it (white space, comments), kept too.
    gap: str = ''
    #: The column it starts at (0-based) in the file as read: a writer moving it re-indents by
    #: the difference.
    column: int = 0
    #: Never edited (a kept piece is written as read).
    dirty: bool = False

    @property
    def original(self) -> str:
        """The text as read."""
        return self.text

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping."""
        return {'type': 'kept', 'what': self.what, 'line': self.line, 'text': self.text}


@dataclass
class Param:
    """A parameter value given in a node's own entry (typed as launch types it)."""

    name: str
    value: Any
    #: The text as read (None for a value the composer set).
    original: str | None = None
    gap: str = ''


@dataclass
class Remap:
    """A remapping rule of a node's own entry: ``source:=target``."""

    source: str
    target: str
    original: str | None = None
    gap: str = ''


@dataclass(eq=False)
class ComposedNode:
    """A node of the composition (see the module docstring)."""

    #: A stable identifier within the composition (``n1``, ``n2``...).
    id: str
    #: One of :data:`NODE_KINDS`.
    kind: str
    package: str
    #: The executable (nodes and containers; None for a composable node).
    executable: str | None
    #: The plugin class of a composable node (``pkg::Class``).
    plugin: str | None = None
    #: ``name=`` as written (None: the program names its node).
    name: str | None = None
    #: ``namespace=`` of the entry itself (None: only the groups' namespaces apply).
    namespace: str | None = None
    #: Parameter values, in the order they apply, and kept parameter sources (files...).
    params: list[Param | Kept] = field(default_factory=list)
    #: Remapping rules, in order (the first match wins), and kept ones.
    remaps: list[Remap | Kept] = field(default_factory=list)
    #: Everything else of the entry (attributes, children, keywords), kept verbatim.
    extra: list[Kept] = field(default_factory=list)
    #: The composable nodes of a container.
    children: list[ComposedNode] = field(default_factory=list)
    #: False when the entry itself is not declarative (a condition, a substitution in its
    #: package, name or namespace): the whole entry is then kept and shown read-only.
    editable: bool = True
    #: Why it is read-only ('' when editable).
    read_only_reason: str = ''
    #: The text as read (None: added by the composer).
    original: str | None = None
    #: True once edited: written anew.
    dirty: bool = False
    #: The line of the entry in the file as read (0: added).
    line: int = 0
    #: The text before the entry (white space, comments).
    gap: str = ''
    #: The indentation of the entry (its column), for writing it anew.
    indent: str = ''
    #: Format-specific facts the writer needs (the Python call's name, the YAML key...).
    style: dict[str, Any] = field(default_factory=dict)

    @property
    def label(self) -> str:
        """``package executable`` or ``package plugin``."""
        return f'{self.package} {self.executable or self.plugin or "?"}'

    def param_values(self) -> dict[str, Any]:
        """The parameter values of the entry itself, by name (a later one wins)."""
        return {p.name: p.value for p in self.params if isinstance(p, Param)}

    def walk(self) -> Iterator[ComposedNode]:
        """This node, then its composable nodes."""
        yield self
        yield from self.children


@dataclass(eq=False)
class Group:
    """A group of items, with the namespace it pushes when that is a literal one."""

    id: str
    #: The namespace it pushes (None: none, or one only the running launch knows).
    namespace: str | None
    items: list[Item] = field(default_factory=list)
    #: True when the group pushes a namespace the composer cannot read (a substitution).
    namespace_unknown: bool = False
    #: True when a condition decides whether the group is launched.
    conditional: bool = False
    #: The opening text (the start tag, ``GroupAction([``...), written back as read.
    open_text: str = ''
    #: The text between the last item and the closing text, and the closing text.
    close_gap: str = ''
    close_text: str = ''
    original: str | None = None
    dirty: bool = False
    line: int = 0
    gap: str = ''
    indent: str = ''
    style: dict[str, Any] = field(default_factory=dict)


Item = ComposedNode | Group | Kept


@dataclass
class Document:
    """A launch file as items (see the module docstring)."""

    #: ``xml``, ``yaml`` or ``python``.
    format: str
    #: The text before the first item (the XML declaration and ``<launch>``, ``launch:``,
    #: a Python module up to ``LaunchDescription([``).
    header: str
    items: list[Item] = field(default_factory=list)
    #: The text between the last item and the trailer, and the trailer itself.
    close_gap: str = ''
    trailer: str = ''
    #: The indentation of the top-level items.
    indent: str = '  '
    #: Format-specific facts (the Python names imported...).
    style: dict[str, Any] = field(default_factory=dict)

    def walk(self) -> Iterator[tuple[Item, Group | None]]:
        """Every item, depth first, with the group holding it (None: the top level)."""
        def visit(items: list[Item], group: Group | None) -> Iterator[tuple[Item, Group | None]]:
            for item in items:
                yield item, group
                if isinstance(item, Group):
                    yield from visit(item.items, item)
        return visit(self.items, None)

    def nodes(self) -> list[ComposedNode]:
        """Every node, composable nodes after their container, in file order."""
        out: list[ComposedNode] = []
        for item, _ in self.walk():
            if isinstance(item, ComposedNode):
                out.extend(item.walk())
        return out

    def kept(self) -> list[Kept]:
        """Every kept piece at item level (not those inside a node), but for a group's push of
        a literal namespace: that is the group's namespace, which the composer reads, shows
        and writes (:func:`pushes_group_namespace`), not a piece it leaves alone."""
        return [item for item, group in self.walk()
                if isinstance(item, Kept) and not pushes_group_namespace(item, group)]


#: How the formats name the action that pushes a namespace.
_PUSHES = ('push-ros-namespace', 'push_ros_namespace', '<push-ros-namespace>',
           '<push_ros_namespace>')


def pushes_group_namespace(item: Kept, group: Group | None) -> bool:
    """True when ``item`` is ``group``'s push of the literal namespace the group records."""
    if group is None or group.namespace is None or group.namespace_unknown:
        return False
    return item.what in _PUSHES or (item.what == 'Python code'
                                    and item.text.lstrip().startswith('PushRosNamespace('))
