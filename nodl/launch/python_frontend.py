"""Python launch files: ``generate_launch_description()`` run against a stand-in for the
``launch``/``launch_ros`` API, which starts nothing.

While a Python launch file is evaluated (and only then) the modules ``launch``,
``launch.actions``, ``launch.substitutions``, ``launch.conditions``,
``launch.launch_description_sources``, ``launch.event_handlers``, ``launch_ros``,
``launch_ros.actions``, ``launch_ros.descriptions``, ``launch_ros.parameter_descriptions``,
``launch_ros.substitutions`` and ``ament_index_python(.packages)`` are the toolkit's
stand-ins (``sys.modules`` is restored afterwards).  Their classes are the actions the
XML and YAML frontends build, so the three formats resolve alike.  An action the stand-in
does not know (and an ``OpaqueFunction``) becomes a warning at its line saying which
nodes may be missing.  A module the launch file imports that is not installed here is
given to it as a module of placeholders, with a warning (see
:mod:`nodl.launch.python_missing`).  Running a Python launch file is running its
code, as ``ros2 launch`` does: analyse only launch files you would launch.
"""

from __future__ import annotations

import importlib.util
import os
import sys
import types
from functools import lru_cache
from typing import TYPE_CHECKING, Any

from nodl.diagnostics import Diagnostic, Severity
from nodl.launch import actions as A
from nodl.launch import conditions as C
from nodl.launch import params as P
from nodl.launch import python_missing as M
from nodl.launch import ros_actions as R
from nodl.launch import substitutions as S
from nodl.launch.errors import LaunchProblem, Unevaluable
from nodl.launch.model import SourceLocation
from nodl.launch.python_arguments import action_arguments
from nodl.launch.python_places import frame_location

if TYPE_CHECKING:
    from nodl.launch.context import LaunchContext

__all__ = ['read_python_launch', 'shim_modules']

_CURRENT: list[Any] = []  # [(context, path)] while a file is evaluated


def _caller() -> SourceLocation:
    path = _CURRENT[-1][1] if _CURRENT else ''
    return frame_location(path, sys._getframe(2))


def _located(cls: type, name: str | None = None) -> type:
    """A subclass whose instances remember the launch-file line that created them."""
    def __init__(self: Any, *args: Any, **kwargs: Any) -> None:
        if M.stubs_active():  # values from a module not installed here: run-time values
            args, kwargs = action_arguments(cls, args, kwargs)
        condition = kwargs.pop('condition', None)
        init: Any = getattr(cls, '__init__')  # noqa: B009  (mypy refuses __init__ read from a type)
        init(self, *args, **kwargs)
        self.location = _caller()
        if hasattr(self, 'remap_sources'):
            _place_remaps(self)
        if isinstance(self, A.Action) or condition is not None:
            self.condition = condition
    return type(name or cls.__name__, (cls,), {'__init__': __init__})


def _place_remaps(node: Any) -> None:
    """Where a node's ``remappings`` items (and ``arguments``/``ros_arguments`` words, for
    ``-r``) are written in the launch file, when they are written out in the call."""
    from nodl.launch.python_places import keyword_places

    places = keyword_places(node.location, 'remappings')
    if isinstance(places, list) and len(places) == len(node.remappings):
        node.remap_sources = places
    elif isinstance(places, SourceLocation):
        node.remap_sources = [places] * len(node.remappings)
    if hasattr(node, 'word_sources'):
        for keyword, key, words in (('arguments', 'args', node.arguments),
                                    ('ros_arguments', 'ros_args', node.ros_arguments)):
            where = keyword_places(node.location, keyword)
            if isinstance(where, SourceLocation) or (isinstance(where, list) and len(where) == len(words)):
                node.word_sources[key] = where


def _unknown(module: str) -> Any:
    def factory(name: str) -> Any:
        if name.startswith('__'):
            raise AttributeError(name)
        return _placeholder(f'{module}.{name}')
    return factory


def _placeholder(qualified: str) -> type:
    """A stand-in for a name the stand-in modules do not define.

    Importing it works (launch files import many names they use only in ``main()`` or in
    type hints); used as an action it is a NODL512 warning at its line, performed as a
    substitution a NODL513 warning: both say what cannot be known without running the launch.
    """
    class Unknown(A.Unevaluated, S.Substitution):
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            A.Unevaluated.__init__(self, qualified)
            self.location = _caller()

        def perform(self, context: LaunchContext) -> str:
            raise Unevaluable(f'{qualified} is not part of what the analyser evaluates; its value '
                              'is known only when the launch runs')

        def describe(self) -> str:
            return qualified

        def __getattr__(self, name: str) -> Any:
            if name.startswith('__'):
                raise AttributeError(name)
            return _placeholder(f'{qualified}().{name}')

    Unknown.__name__ = Unknown.__qualname__ = qualified.rpartition('.')[2]
    return Unknown


class _Finder:
    """Any other submodule of the stand-in packages imports as a module of placeholders (a
    meta path finder and loader by protocol, as :class:`~nodl.launch.python_missing.MissingModules`)."""

    def find_spec(self, fullname: str, path: Any, target: Any = None) -> Any:
        if fullname.partition('.')[0] not in _STAND_IN_PACKAGES or fullname in sys.modules:
            return None
        return importlib.util.spec_from_loader(fullname, self, is_package=True)  # type: ignore[arg-type]  # (exec_module, not load_module)

    def create_module(self, spec: Any) -> types.ModuleType:
        # launch's packages re-export what their submodules define: a submodule
        # (``launch.substitutions.launch_configuration``) offers its package's stand-ins.
        parent = spec.name.rpartition('.')[0]
        members = {k: v for k, v in vars(sys.modules[parent]).items() if not k.startswith('__')} \
            if parent in sys.modules else {}
        return _module(spec.name, members, unknown=True)

    def exec_module(self, module: types.ModuleType) -> None:
        return None


_STAND_IN_PACKAGES = ('launch', 'launch_ros')


def _python_paths(context: LaunchContext) -> list[str]:
    """Where a sourced workspace puts Python packages: ``<prefix>/lib/pythonX.Y/site-packages``
    (and ``local/lib/.../dist-packages``) of every ament prefix, so launch helpers installed
    with a package (``nav2_common.launch``...) import as they do under ``ros2 launch``."""
    import glob

    found = []
    for prefix in context.prefixes:
        for pattern in ('lib/python3*/site-packages', 'local/lib/python3*/dist-packages',
                        'lib/python3*/dist-packages'):
            for path in sorted(glob.glob(os.path.join(glob.escape(prefix), pattern))):
                if os.path.isdir(path) and path not in sys.path and path not in found:
                    found.append(path)
    return found


class _Source:
    def __init__(self, launch_file_path: Any, *args: Any, **kwargs: Any) -> None:
        self.location = M.run_time(launch_file_path)


class _Handler:
    def __init__(self, *args: Any, **kwargs: Any) -> None:
        found: list[Any] = []
        for key in ('on_exit', 'on_start', 'on_completion', 'on_shutdown', 'on_stdout', 'on_stderr',
                    'entities', 'on_state_transition'):
            value = kwargs.get(key)
            if value is None:
                continue
            if callable(value) and not isinstance(value, (list, tuple, A.Action)):
                found.append(A.Unevaluated(f'an event handler function ({key})'))
                found[-1].location = _caller()
            else:
                found.extend(value if isinstance(value, (list, tuple)) else [value])
        self.actions = found


class _RegisterEventHandler(A.Ignored):
    def __init__(self, event_handler: Any, **_: Any) -> None:
        # An unknown handler (a placeholder) is an action: said (NODL512), not dropped.
        super().__init__(actions=[event_handler] if isinstance(event_handler, A.Action)
                         else getattr(event_handler, 'actions', []))


class _Timer(A.Ignored):
    def __init__(self, *, period: Any = None, actions: Any = (), **_: Any) -> None:
        super().__init__(actions=list(actions))


class _Opaque(A.Unevaluated):
    def __init__(self, *args: Any, **kwargs: Any) -> None:
        function = kwargs.get('function', args[0] if args else None)
        super().__init__(f"OpaqueFunction({getattr(function, '__name__', '?')})")


class _ParameterFile(R.ParameterFileEntry):
    def __init__(self, param_file: Any, allow_substs: Any = False) -> None:
        super().__init__(M.run_time(param_file), allow_substs)


class _Parameter:
    def __init__(self, name: Any, value: Any, *, value_type: Any = None) -> None:
        self.nodl_parameter = (S.normalize(M.run_time(name)), _parameter_value(value, value_type))


def _type(value_type: Any) -> Any:
    if getattr(value_type, '__origin__', None) is list:  # list[T] and typing.List[T]
        return ('list', value_type.__args__[0])
    return value_type


def _parameter_value(value: Any, value_type: Any = None) -> P.ParameterValue:
    value = M.run_time(value)
    data_type = _type(value_type)
    if isinstance(value, (S.Substitution,)) or (isinstance(value, (list, tuple)) and value and all(
            isinstance(v, (str, S.Substitution)) for v in value) and any(isinstance(v, S.Substitution)
                                                                          for v in value)):
        return P.ParameterValue(S.normalize(value), data_type)
    if isinstance(value, (list, tuple)):
        return P.ParameterValue([S.normalize(v) if isinstance(v, S.Substitution) else v for v in value],
                                data_type)
    return P.ParameterValue(value, data_type)


def _package_share(package: str) -> str:
    if isinstance(package, (M.Placeholder, M.RunTimeText)):  # a package named at run time
        return M.package_folder(package)
    return os.path.join(_package_prefix(package), 'share', package)


def _package_prefix(package: str) -> str:
    if isinstance(package, (M.Placeholder, M.RunTimeText)):  # a package named at run time
        return M.package_folder(package)
    context = _CURRENT[-1][0] if _CURRENT else None
    if context is None:
        raise LookupError(package)
    try:
        return str(context.package_prefix(package))
    except LaunchProblem as problem:
        raise PackageNotFoundError(problem.message) from None


class PackageNotFoundError(KeyError):
    """``ament_index_python.PackageNotFoundError`` (a ``KeyError``, as there)."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ''


class _LaunchDescription(A.LaunchDescription):
    def __init__(self, initial_entities: Any = None, **kwargs: Any) -> None:
        super().__init__(M.entities(initial_entities), **kwargs)  # a placeholder is one action


_LaunchDescription.__name__ = _LaunchDescription.__qualname__ = 'LaunchDescription'


class _FindPackageShare(S.FindPackageShare):
    @staticmethod
    def find(package_name: str) -> str:
        """``FindPackageShare.find``: the share folder, found at once (no substitution)."""
        return _package_share(package_name)


class _FindPackagePrefix(S.FindPackagePrefix):
    @staticmethod
    def find(package_name: str) -> str:
        """``FindPackagePrefix.find``: the prefix, found at once."""
        return _package_prefix(package_name)


def _perform_substitutions(context: Any, subs: Any) -> str:
    """``launch.utilities.perform_substitutions`` for substitutions written in helper packages."""
    return S.perform(context, subs)


def _perform_typed_substitution(context: Any, value: Any, data_type: Any) -> Any:
    from nodl.launch.params import get_typed_value

    return get_typed_value(S.perform(context, value), data_type)


def _ensure_argument_type(*args: Any, **kwargs: Any) -> None:
    return None


def _expose(*args: Any, **kwargs: Any) -> Any:
    """``launch.frontend.expose_action``/``expose_substitution``: the frontends here have
    their own table of tags; a decorated class stays usable from Python."""
    return lambda cls: cls


def _module(name: str, members: dict[str, Any], unknown: bool = False) -> types.ModuleType:
    module = types.ModuleType(name)
    module.__dict__.update(members)
    module.__path__ = []  # a package: submodules import
    if unknown:
        setattr(module, '__getattr__', _unknown(name))  # noqa: B010  (mypy: a module's method)
    return module


def shim_modules() -> dict[str, types.ModuleType]:
    """The stand-in modules by name (fresh objects: each evaluation gets its own)."""
    L = _located
    subs = {name: getattr(S, name) for name in S.__all__ if isinstance(getattr(S, name), type)}
    subs.update(AnonName=S.AnonName, PythonExpression=S.PythonExpression,
                ThisLaunchFileDir=S.ThisLaunchFileDir, ThisLaunchFile=S.ThisLaunchFile)
    actions = dict(
        DeclareLaunchArgument=L(A.DeclareLaunchArgument), IncludeLaunchDescription=L(A.IncludeLaunchDescription),
        GroupAction=L(A.GroupAction), SetLaunchConfiguration=L(A.SetLaunchConfiguration),
        UnsetLaunchConfiguration=L(A.UnsetLaunchConfiguration),
        SetEnvironmentVariable=L(A.SetEnvironmentVariable),
        UnsetEnvironmentVariable=L(A.UnsetEnvironmentVariable),
        AppendEnvironmentVariable=L(A.AppendEnvironmentVariable),
        LogInfo=L(A.Ignored, 'LogInfo'), ExecuteProcess=L(A.ExecuteProcess),
        ExecuteLocal=L(A.ExecuteProcess, 'ExecuteLocal'), EmitEvent=L(A.Ignored, 'EmitEvent'),
        Shutdown=L(A.Ignored, 'Shutdown'), TimerAction=L(_Timer, 'TimerAction'),
        RegisterEventHandler=L(_RegisterEventHandler, 'RegisterEventHandler'),
        OpaqueFunction=L(_Opaque, 'OpaqueFunction'), OpaqueCoroutine=L(_Opaque, 'OpaqueCoroutine'),
        PushLaunchConfigurations=L(A.Ignored, 'PushLaunchConfigurations'),
        PopLaunchConfigurations=L(A.Ignored, 'PopLaunchConfigurations'),
    )
    conditions = dict(IfCondition=C.IfCondition, UnlessCondition=C.UnlessCondition,
                      LaunchConfigurationEquals=C.LaunchConfigurationEquals,
                      LaunchConfigurationNotEquals=C.LaunchConfigurationNotEquals)
    sources = {n: _Source for n in ('PythonLaunchDescriptionSource', 'XMLLaunchDescriptionSource',
                                    'YAMLLaunchDescriptionSource', 'AnyLaunchDescriptionSource',
                                    'FrontendLaunchDescriptionSource')}
    handlers = {n: _Handler for n in ('OnProcessExit', 'OnProcessStart', 'OnExecutionComplete',
                                      'OnShutdown', 'OnProcessIO', 'OnIncludeLaunchDescription',
                                      'OnStateTransition')}
    descriptions = dict(ComposableNode=L(R.ComposableNode), ParameterValue=_parameter_value,
                        ParameterFile=_ParameterFile, Parameter=_Parameter)
    ros_actions = dict(
        Node=L(R.Node), ComposableNodeContainer=L(R.ComposableNodeContainer),
        LoadComposableNodes=L(R.LoadComposableNodes), PushRosNamespace=L(R.PushRosNamespace),
        PushROSNamespace=L(R.PushRosNamespace), SetRemap=L(R.SetRemap), SetParameter=L(R.SetParameter),
        SetParametersFromFile=L(R.SetParametersFromFile), LifecycleNode=L(R.Node, 'LifecycleNode'),
        SetUseSimTime=L(R.SetParameter, 'SetUseSimTime'), RosTimer=L(_Timer, 'RosTimer'),
    )
    set_parameter: Any = ros_actions['SetParameter']

    def set_use_sim_time(self: Any, value: Any, **kwargs: Any) -> None:
        set_parameter.__init__(self, 'use_sim_time', value, **kwargs)
    ros_actions['SetUseSimTime'] = type('SetUseSimTime', (set_parameter,), {'__init__': set_use_sim_time})
    ros_subs = dict(FindPackageShare=_FindPackageShare, FindPackagePrefix=_FindPackagePrefix,
                    ExecutableInPackage=S.ExecutableInPackage, Parameter=S.ParameterSubstitution)
    ament = dict(get_package_share_directory=_package_share, get_package_prefix=_package_prefix,
                 PackageNotFoundError=PackageNotFoundError)
    utilities = dict(perform_substitutions=_perform_substitutions,
                     normalize_to_list_of_substitutions=S.normalize,
                     perform_typed_substitution=_perform_typed_substitution,
                     ensure_argument_type=_ensure_argument_type)
    types_tuple = (str, S.Substitution, list, tuple)
    launch = dict(LaunchDescription=_LaunchDescription, Action=A.Action, Substitution=S.Substitution,
                  Condition=C.Condition, LaunchContext=object, SomeSubstitutionsType=object,
                  SomeSubstitutionsType_types_tuple=types_tuple, LaunchDescriptionEntity=object)
    modules = {
        'launch': _module('launch', launch, unknown=True),
        'launch.utilities': _module('launch.utilities', utilities, unknown=True),
        'launch.some_substitutions_type': _module('launch.some_substitutions_type', dict(
            SomeSubstitutionsType=object, SomeSubstitutionsType_types_tuple=types_tuple)),
        'launch.substitution': _module('launch.substitution', dict(Substitution=S.Substitution)),
        'launch.action': _module('launch.action', dict(Action=A.Action)),
        'launch.launch_context': _module('launch.launch_context', dict(LaunchContext=object)),
        'launch.launch_description': _module('launch.launch_description',
                                             dict(LaunchDescription=_LaunchDescription)),
        'launch.condition': _module('launch.condition', dict(Condition=C.Condition)),
        'launch.frontend': _module('launch.frontend', dict(expose_action=_expose,
                                                           expose_substitution=_expose), unknown=True),
        'launch.actions': _module('launch.actions', actions, unknown=True),
        'launch.substitutions': _module('launch.substitutions', subs, unknown=True),
        'launch.conditions': _module('launch.conditions', conditions, unknown=True),
        'launch.launch_description_sources': _module('launch.launch_description_sources', sources,
                                                     unknown=True),
        'launch.event_handlers': _module('launch.event_handlers', handlers, unknown=True),
        'launch.events': _module('launch.events', {}, unknown=True),
        'launch_ros': _module('launch_ros', {}, unknown=True),
        'launch_ros.actions': _module('launch_ros.actions', ros_actions, unknown=True),
        'launch_ros.descriptions': _module('launch_ros.descriptions', descriptions, unknown=True),
        'launch_ros.parameter_descriptions': _module('launch_ros.parameter_descriptions', descriptions,
                                                     unknown=True),
        'launch_ros.substitutions': _module('launch_ros.substitutions', ros_subs, unknown=True),
        'ament_index_python': _module('ament_index_python', ament),
        'ament_index_python.packages': _module('ament_index_python.packages', ament),
    }
    for name, module in modules.items():
        parent, _, child = name.rpartition('.')
        if parent:
            setattr(modules[parent], child, module)
    return modules


def _forget_modules(paths: list[str]) -> None:
    """Drop the modules imported from ``paths`` (they hold the stand-ins of this evaluation)."""
    if not paths:
        return
    roots = tuple(os.path.join(p, '') for p in paths)
    for name, module in list(sys.modules.items()):
        if (getattr(module, '__file__', None) or '').startswith(roots):
            del sys.modules[name]


def _problem(path: str, exc: BaseException, text: str = '') -> Diagnostic:
    """The diagnostic for what the launch file's code raised, at the innermost line of the
    launch file the traceback passes through (the column of the failing expression)."""
    import traceback

    line = column = 0
    for frame in traceback.extract_tb(exc.__traceback__):
        if frame.filename == path:
            line = frame.lineno or 0
            column = _column(text, line, frame.colno)
    missing = '; the nodes this launch file would start are missing from the analysis'
    if isinstance(exc, MemoryError):
        from nodl.launch.sandbox import memory_problem

        code, message = memory_problem(f"the Python launch file '{path}'")
        return Diagnostic(Severity.ERROR, message + missing, (), path, line, column or (1 if line else 0),
                          code=code)
    if isinstance(exc, RecursionError):
        return Diagnostic(Severity.ERROR, 'the Python launch file recurses without end (RecursionError: '
                          f'{exc}){missing}', (), path, line, column or (1 if line else 0), code='NODL516')
    if isinstance(exc, PackageNotFoundError):
        return Diagnostic(Severity.ERROR, f'{exc}{missing}', (), path, line, column or (1 if line else 0),
                          code='NODL511')
    if isinstance(exc, SystemExit):
        return Diagnostic(Severity.ERROR, f'the Python launch file exits (sys.exit({exc.code!r})) '
                          f'before it gives its launch description{missing}', (), path, line,
                          column or (1 if line else 0), code='NODL516')
    if isinstance(exc, ModuleNotFoundError) and exc.name:
        return Diagnostic(Severity.ERROR, f"the Python launch file imports '{exc.name}', which is not "
                          'installed here (neither on the Python path nor in the Python folders of an '
                          'ament prefix); install or source the package that provides it'
                          f'{missing}', (), path, line, column or (1 if line else 0), code='NODL516')
    return Diagnostic(Severity.ERROR, f'the Python launch file raised {type(exc).__name__}: {exc}'
                      .split('\n')[0] + missing, (), path, line, column or (1 if line else 0), code='NODL516')


def _column(text: str, line: int, offset: int | None) -> int:
    """The 1-based column (in characters) of a frame's UTF-8 byte ``offset`` in ``line``."""
    if offset is None or not text or line < 1:
        return 0
    lines = text.splitlines()
    if line > len(lines):
        return 0
    return len(lines[line - 1].encode('utf-8', 'surrogatepass')[:offset].decode('utf-8', 'replace')) + 1


@lru_cache(maxsize=64)  # an included file is run twice (its declared arguments, then its nodes)
def _compiled(text: str, path: str) -> types.CodeType:
    """The code of a Python launch file's ``text`` (the same text compiles to the same code)."""
    return compile(text, path, 'exec')


def read_python_launch(path: str, context: LaunchContext,
                       site: SourceLocation | None = None) -> A.LaunchDescription | None:
    """Evaluate ``generate_launch_description()`` of a Python launch file with the stand-ins.

    Under :func:`nodl.launch.load_launch` this runs in its sandbox child (or not at all,
    ``--no-exec``: one NODL525 at ``site``, the include entry, or at the file's first line).
    """
    from nodl.frontends.source import decode, read_limited
    from nodl.launch.sandbox import admit, running

    try:
        text, problem = decode(read_limited(path), path)
    except OSError as exc:
        context.report(Diagnostic(Severity.ERROR, f'cannot read the launch file: {exc.strerror}', (), path,
                                  code='NODL515'))
        return None
    if text is None:
        assert problem is not None
        context.report(problem)
        return None
    what = f"the Python launch file '{path}'"
    where = site if site is not None and site.line else SourceLocation(path, 1, 1)
    refusal = admit('file', os.path.realpath(path), what)
    if refusal is not None:
        context.report(Diagnostic(refusal.severity, refusal.message, (), where.file, where.line,
                                  where.column, code=refusal.code))
        return None
    guard = running(os.path.realpath(path), what, where)
    guard.__enter__()
    shims = shim_modules()
    shims['yaml'] = context.shared_yaml.module()  # (the real PyYAML, each text parsed once a walk)
    saved = {name: sys.modules.get(name) for name in shims}
    stale = [name for name in sys.modules if name.partition('.')[0] in _STAND_IN_PACKAGES
             and name not in shims]
    saved.update((name, sys.modules.pop(name)) for name in stale)  # e.g. a real launch's modules
    sys.modules.update(shims)
    finder = _Finder()
    sys.meta_path.insert(0, finder)
    python_paths = _python_paths(context)
    sys.path.extend(python_paths)
    _CURRENT.append((context, path))
    namespace: dict[str, Any] = {'__file__': path, '__name__': '__nodl_launch__'}
    import contextlib

    stubs = M.MissingModules(context, path, python_paths).__enter__()  # last on sys.meta_path
    try:
        # What the launch file itself prints goes to standard error, as ros2 launch shows it:
        # standard output carries the reports of the tools (--format json, sarif).
        with contextlib.redirect_stdout(sys.stderr):
            code = _compiled(text, path)
            exec(code, namespace)  # noqa: S102 - running the launch file, as ros2 launch does
            generate = namespace.get('generate_launch_description')
            if not callable(generate):
                context.report(Diagnostic(Severity.ERROR, 'the Python launch file has no '
                                          'generate_launch_description() function', (), path, 1, 1,
                                          code='NODL516'))
                return None
            description = generate()
    except SystemExit as exc:  # sys.exit() in the user's code ends the launch, not the analysis
        context.report(_problem(path, exc, text))
        return None
    except SyntaxError as exc:
        context.report(Diagnostic(Severity.ERROR, f'Python syntax error: {exc.msg}', (), path,
                                  exc.lineno or 0, exc.offset or 0, code='NODL516'))
        return None
    except LaunchProblem as exc:
        context.report(exc.diagnostic(path, 0, 0))
        return None
    except RecursionError as exc:
        context.report(_problem(path, exc, text))
        return None
    except Exception as exc:  # the user's code: any error is a finding, never a crash
        context.report(_problem(path, exc, text))
        return None
    finally:
        guard.__exit__(None, None, None)
        stubs.__exit__()
        _CURRENT.pop()
        sys.meta_path.remove(finder)
        for python_path in python_paths:
            sys.path.remove(python_path)
        _forget_modules(python_paths)
        for name in [n for n in sys.modules if n.partition('.')[0] in _STAND_IN_PACKAGES]:
            if name not in saved:  # placeholders made by the finder
                del sys.modules[name]
        for name, module in saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module
    if isinstance(description, M.Placeholder):  # made by a module not installed here: one action
        description = A.LaunchDescription([description])
    if not isinstance(description, A.LaunchDescription):
        context.report(Diagnostic(Severity.ERROR, 'generate_launch_description() returned '
                                  f'{type(description).__name__}, not a LaunchDescription', (), path,
                                  code='NODL516'))
        return None
    description.location = SourceLocation(path, 0, 0)
    return description
