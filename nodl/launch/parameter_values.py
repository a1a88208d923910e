"""The parameter values a launched node receives, resolved as rcl and launch_ros resolve them.

A node started as a process (``node``, ``node_container``) gets its parameters from its
command line: launch writes ``--ros-args`` with the node's ``ros_args`` first, then the
``set_parameter``/``set_parameters_from_file`` in scope, then its own ``param`` entries
(a ``parameters=[{...}]`` dict becomes a parameter file keyed by the node's full name when
its name and namespace are both known, else ``/**``; a ``Parameter(...)`` or a
``set_parameter`` becomes ``-p NAME:=VALUE``, which rcl files under the node key ``/**``).
rcl reads every file and rule, in command-line order, into ONE table of node keys: a key is
added where it first appears, and a value written again under the same key replaces the
earlier value in place.  The node (rclcpp and rclpy alike) then walks that table in order,
takes every key that matches its full name (``/*`` one name token, ``/**`` any number, a
missing leading ``/`` added) and lets a later value win.  So a value under ``/**`` loses to
one under the node's own name whenever ``/**`` entered the table first, even when it was
written later; :func:`process_overrides` reproduces exactly that.  Values are typed by rcl's
YAML rules (:func:`rcl_scalar`): ``y``/``on``/``yes`` are booleans, ``1e5`` and ``inf`` are
doubles, ``010`` is octal, a quoted value is a string.

A composable node gets its parameters from launch_ros in the load request
(:func:`composable_overrides`): the sources in the same order, a later value wins; of a
parameter file only the ``/**`` key and then the node's exact ``namespace/name`` apply
(leading slashes dropped, no other wildcard), typed by PyYAML; a node loaded without a name
gets only ``/**``; the container's own command line does not apply (launch_ros loads nodes
with ``use_global_arguments`` off).

These rules were checked against real rclpy nodes (``tests/test_launch_parameter_values.py``) and
read from the sources of rcl, rclcpp, rclpy and launch_ros.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, NamedTuple

import yaml

from nodl.launch.params import RuntimeValue, load_parameter_file, parse_parameter_text
from nodl.launch.rcl_yaml import (
    composable_key,
    match_composable_parameter_keys,
    match_parameter_file_nodes,
    node_key_applies,
    rcl_scalar,
    rcl_yaml_value,
)

if TYPE_CHECKING:
    from nodl.launch.model import LaunchedNode, ParameterSource

__all__ = ['ParameterOverride', 'parameter_overrides', 'process_overrides', 'composable_overrides',
           'match_parameter_file_nodes', 'match_composable_parameter_keys', 'rcl_scalar',
           'rcl_yaml_value', 'as_rcl_reads_dump', 'as_rcl_reads_text']


class ParameterOverride(NamedTuple):
    """A parameter value a node receives, and where it was written."""

    name: str
    value: Any
    #: The parameter file (at the parameter's key) or the launch entry that set it.
    file: str
    line: int
    column: int
    #: ``arguments`` (``ros_args``), ``global`` (``set_parameter...``) or ``node`` (its own).
    origin: str
    #: ``file`` or ``values``.
    kind: str
    #: The node key it was written under (``/**``, ``/ns/name``...).
    node_key: str


def _known_at_run_time(value: Any) -> bool:
    return isinstance(value, RuntimeValue)


#: Values that are what rcl reads back, however launch_ros writes them (most parameters are
#: numbers or booleans: no check for a run-time value, a string inside a list, and no import).
_AS_READ = (bool, int, float)
#: Texts longer than this (a robot_description of several MB) skip ``yaml.dump`` and the
#: re-read (both pure Python: 20 s for 16 MiB) when rcl reads them as a string even unquoted:
#: then they are a string however PyYAML writes them (it reads back exactly what it wrote).
_LONG_TEXT = 1024


def as_rcl_reads_dump(value: Any) -> Any:
    """What rcl reads back from ``yaml.dump(value)`` (launch_ros writes node dicts and
    ``Parameter`` values that way): PyYAML leaves ``'y'`` or ``'1e5'`` unquoted, rcl reads a
    bool and a double."""
    if type(value) in _AS_READ or _known_at_run_time(value):
        return value
    if type(value) is str and len(value) > _LONG_TEXT and type(rcl_scalar(value)) is str:  # (itself)
        return value
    if isinstance(value, str) or (isinstance(value, list) and any(isinstance(v, str) for v in value)):
        return rcl_yaml_value(yaml.dump(value))
    return value


def as_rcl_reads_text(value: Any) -> Any:
    """What rcl reads from ``-p NAME:={value}`` (launch_ros passes ``set_parameter`` values
    formatted by Python: ``'1'`` becomes the int 1, ``True`` the bool true)."""
    if type(value) in _AS_READ or _known_at_run_time(value):
        return value
    if isinstance(value, (bool, int, float)) and not isinstance(value, str):
        return value
    if isinstance(value, (list, tuple)):
        return rcl_yaml_value(str(list(value)))
    return rcl_yaml_value(str(value))


# -- resolution ------------------------------------------------------------------------------

def _file_entries(path: str, composable: bool, text: str | None = None
                  ) -> list[tuple[str, dict[str, Any], dict[str, tuple[int, int]], int, int]]:
    # (text: the file substituted first, allow_substs)
    loaded = load_parameter_file(path) if text is None else parse_parameter_text(path, text)
    if composable:  # launch_ros reads the file with PyYAML (aliases and merge keys resolved)
        return [(n.key, n.parameters, n.positions, n.line, n.column)
                for n in loaded.composable_nodes]
    if loaded.rcl_refuses:  # rcl refuses the whole file (an alias): the node gets nothing
        return []
    return [(n.key, n.rcl_parameters, n.positions, n.line, n.column) for n in loaded.nodes]


def process_overrides(sources: Iterable[ParameterSource], fqn: str) -> dict[str, ParameterOverride]:
    """The parameters a node started as a process called ``fqn`` receives from ``sources``
    (its records' :attr:`~nodl.launch.model.LaunchedNode.parameters`), as rcl resolves them."""
    table: dict[str, dict[str, ParameterOverride]] = {}
    for source in sources:
        origin = source.origin
        if source.kind == 'file':
            path = source.path
            if not path:
                continue
            for key, values, positions, line, column in _file_entries(path, False, source.text):
                entry = table.setdefault(key, {})
                for name, value in values.items():
                    at = positions.get(name, (line, column))
                    entry[name] = ParameterOverride(name, value, path, at[0], at[1], origin, 'file', key)
            continue
        where, key = source.source, source.node_key
        entry = table.setdefault(key, {})
        read = as_rcl_reads_text if origin == 'global' else \
            as_rcl_reads_dump if origin == 'node' else None
        places = source.places
        for name, value in source.values.items():
            place = places.get(name, where) if places else where  # (most: the source's place)
            # (a bool, int or float is read back as it is: not passed to read)
            entry[name] = ParameterOverride(
                name, value if read is None or type(value) in _AS_READ else read(value),
                place.file, place.line, place.column, origin, 'values', key)
    if len(table) == 1:  # (most nodes: their own parameters, under their own name)
        [(key, entry)] = table.items()
        return entry if node_key_applies(key, fqn) else {}  # (made by this call: no copy needed)
    keys = match_parameter_file_nodes(table, fqn)
    if len(keys) == 1:
        return table[keys[0]]
    out: dict[str, ParameterOverride] = {}
    for key in keys:
        out.update(table[key])
    return out


def composable_overrides(sources: Iterable[ParameterSource], name: str | None,
                         namespace: str) -> dict[str, ParameterOverride]:
    """The parameters launch_ros puts in the load request of a composable node (``name`` as
    given in the launch file, None when not given; ``namespace`` final)."""
    out: dict[str, ParameterOverride] = {}
    for source in sources:
        where = source.source
        if source.kind != 'file':
            for pname, value in source.values.items():
                place = source.places.get(pname, where)
                out[pname] = ParameterOverride(pname, value, place.file, place.line, place.column,
                                               source.origin, 'values', source.node_key)
            continue
        if not source.path:
            continue
        # launch_ros: one dict per normalized key (a later equal key replaces the earlier one).
        by_key: dict[str, tuple[str, dict[str, Any], dict[str, tuple[int, int]], int, int]] = {}
        for entry in _file_entries(source.path, True, source.text):
            by_key[composable_key(entry[0])] = entry
        for key in match_composable_parameter_keys(list(by_key), name, namespace):
            raw, values, positions, line, column = by_key[key]
            for pname, value in values.items():
                at = positions.get(pname, (line, column))
                out[pname] = ParameterOverride(pname, value, source.path, at[0], at[1],
                                               source.origin, 'file', raw)
    return out


def parameter_overrides(node: LaunchedNode, fqn: str | None = None) -> dict[str, ParameterOverride]:
    """The parameters ``node`` receives, by name, as the running system would give them.

    ``fqn`` is the node's final full name; it defaults to the record's own
    (:attr:`~nodl.launch.model.LaunchedNode.fqn`) and must be given for a node
    launched without a name (the name its executable picks decides which keys apply).
    """
    if node.kind == 'composable':
        return composable_overrides(node.parameters, node.name, node.namespace)
    name = fqn if fqn is not None else node.fqn
    if name is None:
        raise ValueError('the node was launched without a name: pass the full name it takes')
    return process_overrides(node.parameters, name)
