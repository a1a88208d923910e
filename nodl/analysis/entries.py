"""What the analysis reads from a launch: one :class:`LaunchEntry` per launched node.

The launch reader (:mod:`nodl.launch`) evaluates launch files; the
analysis needs, per node, only what this module holds: package, executable
(or composable node plugin), name, namespace, remapping rules in the order rcl
applies them, parameter settings in the order they are applied, and where the
node is launched.  :func:`entries_from_launch` adapts the reader's records;
tests and other front ends may build entries directly.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Iterable

from nodl.system.entities import Location

__all__ = ['ParameterSetting', 'ParameterFile', 'LaunchEntry', 'entries_from_launch']


@dataclass(frozen=True, slots=True)  # (no __dict__: one object less per setting)
class ParameterSetting:
    """One parameter value given to a node, where it is written, and how."""

    #: The parameter's name (dotted for nested values).
    name: str
    #: The value, typed as launch types it.
    value: Any
    #: Where it is written (a launch entry, or the line of a parameter file).
    location: Location
    #: ``inline`` (``param``, ``parameters=``), ``file`` (a parameter file), ``global``
    #: (``set_parameter``), ``argument`` (``--ros-args -p``).
    origin: str = 'inline'


@dataclass(frozen=True, slots=True)  # (no __dict__: one object less per file)
class ParameterFile:
    """A parameter file given to a node, applied once the node's final name is known.

    ``settings(fqn)`` returns the settings of the file that apply to the node
    called ``fqn`` (exact name or wildcards, as rcl matches node keys).
    """

    path: str
    settings: Callable[[str], list[ParameterSetting]]
    location: Location


@dataclass(slots=True)  # (no __dict__: one object less per launched node)
class LaunchEntry:
    """One launched node, as the launch would start it."""

    package: str
    #: The executable (None for a composable node).
    executable: str | None
    #: Where the node is launched (the ``node`` / ``composable_node`` entry).
    location: Location
    #: The composable node class (``pkg::ClassName``), None for an executable.
    plugin: str | None = None
    #: ``name=`` (None: the executable picks it).
    name: str | None = None
    #: The namespace, pushed namespaces combined (``/`` for none).
    namespace: str = '/'
    #: ``(from, to)`` in the order rcl applies them (``set_remap`` rules first).
    remaps: list[tuple[str, str]] = field(default_factory=list)
    #: Where each of ``remaps`` is written (the ``remap`` entry, ``set_remap``, the
    #: ``args`` holding ``-r``); missing ones are at :attr:`location`.
    remap_locations: list[Location] = field(default_factory=list)
    #: Parameter values and files, in the order they are applied (a later value wins).
    parameters: list[ParameterSetting | ParameterFile] = field(default_factory=list)
    #: The container a composable node is loaded into (its fully qualified name), if any.
    container: str | None = None
    #: ``node`` (a process), ``container`` (a process hosting composable nodes) or
    #: ``composable`` (a node loaded into a container).
    role: str = 'node'
    #: What of the node only the running launch knows, and where it is written:
    #: ``('parameters', where)`` (a parameter source), ``('remaps', where)`` (its remapping
    #: rules), ``('arguments', where)`` (arguments that may hold ``-p`` and ``-r`` rules).
    #: Empty (the usual case) when everything it is given is known.
    run_time: tuple[tuple[str, Location], ...] = ()

    def remap_location(self, index: int) -> Location:
        """Where rule ``index`` of :attr:`remaps` is written."""
        if 0 <= index < len(self.remap_locations):
            return self.remap_locations[index]
        return self.location

    @property
    def parameters_complete(self) -> bool:
        """False when more parameters may come at run time than :attr:`parameters` give."""
        return not self.run_time or all(part == 'remaps' for part, _ in self.run_time)

    @property
    def remaps_complete(self) -> bool:
        """False when more remapping rules may come at run time than :attr:`remaps`."""
        return not self.run_time or all(part == 'parameters' for part, _ in self.run_time)

    @property
    def composable(self) -> bool:
        """True for a composable node (matched by its plugin)."""
        return self.plugin is not None


def _location(value: Any) -> Location:
    if value is None:
        return Location('<launch>', 0, 0)
    # (tuple.__new__: NamedTuple's own __new__ is a Python function; one or more per node)
    return tuple.__new__(Location, (str(value.file), int(value.line or 0), int(value.column or 0)))


#: The launch reader's parameter origins -> the words of :attr:`ParameterSetting.origin`.
_ORIGINS = {'arguments': 'argument', 'global': 'global', 'node': 'inline'}


def _resolved_settings(record: Any, overrides: Callable[[Any, str], dict[str, Any]]
                       ) -> Callable[[str], list[ParameterSetting]]:
    """The values a launched node receives, given its final name: which parameter-file keys
    apply and which value wins as rcl (processes) or launch_ros (composable nodes) decide it
    (``overrides``: :func:`nodl.launch.overrides.parameter_overrides`)."""
    def settings(fqn: str) -> list[ParameterSetting]:
        new = tuple.__new__  # (a Location per value, without NamedTuple's Python __new__)
        return [ParameterSetting(o.name, o.value, new(Location, (o.file, o.line, o.column)),
                                 'file' if o.kind == 'file' else _ORIGINS.get(o.origin, 'inline'))
                for o in overrides(record, fqn).values()]
    return settings


def entries_from_launch(records: Iterable[Any]) -> list[LaunchEntry]:
    """Launch entries from the launch reader's records
    (:class:`nodl.launch.LaunchedNode`); :class:`LaunchEntry` objects pass through."""
    from nodl.launch.model import remap_source
    from nodl.launch.overrides import parameter_overrides

    out = []
    for record in records:
        if isinstance(record, LaunchEntry):
            out.append(record)
            continue
        namespace = record.namespace or '/'
        where = _location(record.source)  # (one immutable tuple for the entry and its file)
        parameters: list[ParameterSetting | ParameterFile] = []
        if record.parameters:  # all sources at once: rcl merges them into one table
            parameters.append(ParameterFile(record.source.file,
                                            _resolved_settings(record, parameter_overrides), where))
        remaps = record.remaps  # (most nodes have none: no lists made from it then)
        entry = LaunchEntry(
            package=str(record.package or ''), executable=record.executable,
            location=where, plugin=record.plugin, name=record.name,
            namespace=namespace, remaps=[(str(a), str(b)) for a, b in remaps] if remaps else [],
            remap_locations=[_location(remap_source(r, record.source)) for r in remaps]
            if remaps else [],
            parameters=parameters, container=record.container, role=record.kind)
        unknown = getattr(record, 'run_time', ())
        if unknown:  # (rare: a part only the running launch knows)
            entry.run_time = tuple((part, _location(place)) for part, place in unknown)
        out.append(entry)
    return out
