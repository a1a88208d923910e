"""The ``$(...)`` substitution syntax of the XML and YAML launch frontends.

:func:`parse_substitution` turns ``'$(find-pkg-share a)/x'`` into
``[FindPackageShare('a'), TextSubstitution('/x')]`` following the grammar of
``launch/frontend/grammar.lark``: arguments separated by spaces, quoted arguments
(``'...'``, ``"..."``), nesting, ``\\`` escapes.  :data:`SUBSTITUTIONS` is the one table
of substitution names, their argument counts and the objects they build.  Bad syntax and
unknown names raise :class:`~nodl.launch.errors.LaunchProblem` (NODL510, NODL509)
with the character position.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable, Sequence
    from typing import Any

from nodl.launch.errors import LaunchProblem
from nodl.launch.substitutions import (
    AllSubstitution,
    AndSubstitution,
    AnonName,
    AnySubstitution,
    Command,
    EnvironmentVariable,
    EqualsSubstitution,
    ExecutableInPackage,
    FileContent,
    FindExecutable,
    FindPackagePrefix,
    FindPackageShare,
    IfElseSubstitution,
    LaunchConfiguration,
    LaunchLogDir,
    NotEqualsSubstitution,
    NotSubstitution,
    OrSubstitution,
    ParameterSubstitution,
    PythonExpression,
    Substitution,
    TextSubstitution,
    ThisLaunchFile,
    ThisLaunchFileDir,
)

__all__ = ['SUBSTITUTIONS', 'parse_substitution', 'parse_if_substitutions', 'describe_all']


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
    return _ESCAPE.sub(r'\1', text) if '\\' in text else text  # most text has no escape


#: Runs of characters that are text whatever follows, outside quotes and inside each quote
#: (what is not a backslash, a ``$`` or the closing quote).
_ORDINARY = {None: re.compile(r'[^\\$]+'), "'": re.compile(r"[^\\$']+"), '"': re.compile(r'[^\\$"]+')}
#: What ends a substitution's argument (by the quote the substitution stands in): a space, a
#: parenthesis or a quote; and the runs of characters with no meaning there.
_ARGUMENT_STOP = {None: ' ()\'"', "'": " ()'", '"': ' ()"'}
_ARGUMENT_ORDINARY = {quote: re.compile('[^\\\\$' + re.escape(stop) + ']+') for quote, stop in _ARGUMENT_STOP.items()}


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
        return self.pieces(i, quote, _ORDINARY[quote], quote or '')

    def pieces(self, i: int, quote: str | None, ordinary: re.Pattern[str],
               stop: str) -> tuple[list[Substitution], int]:
        """Text (escapes kept until a piece ends) and substitutions from ``i`` up to the end
        or the first character of ``stop``; ``ordinary`` matches a run of characters with no
        meaning here."""
        out: list[Substitution] = []
        buffer: list[str] = []
        text = self.text
        while i < len(text):
            run = ordinary.match(text, i)  # (a run of characters with no meaning here, at once)
            if run is not None:
                buffer.append(run.group())
                i = run.end()
                continue
            char = text[i]
            if char in stop:
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
        out, i = self.pieces(i, quote, _ARGUMENT_ORDINARY[quote], _ARGUMENT_STOP[quote])
        if not out:
            raise self.fail('expected an argument', i)
        return out, i

    def instantiate(self, name: str, args: list[list[Substitution]]) -> Substitution:
        entry = SUBSTITUTIONS.get(name)
        if entry is None:
            from nodl.wording import did_you_mean

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
