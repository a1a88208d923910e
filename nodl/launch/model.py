"""What reading a launch file produces: launched-node records, arguments, the result.

These records say what ``ros2 launch`` would start, without starting it: for
every node (plain, container or composable) its package and executable (or
plugin and container), the name as given, the final namespace, the remapping
rules in the order rcl applies them, the parameter sources in the order they
apply, the extra arguments, and where in which launch file it was written
(with the chain of includes that led there).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, NamedTuple

from nodl.diagnostics import Diagnosed, Diagnostic
from nodl.location import Location

# A place in a launch file (1-based line and column, 0 when unknown) is the toolkit's one
# Location, made once by the reader and carried unchanged to the launched node's instance and
# its findings; SourceLocation is its name in the launch reader.
from nodl.location import Location as SourceLocation

__all__ = ['SourceLocation', 'LaunchRemap', 'ParameterSource', 'RunTimeSource', 'LaunchedNode',
           'LaunchArgument', 'LaunchResult', 'NODE_KINDS', 'PARAMETER_ORIGINS', 'RUN_TIME_PARTS']

#: ``node`` (a process), ``container`` (a process that hosts composable nodes), ``composable``.
NODE_KINDS = ('node', 'container', 'composable')
#: Where a parameter source comes from: the node's ``args``/``ros_args`` (``-p``,
#: ``--params-file``), ``set_parameter``/``set_parameters_from_file`` in scope (``global``),
#: or the node's own ``param`` entries / ``parameters=[...]`` (``node``).
PARAMETER_ORIGINS = ('arguments', 'global', 'node')
#: What of a node only the running launch may know: a parameter source (a parameter file
#: whose path is a run-time value, a ``parameters`` entry computed by a module not installed
#: here), its ``remappings`` or its ``arguments``/``ros_arguments`` given whole as such a value.
RUN_TIME_PARTS = ('parameters', 'remaps', 'arguments')


class LaunchRemap(tuple):  # type: ignore[type-arg]
    """A remapping rule ``(from, to)`` and where it is written (:attr:`source`): the
    ``remap`` entry, the ``set_remap`` action, or the ``args``/``ros_args`` holding ``-r``.

    It is the pair itself (it compares, unpacks and serialises as ``(from, to)``), so code
    that reads rules as pairs keeps working; :func:`remap_source` reads the place.
    """

    source: SourceLocation

    def __new__(cls, src: str, dst: str, source: SourceLocation) -> LaunchRemap:
        self = super().__new__(cls, (src, dst))
        self.source = source
        return self

    def __getnewargs__(self) -> tuple[str, str, SourceLocation]:
        return self[0], self[1], self.source


def remap_source(rule: Any, default: SourceLocation) -> SourceLocation:
    """Where a remapping rule of a launched node is written (``default``, the node's entry,
    for a plain pair)."""
    return rule.source if isinstance(rule, LaunchRemap) else default


class RunTimeSource(NamedTuple):
    """A part of a node only the running launch knows (one of :data:`RUN_TIME_PARTS`), and
    where it is written: the node is analysed without what it gives."""

    part: str
    source: SourceLocation


@dataclass
class ParameterSource:
    """One parameter source of a node, in application order.

    ``kind`` is ``file`` (``path`` is the parameter file) or ``values`` (``values`` maps
    parameter names, nested names joined with ``.``, to values typed as launch types them;
    ``node_key`` is the key rcl files them under: the node's full name, ``/**``, or the node
    prefix of ``-p NODE:NAME:=VALUE``).  Which of them apply and which value wins is
    :func:`nodl.launch.parameter_values.parameter_overrides` (rcl's merged table for a node
    started as a process, launch_ros's rules for a composable node).
    """

    kind: str
    origin: str
    source: SourceLocation
    path: str | None = None
    values: dict[str, Any] = field(default_factory=dict)
    node_key: str = '/**'
    #: Where a value of :attr:`values` is written when that is not :attr:`source` (each
    #: ``param`` of an XML or YAML node entry), by name.
    places: dict[str, SourceLocation] = field(default_factory=dict)
    #: A file's text after launch's substitutions (``allow_substs``): what the node reads
    #: instead of the file's own text (None: the file as it is).
    text: str | None = None

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping."""
        out: dict[str, Any] = {'kind': self.kind, 'origin': self.origin}
        if self.kind == 'file':
            out['path'] = self.path
        else:
            out['values'] = dict(self.values)
            out['node_key'] = self.node_key
        out['source'] = {'file': self.source.file, 'line': self.source.line,
                         'column': self.source.column}
        return out


@dataclass
class LaunchedNode:
    """A node ``ros2 launch`` would start (or load into a container)."""

    #: One of :data:`NODE_KINDS`.
    kind: str
    package: str | None
    #: The executable (plain nodes and containers); ``None`` for composable nodes.
    executable: str | None
    #: The name as given in the launch file, or ``None`` when the launch entry gives none:
    #: the node then takes the name its program gives it, which the launch file does not say
    #: (see :attr:`name_given`; the analysis looks for it in the node's registration).
    name: str | None
    #: The final namespace (absolute; ``/`` when none is given or pushed).
    namespace: str
    source: SourceLocation
    #: Remapping rules ``(from, to)`` in the order rcl applies them (the first match
    #: wins): those of ``args``/``ros_args``, then ``set_remap`` in scope, then the node's own.
    #: The reader records each as a :class:`LaunchRemap` (with the place it is written).
    remaps: list[tuple[str, str]] = field(default_factory=list)
    parameters: list[ParameterSource] = field(default_factory=list)
    #: The plugin class of a composable node (``pkg::Class``).
    plugin: str | None = None
    #: The container a composable node is loaded into (its full name as launch computes it).
    container: str | None = None
    #: ROS arguments after ``--ros-args`` other than ``-r``/``-p``/``--params-file``
    #: (``--log-level``, ``-e``...), as written.
    ros_arguments: list[str] = field(default_factory=list)
    #: Arguments for the program itself (before ``--ros-args``).
    arguments: list[str] = field(default_factory=list)
    #: The include entries that led to this node, outermost first.
    include_chain: tuple[SourceLocation, ...] = ()
    #: True when ``namespace`` was given or pushed (launch passes ``__ns``); False when the
    #: node keeps the namespace it creates itself with (``/`` for nodes created without one).
    namespace_given: bool = False
    #: What of the node only the running launch knows (see :data:`RUN_TIME_PARTS`), in the
    #: order met; empty (the usual case) when everything it is given is known here.
    run_time: tuple[RunTimeSource, ...] = ()

    @property
    def parameters_complete(self) -> bool:
        """False when parameters may come from a source known only at run time (a parameter
        source, or arguments that may hold ``-p``/``--params-file``): :attr:`parameters` are
        the known ones."""
        return not any(s.part != 'remaps' for s in self.run_time)

    @property
    def remaps_complete(self) -> bool:
        """False when remapping rules may come from a value known only at run time (the
        ``remappings``, or arguments that may hold ``-r``): :attr:`remaps` are the known ones."""
        return not any(s.part != 'parameters' for s in self.run_time)

    @property
    def name_given(self) -> bool:
        """True when the launch entry names the node; False when the program picks the name."""
        return self.name is not None

    @property
    def fqn(self) -> str | None:
        """``namespace/name`` when the name is known, else None."""
        if self.name is None:
            return None
        from nodl.naming import join_name

        return join_name(self.namespace, self.name)

    @property
    def remap_rules(self) -> list[str]:
        """The remapping rules as ``from:=to`` strings, in order."""
        return [f'{a}:={b}' for a, b in self.remaps]

    @property
    def launch_file(self) -> str:
        """The launch file the entry is written in."""
        return self.source.file

    # What the system layer (nodl.system.launched) reads of a launched node, in its words:
    # the record itself is the launched node there, not a copy of it.

    @property
    def location(self) -> Location:
        """Where the node is launched (the node entry: :attr:`source`)."""
        return self.source

    @property
    def role(self) -> str:
        """``node``, ``container`` or ``composable`` (:attr:`kind`)."""
        return self.kind

    @property
    def composable(self) -> bool:
        """True for a composable node (matched by its plugin)."""
        return self.plugin is not None

    def remap_location(self, index: int) -> Location:
        """Where rule ``index`` of :attr:`remaps` is written (the node entry for a plain pair)."""
        remaps = self.remaps
        if 0 <= index < len(remaps):
            return remap_source(remaps[index], self.source)
        return self.source

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping."""
        return {
            'kind': self.kind, 'package': self.package, 'executable': self.executable,
            'plugin': self.plugin, 'container': self.container, 'name': self.name,
            'name_given': self.name is not None,
            'namespace': self.namespace, 'remaps': [list(r) for r in self.remaps],
            'remap_sources': [{'file': s.file, 'line': s.line, 'column': s.column}
                              for s in (remap_source(r, self.source) for r in self.remaps)],
            'parameters': [p.to_dict() for p in self.parameters],
            'ros_arguments': list(self.ros_arguments), 'arguments': list(self.arguments),
            'source': {'file': self.source.file, 'line': self.source.line,
                       'column': self.source.column},
            'include_chain': [{'file': s.file, 'line': s.line, 'column': s.column}
                              for s in self.include_chain],
            'run_time': [{'part': s.part, 'file': s.source.file, 'line': s.source.line,
                          'column': s.source.column} for s in self.run_time],
        }


@dataclass
class LaunchArgument:
    """A declared launch argument (``arg``/``DeclareLaunchArgument``) and its final value."""

    name: str
    source: SourceLocation
    default: str | None = None
    description: str = ''
    choices: tuple[str, ...] | None = None
    #: The value it had when declared (given or default); None if it had none.
    value: str | None = None


@dataclass
class LaunchResult(Diagnosed):
    """Everything read from a launch file and the files it includes."""

    file: str
    nodes: list[LaunchedNode] = field(default_factory=list)
    #: Declared arguments by name (the first declaration of a name).
    arguments: dict[str, LaunchArgument] = field(default_factory=dict)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    #: Every launch file read, in the order first read.
    files: list[str] = field(default_factory=list)
