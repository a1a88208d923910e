"""The walk: a launch file (and everything it includes) to launched-node records.

:func:`load_launch` does what ``ros2 launch FILE name:=value`` does before it starts
processes: the file is included with the arguments, and every entity is visited
depth-first in a :class:`~nodl.launch.context.LaunchContext`.  A problem stops
the entity it is found in (reported as a diagnostic) and the walk goes on.
"""

from __future__ import annotations

import os
from typing import Any

from nodl.diagnostics import Diagnostic, Severity
from nodl.launch.actions import (
    Action,
    DeclareLaunchArgument,
    GroupAction,
    IncludeLaunchDescription,
    LaunchDescription,
)
from nodl.launch.context import LaunchContext
from nodl.launch.errors import MAX_INCLUDE_DEPTH, LaunchProblem, Unevaluable
from nodl.launch.model import LaunchResult, SourceLocation
from nodl.launch.sandbox import LaunchLimits, contained
from nodl.launch.substitutions import Oversized, perform, perform_bounded

__all__ = ['load_launch', 'include', 'read_launch_file', 'launch_format']

_PYTHON = ('.py',)
_XML = ('.xml',)
_YAML = ('.yaml', '.yml')


def launch_format(path: str) -> str:
    """``python``, ``xml``, ``yaml`` or ``unknown`` (``.launch``: read by content), by the name."""
    lower = path.lower()
    if lower.endswith(_PYTHON):
        return 'python'
    if lower.endswith(_XML):
        return 'xml'
    if lower.endswith(_YAML):
        return 'yaml'
    return 'unknown'


def read_launch_file(path: str, context: LaunchContext,
                     site: SourceLocation | None = None) -> LaunchDescription | None:
    """Read one launch file into a :class:`LaunchDescription` (None, reported, if it cannot be).

    ``site``: the include entry it is read for (where a Python launch file that is not run,
    or fails its sandbox, is reported)."""
    kind = launch_format(path)
    if kind == 'unknown':
        try:
            with open(path, 'rb') as stream:
                head = stream.read(512).lstrip()
        except OSError:
            head = b''
        kind = 'xml' if head.startswith(b'<') else 'yaml'
    if kind == 'python':
        from nodl.launch.python_frontend import read_python_launch

        return read_python_launch(path, context, site)
    if kind == 'xml':
        from nodl.launch.xml_frontend import read_xml_launch

        description, problems = read_xml_launch(path)
    else:
        from nodl.launch.yaml_frontend import read_yaml_launch

        description, problems = read_yaml_launch(path)
    for problem in problems:
        context.report(problem)
    return description


def _describe_without_context(context: LaunchContext, action: Any,
                              seen: set[str]) -> LaunchDescription | None:
    """The description an include would load, read without a launch context as launch's
    ``try_get_launch_description_without_context`` does (None when its path needs one:
    ``$(var)``, ``$(dirname)``...); read problems are reported when the include runs."""
    scratch = LaunchContext(LaunchResult(context.result.file), context.environment, context.prefixes)
    try:
        path = perform(scratch, action.path)
    except LaunchProblem:
        return None
    real = os.path.realpath(path)
    if not os.path.isabs(path) or real in seen or len(seen) >= MAX_INCLUDE_DEPTH or not os.path.isfile(path):
        return None
    seen.add(real)
    scratch.current_file = path
    return read_launch_file(path, scratch, action.location)


def _argument_names_without_context(context: LaunchContext, action: Any) -> list[str]:
    scratch = LaunchContext(LaunchResult(context.result.file), context.environment, context.prefixes)
    try:
        return [perform(scratch, name) for name, _ in action.launch_arguments]
    except LaunchProblem:
        return []


def _declared_arguments(context: LaunchContext, entities: list[Any], conditional: bool,
                        chain: tuple[Any, ...] | None, seen: set[str], names: set[str],
                        declared: list[tuple[DeclareLaunchArgument, bool, tuple[Any, ...] | None]]) -> None:
    """Collect into ``declared`` (and ``names``) every argument ``entities`` declare, as
    :func:`_missing_required_argument` needs them: whether a condition holds it, and the
    includes it is declared through (``chain``)."""
    for entity in entities:
        if isinstance(entity, DeclareLaunchArgument):
            if entity.name not in names:
                names.add(entity.name)
                declared.append((entity, conditional or entity.condition is not None, chain))
            continue
        inner = conditional or getattr(entity, 'condition', None) is not None
        if isinstance(entity, GroupAction):
            if entity.scoped and not entity.forwarding:
                continue  # launch stops at ResetLaunchConfigurations
            _declared_arguments(context, entity.actions, inner, chain, seen, names, declared)
        elif isinstance(entity, LaunchDescription):
            _declared_arguments(context, entity.entities, inner, chain, seen, names, declared)
        elif isinstance(entity, IncludeLaunchDescription):
            nested = _describe_without_context(context, entity, seen)
            if nested is not None:
                _declared_arguments(context, nested.entities, inner, (*(chain or ()), entity), seen, names,
                                    declared)


def _missing_required_argument(context: LaunchContext, description: LaunchDescription,
                               given: list[str], path: str, top: bool = False) -> LaunchProblem | None:
    """launch's check before an include: every argument declared without a default and not
    under a condition, in the included file or in the files IT includes (as far as they load
    without a context), must be given by this include or by the includes leading to it
    (``top``: the file the user ran, whose arguments are given as ``NAME:=VALUE``)."""
    declared: list[tuple[DeclareLaunchArgument, bool, tuple[Any, ...] | None]] = []
    names: set[str] = set()
    seen = {os.path.realpath(path)}

    _declared_arguments(context, description.entities, False, None, seen, names, declared)
    accepted = list(given)  # launch extends one list: names of nested includes accumulate
    for argument, conditional, chain in declared:
        if conditional or argument.default_value is not None:
            continue
        for nested_include in chain or ():
            accepted.extend(_argument_names_without_context(context, nested_include))
        if argument.name not in accepted:
            where = argument.location
            through = ''
            if chain:
                through = ' (declared in a file it includes: ' + ' -> '.join(
                    str(i.location) for i in chain) + ')'
            if top:  # the file the user ran: its arguments come from the command line
                return LaunchProblem('NODL506', f"the launch file needs the argument '{argument.name}'"
                                                f'{through}, which has no default and is not given; '
                                                f'give it on the command line: {argument.name}:=VALUE',
                                     where.file, where.line, where.column)
            return LaunchProblem('NODL506', f"included launch file '{path}' needs argument "
                                            f"'{argument.name}'{through}, which is not given (given: "
                                            f"{', '.join(given) or 'none'}); add "
                                            f'<arg name="{argument.name}" value="..."/> to the include',
                                 where.file, where.line, where.column)
    return None


class _Leave(Action):
    """Restores the current file and include chain after an included file."""

    def __init__(self, file: str, chain: tuple[SourceLocation, ...]) -> None:
        self.file, self.chain = file, chain

    def execute(self, context: LaunchContext) -> list[Action] | None:
        context.current_file = self.file
        context.include_chain = self.chain
        context.file_stack.pop()
        return None


def include(context: LaunchContext, action: Any) -> list[Action] | None:
    """Execute an include: read the file, check cycles and required arguments, set its arguments."""
    from nodl.files import tidy_path

    # Absolute and tidy ('launch/../x.launch.xml' as 'x.launch.xml'): the file findings name.
    path = tidy_path(perform(context, action.path))
    if not os.path.isabs(path):
        path = os.path.abspath(path)
    real = os.path.realpath(path)
    where = action.location
    if real in context.file_stack:
        start = context.file_stack.index(real)
        chain = ' -> '.join([*context.file_stack[start:], real])
        raise LaunchProblem('NODL507', f'include cycle: {chain}; a launch file includes itself '
                                       'through this chain')
    if len(context.file_stack) >= MAX_INCLUDE_DEPTH:
        raise LaunchProblem('NODL508', f'includes nest deeper than {MAX_INCLUDE_DEPTH} files; '
                                       f"not following '{path}'")
    if not os.path.isfile(path):
        raise LaunchProblem('NODL515', f"included launch file '{path}' does not exist"
                            + (' (or is not a file)' if os.path.exists(path) else ''))
    arguments = [(perform(context, k), v) for k, v in action.launch_arguments]
    saved = (context.current_file, context.include_chain)
    description = read_launch_file(path, context, where)
    if path not in context.result.files:
        context.result.files.append(path)
    if description is None:
        return None
    top = not context.include_chain and not getattr(getattr(action, 'location', None), 'line', 1)
    missing = _missing_required_argument(context, description, [name for name, _ in arguments], path,
                                         top)
    if missing is not None:
        raise missing
    values = [(name, perform_bounded(context, value, f"launch argument '{name}' given to '{path}'", where))
              for name, value in arguments]
    for name, value in values:
        context.configurations[name] = value
        if isinstance(value, Oversized):  # reported at the include; the file is still read
            context.problem(value.problem.again(), where)
    context.current_file = path
    if where.line:
        context.include_chain = (*context.include_chain, where)
    context.file_stack.append(real)
    return [description, _Leave(*saved)]


def _what_is_missing(entity: Action) -> str:
    """What the analysis lacks when a value only the running launch knows stops ``entity``."""
    from nodl.launch.ros_actions import LoadComposableNodes, Node

    if isinstance(entity, Node):
        return '; this node is missing from the analysis'
    if isinstance(entity, LoadComposableNodes):
        return '; these composable nodes are missing from the analysis'
    if isinstance(entity, IncludeLaunchDescription):
        return '; the nodes of the included launch file are missing from the analysis'
    return '; nodes that depend on it may be missing from the analysis'


def _visit(context: LaunchContext, root: Action) -> None:
    """Depth-first, as launch visits entities (iterative: deep nesting cannot overflow)."""
    stack: list[Any] = [root]
    while stack:
        entity = stack.pop()
        if not isinstance(entity, Action):
            context.report(Diagnostic(Severity.WARNING, f'a launch description holds {type(entity).__name__}, '
                                      'not an action; ignored', (), context.current_file, code='NODL512'))
            continue
        try:
            context.count_entity()
        except LaunchProblem as problem:
            context.problem(problem, entity.location)
            return
        try:
            if entity.condition is not None and not entity.condition.evaluate(context):
                continue
            if isinstance(entity, IncludeLaunchDescription) and type(entity).execute is Action.execute:
                children = include(context, entity)  # (not overridden by a launch file's subclass)
            else:
                children = entity.execute(context)
        except Unevaluable as problem:
            problem.message += _what_is_missing(entity)
            context.problem(problem, entity.location)
            continue
        except LaunchProblem as problem:
            context.problem(problem, entity.location)
            continue
        except RecursionError:
            context.problem(LaunchProblem('NODL508', 'the launch nests too deeply'), entity.location)
            continue
        if children:
            stack.extend(reversed(children))


def load_launch(path: str | os.PathLike[str], arguments: dict[str, str] | None = None, *,
                environment: dict[str, str] | None = None,
                prefixes: list[str] | None = None, limits: LaunchLimits | None = None) -> LaunchResult:
    """Read a launch file (XML, YAML or Python) as ``ros2 launch PATH name:=value...`` would.

    ``arguments`` are the launch arguments; ``environment`` (default ``os.environ``) is what
    ``$(env)`` reads and where ``AMENT_PREFIX_PATH`` is taken from unless ``prefixes`` is given.
    ``limits``: whether the launch's Python code (Python launch files, ``$(eval)``) runs, and
    for how long and with how much memory (default :class:`~nodl.launch.sandbox.LaunchLimits`:
    it runs in a forked child, 30 s, 2048 MiB; see :mod:`nodl.launch.sandbox`).
    Never raises for a problem in a launch file: see :attr:`LaunchResult.diagnostics`.
    """
    name = os.path.abspath(os.fspath(path))
    return contained(lambda: _walk(name, arguments, environment, prefixes), name, limits)


def _walk(name: str, arguments: dict[str, str] | None, environment: dict[str, str] | None,
          prefixes: list[str] | None) -> LaunchResult:
    """:func:`load_launch` of ``name`` in this process."""
    result = LaunchResult(name)
    context = LaunchContext(result, environment, prefixes)
    context.current_file = name
    given = dict(arguments or {})
    root = IncludeLaunchDescription(name, launch_arguments=list(given.items()))
    root.location = SourceLocation(name, 0, 0)
    _visit(context, LaunchDescription([root]))
    declared = set(result.arguments)
    for argument in given:
        if argument not in declared:
            from nodl.wording import did_you_mean

            result.diagnostics.append(Diagnostic(
                Severity.WARNING, f"launch argument '{argument}' is given but no launch file declares "
                f'it{did_you_mean(argument, declared)}', (), name, code='NODL520'))
    return result


