"""The ROS launch actions (``launch_ros``'s): nodes, containers, composable nodes, pushed
namespaces, ``set_remap`` and ``set_parameter``.

A :class:`Node` adds a :class:`~nodl.launch.model.LaunchedNode` to the result
instead of starting a process: its final namespace (pushed namespaces combined as
launch_ros combines them), its remapping rules in the order rcl applies them, and its
parameter sources in command-line order (see :mod:`nodl.launch.parameter_values` for
how they resolve to values).

A part of a node only the running launch knows does not drop the node: a parameter source
whose path is a run-time value (``$(command ...)``, a value computed by a module not
installed here, such as nav2's ``RewrittenYaml``), a parameters dict such a value is unpacked
into (``{**config, 'x': 1}``: the names written out are known), or ``remappings``/``arguments``
given whole as such a value, is one NODL513 warning and a :class:`~nodl.launch.model.RunTimeSource`
in the record's ``run_time``: the node is analysed with what is known.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from nodl.launch.actions import Action
from nodl.launch.conditions import Condition
from nodl.launch.errors import LaunchProblem, Unevaluable
from nodl.launch.model import LaunchedNode, LaunchRemap, ParameterSource, RunTimeSource, SourceLocation
from nodl.launch.params import ParameterValue, RuntimeValue, evaluate_value, normalize_python_dict
from nodl.launch.python_missing import unpacked
from nodl.launch.substitutions import normalize, perform
from nodl.launch.text_checks import check_node_text, refuse_unsafe
from nodl.naming import join_name, namespace_error, node_name_error, normalize_namespace

if TYPE_CHECKING:
    from nodl.launch.context import LaunchContext

__all__ = ['PushRosNamespace', 'SetRemap', 'SetParameter', 'SetParametersFromFile', 'Node',
           'ComposableNode', 'ComposableNodeContainer', 'LoadComposableNodes', 'Container',
           'ParameterFileEntry', 'make_namespace_absolute', 'prefix_namespace', 'RUN_TIME_KEYWORD']


class PushRosNamespace(Action):
    """``push-ros-namespace``: relative namespaces of later nodes in scope are prefixed."""

    def __init__(self, namespace: Any, **_: Any) -> None:
        self.namespace = normalize(namespace)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        pushed = perform(context, self.namespace)
        refuse_unsafe(pushed, 'the pushed namespace', self.location)
        previous = context.configurations.get('ros_namespace')
        namespace = make_namespace_absolute(prefix_namespace(previous, pushed))
        problem = namespace_error(namespace or '/')
        if problem:
            raise LaunchProblem('NODL519', f"the resulting namespace '{namespace}' is invalid: "
                                           f'{problem} (previous {previous!r}, pushed {pushed!r})')
        context.configurations['ros_namespace'] = namespace
        return None


class SetRemap(Action):
    """``set_remap``: a rule every later node in scope gets before its own."""

    def __init__(self, src: Any, dst: Any, **_: Any) -> None:
        self.src, self.dst = normalize(src), normalize(dst)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        rule = LaunchRemap(perform(context, self.src), perform(context, self.dst), self.location)
        remaps = context.configurations.get('ros_remaps', [])
        remaps.append(rule)  # in place, as launch_ros does (see context.py)
        context.configurations['ros_remaps'] = remaps
        return None


class SetParameter(Action):
    """``set_parameter``: a parameter every later node in scope gets (before its own)."""

    def __init__(self, name: Any, value: Any, **_: Any) -> None:
        self.name = normalize(name)
        # As normalize_parameter_dict: text stays text, substitutions are read as YAML.
        self.value = value if isinstance(value, ParameterValue) else normalize_python_dict({'_': value})[0][1]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        name = perform(context, self.name)
        value = evaluate_parameter(context, self.value, name, self.location)
        params = context.configurations.get('global_params', [])
        params.append((name, value))
        context.configurations['global_params'] = params
        return None


class SetParametersFromFile(Action):
    """``set_parameters_from_file``: a parameter file every later node in scope gets."""

    def __init__(self, filename: Any, **_: Any) -> None:
        self.filename = normalize(filename)

    def execute(self, context: LaunchContext) -> list[Action] | None:
        params = context.configurations.get('global_params', [])
        try:
            params.append(perform(context, self.filename))
        except Unevaluable as problem:
            # The nodes in scope stay in the analysis, known to lack what this file gives.
            context.warn(problem.code, f'parameter file: {problem.message}; the nodes in its scope are '
                                    'analysed without the parameters it gives', self.location, cause=problem)
            params.append(_RunTimeFile(self.location))
        context.configurations['global_params'] = params
        return None


class _RunTimeFile:
    """In ``global_params``: a ``set_parameters_from_file`` whose path only the running
    launch knows (where it is written)."""

    def __init__(self, location: SourceLocation) -> None:
        self.location = location


# -- nodes -----------------------------------------------------------------------------------

def prefix_namespace(base: str | None, namespace: str | None) -> str | None:
    """launch_ros's ``prefix_namespace``: ``namespace`` under ``base`` unless it is absolute."""
    if base is None and namespace is None:
        return None
    if namespace is None:
        combined = base
    elif not base or namespace.startswith('/'):
        combined = namespace
    else:
        combined = ('' if base == '/' else base) + '/' + namespace
    assert combined is not None
    return combined if combined == '/' else combined.rstrip('/')


def make_namespace_absolute(namespace: str | None) -> str | None:
    """A leading ``/`` for a relative namespace (as ``rcl_node_init`` takes it)."""
    if namespace is None:
        return None
    return normalize_namespace(namespace)


class ParameterFileEntry:
    """A parameter file in a node's ``parameters`` (``param from=``, a path, ``ParameterFile``)."""

    #: Where it is written when a frontend knows (``<param from=...>``), else None.
    location: SourceLocation | None = None

    def __init__(self, param_file: Any, allow_substs: Any = False) -> None:
        self.path = normalize(param_file)
        self.allow_substs = allow_substs
        #: The file once evaluated, as launch_ros's ``ParameterFile.evaluate`` keeps it: the
        #: path and, with ``allow_substs``, the substituted text (None: not substituted).  One
        #: entry given to many nodes (``configured_params = ParameterFile(RewrittenYaml(...))``,
        #: nav2's bringup) is evaluated by the first node that reads it; the others get what it
        #: gave, in whatever scope they are, as launch_ros gives them the same file.
        self.evaluated: tuple[str, str | None] | None = None


def _normalize_parameters(parameters: Any) -> list[Any]:
    out: list[Any] = []
    for item in parameters or []:
        if isinstance(item, dict):
            out.append(normalize_python_dict(item))
        elif (isinstance(item, ParameterFileEntry) or (isinstance(item, list) and item and isinstance(item[0], tuple))
              or hasattr(item, 'nodl_parameter')):
            out.append(item)
        else:
            out.append(ParameterFileEntry(item))
    return out


def _ros_arguments(context: LaunchContext, node: Any, location: SourceLocation,
                   record: LaunchedNode) -> None:
    """Split ``arguments`` + ``--ros-args`` + ``ros_arguments`` as rcl reads a command line."""
    words = [perform(context, a) for a in node.arguments]
    first_ros = len(words)  # words from here on are ros_args (their place: ros_arguments_source)
    if node.ros_arguments:
        words += ['--ros-args', *[perform(context, a) for a in node.ros_arguments]]
    in_ros = False
    i = 0
    while i < len(words):
        word = words[i]
        if word == '--ros-args':
            in_ros = True
        elif word == '--' and in_ros:
            in_ros = False
        elif not in_ros:
            record.arguments.append(word)
        elif word in ('-r', '--remap', '-p', '--param', '--params-file') and i + 1 < len(words):
            value = words[i + 1]
            i += 1
            if word in ('-r', '--remap'):
                if ':=' not in value:
                    raise LaunchProblem('NODL519', f"invalid remapping rule '{value}' in the node's "
                                                   'arguments; expected FROM:=TO')
                src, dst = value.split(':=', 1)
                record.remaps.append(LaunchRemap(src, dst, _word_source(node, i, first_ros, location)))
            elif word in ('-p', '--param'):
                if ':=' not in value:
                    raise LaunchProblem('NODL518', f"invalid parameter rule '{value}'; expected NAME:=VALUE")
                name, text = value.split(':=', 1)
                from nodl.launch.rcl_yaml import rcl_yaml_value

                # rcl: "-p NODE:NAME:=VALUE" files the value under the node key NODE (a node
                # name, matched as "/NODE"), "-p NAME:=VALUE" under "/**"; VALUE typed by rcl.
                node_key, _, name = name.rpartition(':')
                record.parameters.append(ParameterSource('values', 'arguments', location,
                                                         values={name: rcl_yaml_value(text)},
                                                         node_key=node_key or '/**'))
            else:
                record.parameters.append(ParameterSource('file', 'arguments', location,
                                                         path=os.path.abspath(value)))
        else:
            record.ros_arguments.append(word)
        i += 1


def _word_source(node: Any, index: int, first_ros: int, location: SourceLocation) -> SourceLocation:
    """Where word ``index`` of a node's command line is written: its ``args``/``ros_args``
    attribute, the item of a Python list written out, else the node's entry."""
    key, offset = ('ros_args', index - first_ros - 1) if index > first_ros else ('args', index)
    where = getattr(node, 'word_sources', {}).get(key)
    if isinstance(where, list):
        return where[offset] if 0 <= offset < len(where) else location
    return where or location


def _global_parameters(context: LaunchContext, location: SourceLocation,
                       record: LaunchedNode) -> list[ParameterSource]:
    out = []
    for entry in context.configurations.get('global_params') or []:
        if isinstance(entry, tuple):
            out.append(ParameterSource('values', 'global', location, values={entry[0]: entry[1]}))
        elif isinstance(entry, _RunTimeFile):
            record.run_time += (RunTimeSource('parameters', entry.location),)
        else:
            out.append(ParameterSource('file', 'global', location, path=os.path.abspath(entry)))
    return out


def evaluate_parameter(context: LaunchContext, spec: Any, name: str, location: SourceLocation) -> Any:
    """A parameter's value, or a :class:`RuntimeValue` (with a warning) when only the running
    launch can know it: the node stays in the analysis, this one value unchecked."""
    try:
        return evaluate_value(context, spec, name)
    except Unevaluable as problem:
        context.warn(problem.code, f"parameter '{name}': {problem.message}; the node is analysed "
                                'without this value', location, cause=problem)
        return RuntimeValue(name)


def _item_place(location: SourceLocation, keyword: str, index: int) -> SourceLocation:
    """Where item ``index`` of the ``keyword`` argument of the call at ``location`` is
    written in a Python launch file (the argument, else the call); ``location`` elsewhere."""
    if not location.file.endswith('.py'):
        return location  # an XML or YAML entry: its place is the node's entry
    from nodl.launch.python_places import keyword_places

    places = keyword_places(location, keyword)
    if isinstance(places, list):
        return places[index] if 0 <= index < len(places) else location
    return places or location


def _run_time_parameters(context: LaunchContext, problem: Unevaluable, record: LaunchedNode,
                         parameters: list[Any], item: Any) -> None:
    """A parameter source only the running launch knows: the node is kept without it."""
    index = next(i for i, other in enumerate(parameters) if other is item)  # (only now: rare)
    where = getattr(item, 'location', None) or _item_place(record.source, 'parameters', index)
    what = 'composable node' if record.kind == 'composable' else 'node'
    context.warn(problem.code, f'parameters entry: {problem.message}; the {what} is analysed without the '
                            'parameters this entry gives (the known ones are checked; no parameter is '
                            'reported missing for it)', where, cause=problem)
    record.run_time += (RunTimeSource('parameters', where),)


def _own_parameters(context: LaunchContext, parameters: list[Any], location: SourceLocation,
                    node_key: str, record: LaunchedNode) -> list[ParameterSource]:
    out = []
    for item in parameters:
        if type(item) is list:  # name-value pairs (a frontend's params): neither of the others
            out.append(_named_parameters(context, item, location, node_key, record, parameters))
        elif isinstance(item, ParameterFileEntry):
            from nodl.files import tidy_path

            where = item.location or location
            if item.evaluated is not None:  # evaluated once for every node, as launch_ros does
                source = ParameterSource('file', 'node', where, path=item.evaluated[0])
                source.text = item.evaluated[1]
                out.append(source)
                continue
            try:
                path = perform(context, item.path)
            except Unevaluable as problem:
                _run_time_parameters(context, problem, record, parameters, item)
                continue
            except LaunchProblem as problem:
                raise _placed(problem, where) from None
            path = tidy_path(path)  # '$(dirname)/../config/x.yaml' tidied
            if not os.path.isfile(path):
                context.warn('NODL517', f"parameter file '{path}' is not a file; launch skips it", where)
                continue
            source = ParameterSource('file', 'node', where, path=path)
            if item.allow_substs is not False and _allow_substs(context, item.allow_substs, where):
                _substitute_file(context, source, record, where)
            if source.path is not None:  # (a file only the running launch can read: each node says so)
                item.evaluated = (source.path, source.text)
            out.append(source)
        elif hasattr(item, 'nodl_parameter'):
            name, spec = item.nodl_parameter
            pname = perform(context, name)
            out.append(ParameterSource('values', 'node', location,
                                       values={pname: evaluate_parameter(context, spec, pname, location)}))
        else:
            out.append(_named_parameters(context, item, location, node_key, record, parameters))
    return out


def _allow_substs(context: LaunchContext, value: Any, where: SourceLocation) -> bool:
    """Whether a parameter file's text is substituted first (``allow_substs``: a bool, or
    text or substitutions that launch reads as one)."""
    if isinstance(value, bool) or value is None:
        return bool(value)
    from nodl.launch.substitutions import to_bool

    try:
        return to_bool(context, normalize(value))
    except LaunchProblem as problem:
        raise _placed(problem, where) from None


def _substitute_file(context: LaunchContext, source: ParameterSource, record: LaunchedNode,
                     where: SourceLocation) -> None:
    """launch_ros's ``ParameterFile(..., allow_substs=True)``: the file's text, every
    substitution in it (``$(var name)``, ``$(env NAME)``, ``$(find-pkg-share pkg)``...)
    performed in the launch's context, is what the node reads (``source.text``)."""
    from nodl.launch.params import read_parameter_text
    from nodl.launch.substitution_grammar import parse_substitution

    assert source.path is not None
    text, problem = read_parameter_text(source.path)
    if text is None:
        return  # said where unreadable parameter files are (the analysis, at the file)
    try:
        source.text = perform(context, parse_substitution(text))
    except Unevaluable as unknown:
        what = 'composable node' if record.kind == 'composable' else 'node'
        context.warn(unknown.code, f"parameter file '{source.path}' (allow_substs): {unknown.message}; "
                                f'the {what} is analysed without the parameters it gives', where, cause=unknown)
        record.run_time += (RunTimeSource('parameters', where),)
        source.path = None  # (its values are unknown: none are read from the text as written)
    except LaunchProblem as failed:
        raise LaunchProblem(failed.code, f"parameter file '{source.path}' (allow_substs): "
                                         f'{failed.message}', where.file, where.line, where.column) from None


def _named_parameters(context: LaunchContext, item: Any, location: SourceLocation, node_key: str,
                      record: LaunchedNode, parameters: list[Any]) -> ParameterSource:
    values: dict[str, Any] = {}
    places: dict[str, SourceLocation] = {}
    for name, spec in item:
        # an XML or YAML <param> knows where it is written: its findings sit there
        where = getattr(spec, 'location', None) or location
        try:
            pname = perform(context, name)
        except Unevaluable as problem:
            # A Python dict with a value of a module not installed here unpacked into it
            # ({**config, 'x': 1}): the parameters it gives only the running launch knows,
            # the ones written out are checked (any other name not known stays a problem).
            if not _unpacked(name):
                raise
            _run_time_parameters(context, problem, record, parameters, item)
            continue
        except LaunchProblem as problem:
            raise _placed(problem, where) from None
        try:
            values[pname] = evaluate_parameter(context, spec, pname, where)
        except LaunchProblem as problem:
            raise _placed(problem, where) from None
        if where is not location:
            places[pname] = where
    return ParameterSource('values', 'node', location, values=values, node_key=node_key,
                           places=places)


def _placed(problem: LaunchProblem, where: SourceLocation) -> LaunchProblem:
    """``problem`` at ``where`` unless it already has a place of its own."""
    if problem.file and problem.line:
        return problem
    problem.file, problem.line, problem.column = where.file, where.line, where.column
    return problem


def _unpacked(name: Any) -> bool:
    return unpacked(name) is not None


#: The keyword a frontend gives a node the lists it got whole as a value only the running
#: launch knows (``{'remappings': value, 'arguments': value}``: see
#: :func:`nodl.launch.python_arguments.action_arguments`); they are left out.
RUN_TIME_KEYWORD = 'nodl_run_time'

#: What a node lacks when one of its lists is known only at run time, by keyword.
_RUN_TIME_LISTS = {'arguments': ('arguments', 'its arguments (nor the -r, -p and --params-file '
                                              'rules they may hold)'),
                   'ros_arguments': ('arguments', 'its ROS arguments (nor the -r, -p and '
                                                  '--params-file rules they may hold)'),
                   'remappings': ('remaps', 'its remapping rules')}


def _run_time_lists(context: LaunchContext, lists: dict[str, Any], keywords: tuple[str, ...],
                    record: LaunchedNode) -> None:
    """One warning per list of ``keywords`` given whole as a run-time value; the record
    says the node is analysed without it."""
    what = 'composable node' if record.kind == 'composable' else 'node'
    for keyword in keywords:
        value = lists.get(keyword)
        if value is None:
            continue
        part, words = _RUN_TIME_LISTS[keyword]
        where = _item_place(record.source, keyword, -1)
        try:  # what the value is, said as its substitution says it
            perform(context, value)
            why = 'the value is known only when the launch runs'
        except LaunchProblem as problem:
            why = problem.message
        context.warn('NODL513', f'{keyword}: {why}; the {what} is analysed without {words}', where)
        record.run_time += (RunTimeSource(part, where),)


class Node(Action):
    """``node``: a ROS node started as a process."""

    kind = 'node'

    def __init__(self, *, executable: Any, package: Any = None, name: Any = None, namespace: Any = None,
                 parameters: Any = None, remappings: Any = None, ros_arguments: Any = None,
                 arguments: Any = None, nodl_run_time: dict[str, Any] | None = None, **_: Any) -> None:
        self.executable = normalize(executable)
        self.package = None if package is None else normalize(package)
        self.name = None if name is None else normalize(name)
        self.namespace = None if namespace is None else normalize(namespace)
        self.parameters = _normalize_parameters(parameters)
        self.remappings = [(normalize(a), normalize(b)) for a, b in (remappings or [])]
        self.ros_arguments = list(ros_arguments or [])
        self.arguments = list(arguments or [])
        self.node_name: str | None = None
        #: Where each of ``remappings`` is written (set by the frontends; the entry's
        #: location when unknown), and where ``args``/``ros_args`` are (``-r`` rules).
        self.remap_sources: list[SourceLocation] = []
        #: Where an attribute of the entry is written, by name (a frontend's; None: a call).
        self.place_of: Callable[[str], tuple[int, int]] | None = None
        self.word_sources: dict[str, SourceLocation | list[SourceLocation]] = {}
        #: ``remappings``/``arguments``/``ros_arguments`` given whole as a value only the
        #: running launch knows (None: none, the usual case).
        self.run_time_lists = nodl_run_time
        #: What the last execution launched (a container's record: its command line's rules
        #: reach the composable nodes loaded with ``forward_global_arguments``).
        self.record: LaunchedNode | None = None

    def execute(self, context: LaunchContext) -> list[Action] | None:
        name = None
        if self.name is not None:
            name = perform(context, self.name)
            refuse_unsafe(name, 'the node name', lambda: _attribute_place(self, 'name'))
            problem = node_name_error(name)
            if problem:
                raise LaunchProblem('NODL519', f"invalid node name '{name}': {problem}")
        given = None if self.namespace is None else perform(context, self.namespace)
        refuse_unsafe(given, 'the namespace', lambda: _attribute_place(self, 'namespace'))
        namespace = make_namespace_absolute(prefix_namespace(context.configurations.get('ros_namespace'),
                                                             given))
        if namespace is not None:
            problem = context.namespace_error(namespace)
            if problem:
                raise LaunchProblem('NODL519', f"invalid namespace '{namespace}': {problem}")
        record = LaunchedNode(self.kind, None if self.package is None else perform(context, self.package),
                              perform(context, self.executable), name, namespace or '/', self.location,
                              include_chain=context.include_chain, namespace_given=namespace is not None)
        if self.run_time_lists:
            _run_time_lists(context, self.run_time_lists, ('arguments', 'ros_arguments'), record)
        if self.arguments or self.ros_arguments:
            _ros_arguments(context, self, self.location, record)
        fully = name is not None and namespace is not None
        fqn = join_name(namespace or '/', name or '')
        self.node_name = fqn if name is not None else None
        record.parameters += _global_parameters(context, self.location, record)
        record.parameters += _own_parameters(context, self.parameters, self.location,
                                             fqn if fully else '/**', record)
        record.remaps += list(context.configurations.get('ros_remaps') or [])
        record.remaps += _own_remaps(context, self.remappings, self.remap_sources, self.location, record)
        if self.run_time_lists:
            _run_time_lists(context, self.run_time_lists, ('remappings',), record)
        check_node_text(context, record)
        context.result.nodes.append(record)
        self.record = record
        return self.after(context)

    def after(self, context: LaunchContext) -> list[Action] | None:
        """What follows the node (a container's composable nodes)."""
        return None


def _attribute_place(node: Any, keyword: str) -> SourceLocation:
    """Where the ``keyword`` attribute (``name``, ``namespace``) of a node entry is written:
    the attribute of an XML or YAML entry, the argument of a Python call, else the entry."""
    place_of = getattr(node, 'place_of', None)
    if place_of is not None:
        return SourceLocation(node.location.file, *place_of(keyword))
    return _item_place(node.location, keyword, -1)


def _own_remaps(context: LaunchContext, remappings: list[tuple[Any, Any]], sources: list[SourceLocation],
                location: SourceLocation, record: LaunchedNode | None = None) -> list[tuple[str, str]]:
    """A node's own remapping rules, each with where it is written.  A rule with a side only
    the running launch knows is left out (NODL513 at the rule; the record's remapping rules
    are then incomplete), never kept as a made-up name."""
    out: list[tuple[str, str]] = []
    for i, (a, b) in enumerate(remappings):
        where = sources[i] if i < len(sources) else location
        try:
            out.append(LaunchRemap(perform(context, a), perform(context, b), where))
        except Unevaluable as problem:
            if record is None:
                raise
            what = 'composable node' if record.kind == 'composable' else 'node'
            context.warn(problem.code, f'remapping rule: {problem.message}; the {what} is analysed '
                                       'without this rule', where, cause=problem)
            record.run_time += (RunTimeSource('remaps', where),)
    return out


class ComposableNode:
    """``composable_node``: a node loaded into a container (not an action)."""

    def __init__(self, *, package: Any, plugin: Any, name: Any = None, namespace: Any = None,
                 parameters: Any = None, remappings: Any = None, extra_arguments: Any = None,
                 condition: Condition | None = None, nodl_run_time: dict[str, Any] | None = None,
                 **_: Any) -> None:
        self.package, self.plugin = normalize(package), normalize(plugin)
        self.name = None if name is None else normalize(name)
        self.namespace = None if namespace is None else normalize(namespace)
        self.parameters = _normalize_parameters(parameters)
        self.remappings = [(normalize(a), normalize(b)) for a, b in (remappings or [])]
        #: ``extra_arguments``: dicts of the options rclcpp_components reads when it loads
        #: the node (``use_intra_process_comms``, ``forward_global_arguments``).
        self.extra_arguments = [item for item in (extra_arguments or []) if isinstance(item, dict)]
        self.condition = condition
        self.location = SourceLocation('', 0, 0)
        self.remap_sources: list[SourceLocation] = []
        self.place_of: Callable[[str], tuple[int, int]] | None = None
        #: ``remappings`` given whole as a value only the running launch knows (as Node's).
        self.run_time_lists = nodl_run_time


class LoadComposableNodes(Action):
    """``load_composable_node``: composable nodes loaded into a target container."""

    def __init__(self, *, composable_node_descriptions: Any, target_container: Any, **_: Any) -> None:
        self.descriptions = list(composable_node_descriptions)
        self.target = target_container

    def execute(self, context: LaunchContext) -> list[Action] | None:
        host: LaunchedNode | None
        if isinstance(self.target, Node):
            container = self.target.node_name or ''
            host = self.target.record
        else:
            container = perform(context, self.target)
            if container and not container.startswith('/'):
                container = '/' + container
            host = next((r for r in reversed(context.result.nodes) if r.kind == 'container'
                         and join_name(r.namespace, r.name or '') == container), None)
        for description in self.descriptions:
            try:
                _load(context, description, container, host)
            except LaunchProblem as problem:
                context.problem(problem, description.location)
        return None


def _load(context: LaunchContext, description: ComposableNode, container: str,
          host: LaunchedNode | None = None) -> None:
    if description.condition is not None and not description.condition.evaluate(context):
        return
    forwarded = _forwards_global_arguments(context, description)
    name = None if description.name is None else perform(context, description.name)
    refuse_unsafe(name, 'the node name', lambda: _attribute_place(description, 'name'))
    given = None if description.namespace is None else perform(context, description.namespace)
    refuse_unsafe(given, 'the namespace', lambda: _attribute_place(description, 'namespace'))
    namespace = make_namespace_absolute(prefix_namespace(context.configurations.get('ros_namespace'), given))
    record = LaunchedNode('composable', perform(context, description.package), None, name,
                          namespace or '/', description.location, plugin=perform(context, description.plugin),
                          container=container, include_chain=context.include_chain,
                          namespace_given=namespace is not None)
    record.remaps += list(context.configurations.get('ros_remaps') or [])
    record.remaps += _own_remaps(context, description.remappings, description.remap_sources,
                                 description.location, record)
    if description.run_time_lists:
        _run_time_lists(context, description.run_time_lists, ('remappings',), record)
    if forwarded is None:
        record.run_time += (RunTimeSource('remaps', description.location),)
    elif forwarded and host is not None:
        record.remaps += _global_rules(host, record)
    record.parameters += _global_parameters(context, description.location, record)
    record.parameters += _own_parameters(context, description.parameters, description.location, '/**',
                                         record)
    check_node_text(context, record)
    context.result.nodes.append(record)


#: The ``extra_arguments`` rclcpp_components reads when it loads a node; each must be a
#: bool (else the container refuses to load the node).
_LOAD_OPTIONS = ('use_intra_process_comms', 'forward_global_arguments')


def _forwards_global_arguments(context: LaunchContext, description: ComposableNode) -> bool | None:
    """Whether the container gives the composable node its process's global arguments.

    rclcpp_components loads each node with ``use_global_arguments(false)``: the rules on
    the container's command line (its ``args``/``ros_args``, ``remappings``, the
    ``set_remap`` rules it was given, its ``__node``/``__ns``) do not reach the node, unless
    the load's ``extra_arguments`` hold ``forward_global_arguments: true`` (the last one
    given wins).  None when that value is known only at run time (NODL513 at the node);
    LaunchProblem NODL533 when an option is not a bool (the container refuses the load)."""
    forwarded: bool | None = False
    for item in description.extra_arguments:
        for name, spec in normalize_python_dict(item):
            option = perform(context, name)
            if option not in _LOAD_OPTIONS:
                continue
            try:
                value = evaluate_value(context, spec, option)
            except Unevaluable as problem:
                context.warn(problem.code, f"extra argument '{option}': {problem.message}; whether the "
                                           "container's command-line rules reach the composable node is "
                                           'known only at run time (it is analysed without them)',
                             description.location, cause=problem)
                if option == 'forward_global_arguments':
                    forwarded = None
                continue
            if not isinstance(value, bool):
                raise LaunchProblem('NODL533', f"extra argument '{option}' is {value!r}, not a bool: "
                                               'the container refuses to load the composable node '
                                               "(rclcpp_components: it must be a boolean); write "
                                               f"{option}: true or false")
            if option == 'forward_global_arguments':
                forwarded = value
    return forwarded


def _global_rules(host: LaunchedNode, record: LaunchedNode) -> list[tuple[str, str]]:
    """The rules a container's process has as global arguments, in rcl's order, each at the
    place it is written: its ``-r`` words and remappings (:attr:`LaunchedNode.remaps`), and
    the ``__node``/``__ns`` launch_ros gives it.  The loaded node ``record`` checks them
    after its own (rcl: local rules first), so the container's ``__node``/``__ns`` rename it
    only when the load gives it no name/namespace of its own (launch_ros sends them as
    local ``__node``/``__ns`` rules when they are given)."""
    rules = list(host.remaps)
    if host.name and not record.name:
        rules.append(LaunchRemap('__node', host.name, host.source))
    if host.namespace_given and not record.namespace_given:
        rules.append(LaunchRemap('__ns', host.namespace, host.source))
    return rules


class ComposableNodeContainer(Node):
    """``node_container``: a container process, then its composable nodes."""

    kind = 'container'

    def __init__(self, *, name: Any, namespace: Any, composable_node_descriptions: Any = None,
                 **kwargs: Any) -> None:
        super().__init__(name=name, namespace=namespace, **kwargs)
        self.descriptions = list(composable_node_descriptions or [])

    def after(self, context: LaunchContext) -> list[Action] | None:
        if not self.descriptions:
            return None
        load = LoadComposableNodes(composable_node_descriptions=self.descriptions, target_container=self)
        load.location = self.location
        return [load]


Container = ComposableNodeContainer
