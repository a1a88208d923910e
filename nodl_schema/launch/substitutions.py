"""Launch substitutions: the ``$(...)`` syntax of the XML and YAML frontends, and the
substitution objects the Python API builds (``LaunchConfiguration``, ``PathJoinSubstitution``...).

Both spell the same objects: :func:`parse_substitution` turns ``'$(find-pkg-share a)/x'``
into ``[FindPackageShare('a'), Text('/x')]`` following the grammar of
``launch/frontend/grammar.lark`` (quoted arguments, nesting, ``\\`` escapes), and
each object's :meth:`Substitution.perform` computes its text in a
:class:`~nodl_schema.launch.context.LaunchContext` as ``launch`` does.

``$(eval EXPR)`` (``PythonExpression``) evaluates a Python expression with the
names of :mod:`math` available, exactly as ``launch`` does: it is code execution,
as when the launch file is launched; analyse only launch files you would launch.
``$(command ...)`` and ``$(find-exec ...)`` would run or look for programs: they are
not run; their value is reported as known only at run time (NODL513).
"""

from __future__ import annotations

import math
import os
import re

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, Callable, Iterable, Sequence

    from nodl_schema.launch.context import LaunchContext

from nodl_schema.launch.errors import LaunchProblem, Unevaluable

__all__ = [
    'Substitution', 'TextSubstitution', 'LaunchConfiguration', 'EnvironmentVariable',
    'FindPackageShare', 'FindPackagePrefix', 'PythonExpression', 'ThisLaunchFileDir',
    'ThisLaunchFile', 'AnonName', 'NotSubstitution', 'AndSubstitution', 'OrSubstitution',
    'AnySubstitution', 'AllSubstitution', 'EqualsSubstitution', 'NotEqualsSubstitution',
    'IfElseSubstitution', 'PathJoinSubstitution', 'Command', 'FindExecutable', 'FileContent',
    'ExecutableInPackage', 'LaunchLogDir', 'ParameterSubstitution', 'SUBSTITUTIONS',
    'parse_substitution', 'normalize', 'perform', 'to_bool', 'yaml_bool',
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
    out: list[Substitution] = []
    for item in value:
        out.extend(normalize(item))
    return out


def perform(context: LaunchContext, value: Any) -> str:
    """Perform every substitution of ``value`` and join the texts."""
    return ''.join(s.perform(context) for s in normalize(value))


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
        import importlib

        expression = perform(context, self.expression)
        names: dict[str, Any] = {}
        for module_name in self.python_modules:
            module_name = perform(context, module_name) if not isinstance(module_name, str) else module_name
            try:
                module = math if module_name == 'math' else importlib.import_module(module_name)
            except ImportError as exc:
                raise LaunchProblem('NODL510', f"$(eval): cannot import module '{module_name}': {exc}")
            if module.__name__ == 'math':
                names.update(vars(module))
            names[module.__name__] = module
        try:
            return str(eval(expression, {}, names))  # noqa: S307 - what launch itself does
        except Exception as exc:  # any error of the user's expression
            raise LaunchProblem('NODL510', f'$(eval) of {expression!r} failed: '
                                           f'{type(exc).__name__}: {exc}')


class ThisLaunchFileDir(Substitution):
    """``$(dirname)``: the folder of the launch file the substitution is written in."""

    def perform(self, context: LaunchContext) -> str:
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
        return os.path.join(*[perform(context, p) for p in self.parts]) if self.parts else ''

    def __truediv__(self, other: Any) -> 'PathJoinSubstitution':
        joined = PathJoinSubstitution([])
        joined.parts = [*self.parts, normalize(other)]
        return joined


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
        from nodl_schema.frontends.source import MAX_BYTES

        path = perform(context, self.path)
        try:
            with open(path, encoding='utf-8') as stream:
                text = stream.read(MAX_BYTES + 1)
        except (OSError, UnicodeDecodeError) as exc:
            raise LaunchProblem('NODL510', f"$(file-content): cannot read '{path}': {exc}")
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
                return value if isinstance(value, str) else yaml.dump(value).strip().removesuffix('...').strip()
        raise LaunchProblem('NODL510', f"parameter '{name}' is not set (with set_parameter) "
                                       'in this scope')


def _arity(name: str, low: int, high: int | None) -> Callable[[list[list[Substitution]]], None]:
    def check(args: list[list[Substitution]]) -> None:
        if len(args) < low or (high is not None and len(args) > high):
            expected = (f'{low}' if low == high else f'{low} to {high}' if high is not None
                        else f'at least {low}')
            raise LaunchProblem('NODL510', f'$({name}) takes {expected} argument(s), '
                                           f'got {len(args)}')
    return check


def _eval_from_args(args: list[list[Substitution]]) -> Substitution:
    if len(args) == 2:
        modules = ''.join(s.text for s in args[1] if isinstance(s, TextSubstitution))
        return PythonExpression(args[0], [m.strip() for m in modules.split(',') if m.strip()])
    return PythonExpression(args[0])


#: Frontend name -> (argument count (min, max), constructor from the parsed arguments).
SUBSTITUTIONS: dict[str, tuple[int, int | None, Callable[[list[list[Substitution]]], Substitution]]] = {
    'var': (1, 2, lambda a: LaunchConfiguration(a[0], a[1] if len(a) > 1 else None)),
    'env': (1, 2, lambda a: EnvironmentVariable(a[0], default_value=a[1] if len(a) > 1 else None)),
    'find-pkg-share': (1, 1, lambda a: FindPackageShare(a[0])),
    'find-pkg-prefix': (1, 1, lambda a: FindPackagePrefix(a[0])),
    'eval': (1, 2, _eval_from_args),
    'dirname': (0, 0, lambda a: ThisLaunchFileDir()),
    'filename': (0, 0, lambda a: ThisLaunchFile()),
    'anon': (1, 1, lambda a: AnonName(a[0])),
    'not': (1, 1, lambda a: NotSubstitution(a[0])),
    'and': (2, 2, lambda a: AndSubstitution(a[0], a[1])),
    'or': (2, 2, lambda a: OrSubstitution(a[0], a[1])),
    'any': (0, None, lambda a: AnySubstitution(*a)),
    'all': (0, None, lambda a: AllSubstitution(*a)),
    'equals': (2, 2, lambda a: EqualsSubstitution(a[0], a[1])),
    'not-equals': (2, 2, lambda a: NotEqualsSubstitution(a[0], a[1])),
    'if': (2, 3, lambda a: IfElseSubstitution(a[0], a[1], a[2] if len(a) > 2 else '')),
    'command': (1, 2, lambda a: Command(a[0])),
    'find-exec': (1, 1, lambda a: FindExecutable(name=a[0])),
    'file-content': (1, 1, lambda a: FileContent(a[0])),
    'exec-in-pkg': (2, 2, lambda a: ExecutableInPackage(a[0], a[1])),
    'log_dir': (0, 0, lambda a: LaunchLogDir()),
    'launch_log_dir': (0, 0, lambda a: LaunchLogDir()),
    'param': (1, 1, lambda a: ParameterSubstitution(a[0])),
}

_IDENTIFIER = re.compile(r'[A-Za-z][A-Za-z0-9_-]*')
_ESCAPE = re.compile(r'\\(.)', re.S)


def _unescape(text: str) -> str:
    return _ESCAPE.sub(r'\1', text)


class _Parser:
    """A recursive-descent reader of launch's substitution grammar."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.depth = 0

    def fail(self, message: str, at: int) -> LaunchProblem:
        return LaunchProblem('NODL510', f'invalid substitution syntax in {self.text!r} at character '
                                        f'{at + 1}: {message}')

    def template(self, i: int, quote: str | None) -> tuple[list[Substitution], int]:
        """Text and substitutions up to the end (or the closing ``quote``)."""
        out: list[Substitution] = []
        buffer: list[str] = []
        text = self.text
        while i < len(text):
            char = text[i]
            if quote is not None and char == quote:
                break
            if char == '\\' and i + 1 < len(text):
                buffer.append(text[i:i + 2])
                i += 2
                continue
            if char == '$' and text.startswith('$(', i):
                if buffer:
                    out.append(TextSubstitution(_unescape(''.join(buffer))))
                    buffer = []
                sub, i = self.substitution(i, quote)
                out.append(sub)
                continue
            buffer.append(char)
            i += 1
        if buffer:
            out.append(TextSubstitution(_unescape(''.join(buffer))))
        return out, i

    def substitution(self, i: int, quote: str | None) -> tuple[Substitution, int]:
        start = i
        self.depth += 1
        if self.depth > 50:
            raise self.fail('substitutions nest deeper than 50 levels', start)
        i += 2
        match = _IDENTIFIER.match(self.text, i)
        if match is None:
            raise self.fail("expected a substitution name after '$('", i)
        name = match.group()
        i = match.end()
        args: list[list[Substitution]] = []
        while i < len(self.text) and self.text[i] == ' ':
            while i < len(self.text) and self.text[i] == ' ':
                i += 1
            if i < len(self.text) and self.text[i] == ')':
                break
            value, i = self.value(i, quote)
            args.append(value)
        if i >= len(self.text) or self.text[i] != ')':
            raise self.fail(f"'$({name}' is not closed with ')'", start)
        self.depth -= 1
        return self.instantiate(name, args), i + 1

    def value(self, i: int, quote: str | None) -> tuple[list[Substitution], int]:
        text = self.text
        if quote is None and i < len(text) and text[i] in '\'"':
            q = text[i]
            parts, j = self.template(i + 1, q)
            if j >= len(text) or text[j] != q:
                raise self.fail(f'unterminated {q}-quoted argument', i)
            return parts, j + 1
        out: list[Substitution] = []
        buffer: list[str] = []
        stop = ' ()' + ('\'"' if quote is None else quote)
        while i < len(text):
            char = text[i]
            if char == '\\' and i + 1 < len(text):
                buffer.append(text[i:i + 2])
                i += 2
                continue
            if char == '$' and text.startswith('$(', i):
                if buffer:
                    out.append(TextSubstitution(_unescape(''.join(buffer))))
                    buffer = []
                sub, i = self.substitution(i, quote)
                out.append(sub)
                continue
            if char in stop:
                break
            buffer.append(char)
            i += 1
        if buffer:
            out.append(TextSubstitution(_unescape(''.join(buffer))))
        if not out:
            raise self.fail('expected an argument', i)
        return out, i

    def instantiate(self, name: str, args: list[list[Substitution]]) -> Substitution:
        entry = SUBSTITUTIONS.get(name)
        if entry is None:
            from nodl_schema.validation.messages import did_you_mean

            raise LaunchProblem('NODL509', f"unknown substitution '$({name})'"
                                           f'{did_you_mean(name, SUBSTITUTIONS)}; known: '
                                           f'{", ".join(sorted(SUBSTITUTIONS))}')
        low, high, make = entry
        _arity(name, low, high)(args)
        return make(args)


def parse_substitution(text: str) -> list[Substitution]:
    """Parse launch's ``$(...)`` syntax (raises :class:`LaunchProblem` for bad syntax)."""
    if not text:
        return [TextSubstitution('')]
    if '$(' not in text:
        return [TextSubstitution(_unescape(text))]
    parts, _ = _Parser(text).template(0, None)
    return parts


def parse_if_substitutions(value: Any) -> Any:
    """Strings become substitutions (or stay text when they hold none); other scalars stay."""
    def one(item: Any) -> Any:
        if isinstance(item, str):
            parts = parse_substitution(item)
            if len(parts) == 1 and isinstance(parts[0], TextSubstitution):
                return parts[0].text
            return parts
        return item
    if isinstance(value, list):
        return [one(v) for v in value]
    return one(value)


def describe_all(values: Iterable[Substitution] | Sequence[Substitution]) -> str:
    """A short text for a list of substitutions."""
    return ' + '.join(v.describe() for v in values)
