"""Launch substitutions: the objects the Python API builds (``LaunchConfiguration``,
``PathJoinSubstitution``...) and the ``$(...)`` syntax of the frontends stands for
(:mod:`nodl.launch.substitution_grammar` parses it into these objects).

Each object's :meth:`Substitution.perform` computes its text in a
:class:`~nodl.launch.context.LaunchContext` as ``launch`` does.

``$(eval EXPR)`` (``PythonExpression``) evaluates a Python expression with the
names of :mod:`math` available, exactly as ``launch`` does: it is code execution,
as when the launch file is launched; analyse only launch files you would launch.
``$(command ...)`` and ``$(find-exec ...)`` would run or look for programs: they are
not run; their value is reported as known only at run time (NODL513).
"""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

    from nodl.launch.context import LaunchContext

from nodl.launch.errors import (
    MAX_SUBSTITUTION_CHARS,
    LaunchProblem,
    SubstitutionTooLarge,
    Unevaluable,
    too_large_message,
)

__all__ = [
    'Substitution', 'TextSubstitution', 'LaunchConfiguration', 'EnvironmentVariable',
    'FindPackageShare', 'FindPackagePrefix', 'PythonExpression', 'ThisLaunchFileDir',
    'ThisLaunchFile', 'AnonName', 'NotSubstitution', 'AndSubstitution', 'OrSubstitution',
    'AnySubstitution', 'AllSubstitution', 'EqualsSubstitution', 'NotEqualsSubstitution',
    'IfElseSubstitution', 'PathJoinSubstitution', 'PathSubstitution', 'Command', 'FindExecutable',
    'FileContent', 'ExecutableInPackage', 'Deferred', 'Oversized', 'perform_or_defer', 'perform_bounded',
    'check_joined_size', 'LaunchLogDir', 'ParameterSubstitution', 'normalize', 'perform',
    'to_bool', 'yaml_bool',
]


class Substitution:
    """A piece of text computed when the launch runs."""

    def perform(self, context: LaunchContext) -> str:
        """The text, in ``context``."""
        raise NotImplementedError

    def describe(self) -> str:
        """A short description for messages."""
        return type(self).__name__

    def __repr__(self) -> str:
        return self.describe()


SomeSubstitutions = object  # str, a Substitution, or a sequence of them (typed as Any below)


def normalize(value: Any) -> list[Substitution]:
    """``str``, a substitution, a path or a sequence of those -> a list of substitutions."""
    if type(value) is list:  # the usual value (a parsed attribute), without the ABC check for a path
        return _normalize_items(value)
    if isinstance(value, Substitution):
        return [value]
    if isinstance(value, str):
        return [TextSubstitution(value)]
    if isinstance(value, os.PathLike):
        return [TextSubstitution(os.fspath(value))]
    if isinstance(value, (bool, int, float)):
        return [TextSubstitution(str(value))]
    if value is None:
        return [TextSubstitution('')]
    return _normalize_items(value)


def _normalize_items(value: Any) -> list[Substitution]:
    out: list[Substitution] = []
    for item in value:
        if isinstance(item, Substitution):  # the usual item (a parsed attribute), without recursing
            out.append(item)
        else:
            out.extend(normalize(item))
    return out


def perform(context: LaunchContext, value: Any) -> str:
    """Perform every substitution of ``value`` and join the texts.

    Raises :class:`~nodl.launch.errors.SubstitutionTooLarge` (NODL521) as soon as the
    texts together pass :data:`~nodl.launch.errors.MAX_SUBSTITUTION_CHARS`, before the
    oversized text is made."""
    if type(value) is list and len(value) == 1:
        part = value[0]
        # Plain text (most attributes): its text, without a copy, a generator and a join.
        if type(part) is TextSubstitution and type(part.text) is str:
            if len(part.text) > MAX_SUBSTITUTION_CHARS:
                raise SubstitutionTooLarge(too_large_message('a text substitution', made=True))
            return part.text
    texts = []
    size = 0
    for s in normalize(value):
        text = s.perform(context)
        size += len(text)
        if size > MAX_SUBSTITUTION_CHARS:
            raise SubstitutionTooLarge()
        texts.append(text)
    return ''.join(texts)


def check_joined_size(texts: list[str], separator: str = '') -> None:
    """:class:`SubstitutionTooLarge` if ``separator.join(texts)`` would pass the substitution
    limit (checked before the text is made)."""
    if sum(map(len, texts)) + len(separator) * max(len(texts) - 1, 0) > MAX_SUBSTITUTION_CHARS:
        raise SubstitutionTooLarge()


def yaml_bool(text: str) -> bool:
    """``text`` as a boolean as launch coerces it (``1``/``0``, then YAML's true/false/on/off/yes/no)."""
    import yaml

    value = {'1': 'true', '0': 'false'}.get(text, text)
    try:
        loaded = yaml.safe_load(value) if value else value
    except yaml.YAMLError:
        loaded = None
    if isinstance(loaded, bool):
        return loaded
    raise LaunchProblem('NODL510', f"cannot convert '{text}' to a boolean; expected true, false, 1 or 0")


def to_bool(context: LaunchContext, value: Any) -> bool:
    """Perform ``value`` and coerce it to a boolean (``perform_typed_substitution(..., bool)``)."""
    return yaml_bool(perform(context, value))


class TextSubstitution(Substitution):
    """Plain text."""

    def __init__(self, text: str = '') -> None:
        self.text = text

    def perform(self, context: LaunchContext) -> str:
        return self.text

    def describe(self) -> str:
        return repr(self.text)


class Deferred:
    """A launch configuration only the running launch knows (``<let value="$(command ...)">``):
    where it is used, the value is :class:`~nodl.launch.errors.Unevaluable` again."""

    def __init__(self, message: str) -> None:
        self.message = message
        #: Where the ``let`` (or ``arg`` default) that sets it is written, when known.
        self.location: tuple[str, int, int] | None = None


class Oversized:
    """A launch configuration whose value passed the substitution limit (reported once, at
    its ``let`` or ``arg``): where it is used, the same located problem is raised again, which
    the walk reports only once, so that what uses it stops without a cascade of errors."""

    def __init__(self, problem: SubstitutionTooLarge) -> None:
        self.problem = problem


def perform_bounded(context: LaunchContext, value: Any, what: str,
                    at: tuple[str, int, int]) -> str | Deferred | Oversized:
    """``perform_or_defer`` for the value of configuration ``what`` set at ``at``: a value
    past the substitution limit becomes :class:`Oversized`, its problem placed at ``at``."""
    try:
        return perform_or_defer(context, value)
    except SubstitutionTooLarge as problem:
        if problem.line:  # from another configuration, reported where that one is set
            return Oversized(problem)
        return Oversized(SubstitutionTooLarge(
            too_large_message(what) + '; what uses it is not analysed', *at))


def perform_or_defer(context: LaunchContext, value: Any) -> str | Deferred:
    """``perform`` for a value stored as a configuration: unknowable values are deferred."""
    try:
        return perform(context, value)
    except Unevaluable as problem:
        return Deferred(problem.message)


class LaunchConfiguration(Substitution):
    """``$(var NAME [DEFAULT])``: a launch configuration (argument, ``let``)."""

    def __init__(self, variable_name: Any, default: Any = None) -> None:
        self.variable_name = normalize(variable_name)
        self.default = None if default is None else normalize(default)

    def perform(self, context: LaunchContext) -> str:
        name = perform(context, self.variable_name)
        value = context.configurations.get(name)
        if isinstance(value, str):
            return value
        if isinstance(value, Deferred):
            where = value.location
            set_at = f' (set at {where[0]}:{where[1]}:{where[2]})' if where and where[1] else ''
            problem = Unevaluable(f"launch configuration '{name}'{set_at}: {value.message}")
            if where and where[1]:  # reported once at the let/arg, each use a related place
                problem.origin = (where[0], where[1], where[2])
                problem.configuration, problem.reason = name, value.message
            raise problem
        if isinstance(value, Oversized):
            raise value.problem.again()
        if self.default is not None:
            return perform(context, self.default)
        context.note_missing_configuration(name)
        raise LaunchProblem('NODL510', f"launch configuration '{name}' does not exist"
                            f'{context.configuration_hint(name)}')

    def describe(self) -> str:
        return f'$(var {"".join(s.describe() for s in self.variable_name)})'


class EnvironmentVariable(Substitution):
    """``$(env NAME [DEFAULT])``."""

    def __init__(self, name: Any, *, default_value: Any = None) -> None:
        self.name = normalize(name)
        self.default_value = None if default_value is None else normalize(default_value)

    def perform(self, context: LaunchContext) -> str:
        name = perform(context, self.name)
        if name in context.oversized_environment:
            raise context.oversized_environment[name].again()
        value = context.environment.get(name)
        if value is None and self.default_value is not None:
            value = perform(context, self.default_value)
        if value is None:
            raise LaunchProblem('NODL510', f"environment variable '{name}' does not exist; set it, "
                                           'or give a default: $(env NAME DEFAULT)')
        return value


class _FindPackage(Substitution):
    _what = 'share'

    def __init__(self, package: Any) -> None:
        self.package = normalize(package)

    def perform(self, context: LaunchContext) -> str:
        package = perform(context, self.package)
        prefix = context.package_prefix(package)
        return os.path.join(prefix, 'share', package) if self._what == 'share' else prefix


class FindPackageShare(_FindPackage):
    """``$(find-pkg-share PKG)``: ``<prefix>/share/PKG`` through the ament index."""


class FindPackagePrefix(_FindPackage):
    """``$(find-pkg-prefix PKG)``: the prefix the package is installed in."""

    _what = 'prefix'


class PythonExpression(Substitution):
    """``$(eval EXPR [MODULES])``: a Python expression evaluated as launch does (code execution)."""

    def __init__(self, expression: Any, python_modules: Any = ('math',)) -> None:
        self.expression = normalize(expression)
        self.python_modules = [m if isinstance(m, str) else m for m in python_modules]

    def perform(self, context: LaunchContext) -> str:
        # Imports and evaluation run in the launch's sandbox child, or not at all (--no-exec).
        from nodl.launch.model import SourceLocation
        from nodl.launch.sandbox import python_expression

        expression = perform(context, self.expression)
        modules = [m if isinstance(m, str) else perform(context, m) for m in self.python_modules]
        result = python_expression(expression, modules,
                                   SourceLocation(context.current_file or '<launch>', 1, 1))
        if isinstance(result, (str, bytes, list, tuple, dict, set)) and len(result) > MAX_SUBSTITUTION_CHARS:
            raise SubstitutionTooLarge(too_large_message('the result of $(eval)'))
        text = str(result)
        if len(text) > MAX_SUBSTITUTION_CHARS:
            raise SubstitutionTooLarge(too_large_message('the result of $(eval)'))
        return text


class ThisLaunchFileDir(Substitution):
    """``$(dirname)``: the folder of the launch file the substitution is written in."""

    def perform(self, context: LaunchContext) -> str:
        if not context.current_file:
            raise LaunchProblem('NODL510', '$(dirname) is known only inside a launch file')
        return os.path.dirname(context.current_file)


class ThisLaunchFile(Substitution):
    """``$(filename)``: the launch file the substitution is written in."""

    def perform(self, context: LaunchContext) -> str:
        return context.current_file


class AnonName(Substitution):
    """``$(anon NAME)``: a unique name, the same for the same NAME within one launch."""

    def __init__(self, name: Any) -> None:
        self.name = normalize(name)

    def perform(self, context: LaunchContext) -> str:
        name = perform(context, self.name)
        key = 'anon' + name
        value = context.configurations.get(key)
        if not isinstance(value, str):
            value = context.anonymous_name(name)
            context.configurations[key] = value
        return value


class NotSubstitution(Substitution):
    """``$(not VALUE)``."""

    def __init__(self, value: Any) -> None:
        self.value = normalize(value)

    def perform(self, context: LaunchContext) -> str:
        return str(not to_bool(context, self.value)).lower()


class AndSubstitution(Substitution):
    """``$(and LEFT RIGHT)``."""

    def __init__(self, left: Any, right: Any) -> None:
        self.left, self.right = normalize(left), normalize(right)

    def perform(self, context: LaunchContext) -> str:
        left = to_bool(context, self.left)
        right = to_bool(context, self.right)
        return str(left and right).lower()


class OrSubstitution(AndSubstitution):
    """``$(or LEFT RIGHT)``."""

    def perform(self, context: LaunchContext) -> str:
        left = to_bool(context, self.left)
        right = to_bool(context, self.right)
        return str(left or right).lower()


class AnySubstitution(Substitution):
    """``$(any A B ...)``."""

    def __init__(self, *args: Any) -> None:
        self.args = [normalize(a) for a in args]

    def perform(self, context: LaunchContext) -> str:
        return str(any([to_bool(context, a) for a in self.args])).lower()


class AllSubstitution(AnySubstitution):
    """``$(all A B ...)``."""

    def perform(self, context: LaunchContext) -> str:
        return str(all([to_bool(context, a) for a in self.args])).lower()


def _is_bool_text(text: str) -> bool:
    return text.lower() in ('true', 'false', '1', '0')


def _is_float_text(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _operand(value: Any) -> list[Substitution]:
    if value is None:
        return [TextSubstitution('')]
    if isinstance(value, bool):
        return [TextSubstitution(str(value).lower())]
    return normalize(value)


class EqualsSubstitution(Substitution):
    """``$(equals LEFT RIGHT)``: booleans as booleans, numbers as numbers, else text."""

    def __init__(self, left: Any, right: Any) -> None:
        self.left, self.right = _operand(left), _operand(right)

    def _equal(self, context: LaunchContext) -> bool:
        left, right = perform(context, self.left), perform(context, self.right)
        if _is_bool_text(left) and _is_bool_text(right):
            return (left.lower() in ('true', '1')) == (right.lower() in ('true', '1'))
        if _is_float_text(left) and _is_float_text(right):
            return math.isclose(float(left), float(right))
        return left == right

    def perform(self, context: LaunchContext) -> str:
        return str(self._equal(context)).lower()


class NotEqualsSubstitution(EqualsSubstitution):
    """``$(not-equals LEFT RIGHT)``."""

    def perform(self, context: LaunchContext) -> str:
        return str(not self._equal(context)).lower()


class IfElseSubstitution(Substitution):
    """``$(if CONDITION IF_VALUE [ELSE_VALUE])``."""

    def __init__(self, condition: Any, if_value: Any = '', else_value: Any = '') -> None:
        self.condition = normalize(condition)
        self.if_value, self.else_value = normalize(if_value), normalize(else_value)

    def perform(self, context: LaunchContext) -> str:
        chosen = self.if_value if to_bool(context, self.condition) else self.else_value
        return perform(context, chosen)


class PathJoinSubstitution(Substitution):
    """``PathJoinSubstitution([a, b, c])``: ``os.path.join`` of the performed parts."""

    def __init__(self, substitutions: Any) -> None:
        self.parts = [normalize(s) for s in substitutions]

    def perform(self, context: LaunchContext) -> str:
        if not self.parts:
            return ''
        texts = [perform(context, p) for p in self.parts]
        check_joined_size(texts, os.sep)  # the joined path is no longer than this
        return os.path.join(*texts)

    def __truediv__(self, other: Any) -> PathJoinSubstitution:
        joined = PathJoinSubstitution([])
        joined.parts = [*self.parts, normalize(other)]
        return joined


class PathSubstitution(Substitution):
    """``PathSubstitution(path)``: a path that joins with ``/`` (``... / 'config' / 'x.yaml'``)."""

    def __init__(self, path: Any) -> None:
        self.path = normalize(path)

    def perform(self, context: LaunchContext) -> str:
        return perform(context, self.path)

    def __truediv__(self, other: Any) -> PathJoinSubstitution:
        return PathJoinSubstitution([self, other])


class Command(Substitution):
    """``$(command CMD)``: the output of a program; not run by the analyser."""

    def __init__(self, command: Any, on_stderr: Any = 'fail') -> None:
        self.command = command

    def perform(self, context: LaunchContext) -> str:
        try:
            text = perform(context, self.command)
        except LaunchProblem:
            text = '...'
        raise Unevaluable(f"the value comes from running '{text}' ($(command)), which the "
                          'analyser does not do; it is known only at run time')


class FindExecutable(Substitution):
    """``$(find-exec NAME)``: a program on ``PATH``."""

    def __init__(self, *, name: Any) -> None:
        self.name = normalize(name)

    def perform(self, context: LaunchContext) -> str:
        import shutil

        name = perform(context, self.name)
        found = shutil.which(name, path=context.environment.get('PATH'))
        if found is None:
            raise LaunchProblem('NODL510', f"executable '{name}' not found on the PATH")
        return found


class FileContent(Substitution):
    """``$(file-content PATH)``: a file's text."""

    def __init__(self, path: Any) -> None:
        self.path = normalize(path)

    def perform(self, context: LaunchContext) -> str:
        from nodl.frontends.source import MAX_BYTES

        path = perform(context, self.path)
        try:
            with open(path, encoding='utf-8') as stream:
                text = stream.read(MAX_BYTES + 1)
        except OSError as exc:
            from nodl.files import describe_os_error

            raise LaunchProblem('NODL510', f"$(file-content): cannot read '{path}': "
                                           f'{describe_os_error(exc)}') from None
        except UnicodeDecodeError:
            raise LaunchProblem('NODL510', f"$(file-content): cannot read '{path}': it is not "
                                           'UTF-8 text') from None
        if len(text) > MAX_BYTES:
            raise LaunchProblem('NODL508', f"$(file-content): '{path}' is larger than 10 MB")
        return text


class ExecutableInPackage(Substitution):
    """``$(exec-in-pkg EXE PKG)``: ``<prefix>/lib/PKG/EXE``."""

    def __init__(self, executable: Any, package: Any) -> None:
        self.executable, self.package = normalize(executable), normalize(package)

    def perform(self, context: LaunchContext) -> str:
        package = perform(context, self.package)
        return os.path.join(context.package_prefix(package), 'lib', package,
                            perform(context, self.executable))


class LaunchLogDir(Substitution):
    """``$(log_dir)``: where launch writes its logs (known only at run time)."""

    def perform(self, context: LaunchContext) -> str:
        raise Unevaluable('the launch log folder ($(log_dir)) is known only at run time')


class ParameterSubstitution(Substitution):
    """``$(param NAME)``: a parameter set with ``set_parameter`` in the current scope."""

    def __init__(self, name: Any) -> None:
        self.name = normalize(name)

    def perform(self, context: LaunchContext) -> str:
        import yaml

        name = perform(context, self.name)
        for entry in reversed(list(context.configurations.get('global_params') or [])):
            if isinstance(entry, tuple) and entry[0] == name:
                value = entry[1]
                if isinstance(value, str):
                    return value
                if isinstance(value, (list, tuple)) and len(value) > MAX_SUBSTITUTION_CHARS // 2:
                    raise SubstitutionTooLarge(too_large_message(f"parameter '{name}' as text"))
                text = yaml.dump(value).strip().removesuffix('...').strip()
                if len(text) > MAX_SUBSTITUTION_CHARS:
                    raise SubstitutionTooLarge(too_large_message(f"parameter '{name}' as text"))
                return text
        raise LaunchProblem('NODL510', f"parameter '{name}' is not set (with set_parameter) "
                                       'in this scope')
