"""Python source text: literals, docstrings, comments and the built-in validators as expressions.

The pieces the Python generator writes that must be exact: a value from a
definition as a Python literal (deterministic, ``repr`` based), a
description as an escaped docstring or comment, and each built-in validator
of the validator table as a Python expression over ``v`` (the translation the
generated code carries, because it must not import the toolkit; the tests
keep each expression in agreement with the table's predicate).
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Callable
from typing import Any

from nodl.text_safety import python_escapes, visible

__all__ = ['literal', 'docstring', 'comment', 'VALIDATOR_EXPRESSIONS', 'validator_expression',
           'python_value', 'LINE_LENGTH', 'mark_long_lines']

#: The longest line generated code may have: ament_flake8's limit (the lint test ``nodl new`` and
#: ``ros2 pkg create`` add to an ament_python package runs it on every file, generated ones too).
LINE_LENGTH = 99


def python_value(value: Any, base: str) -> Any:
    """A definition's value as the Python value rclpy expects for a parameter of type ``base``.

    Doubles become floats (``1`` -> ``1.0``); a byte array becomes a list of one-byte ``bytes``.
    """
    if base == 'double':
        return float(value)
    if base == 'double_array':
        return [float(v) for v in value]
    if base == 'byte_array':
        return [bytes([v]) for v in value]
    return value


def literal(value: Any) -> str:
    """``value`` as a Python literal (lists, strings, numbers, bools, bytes, None)."""
    if isinstance(value, (list, tuple)):
        inner = ', '.join(literal(v) for v in value)
        return f'[{inner}]' if isinstance(value, list) else f'({inner}{"," if len(value) == 1 else ""})'
    if isinstance(value, float):
        text = repr(value)
        return text if text not in ('inf', '-inf', 'nan') else f"float('{text}')"
    return repr(value)


def docstring(text: str, indent: str = '') -> str:
    """``text`` as a docstring, its lines within :data:`LINE_LENGTH` with the quotes (a word
    longer than a line stays whole).

    As ament_pep257 and ament_flake8 (pydocstyle) want it: a multi-line docstring
    starts on the line after the quotes (D213), and a backslash, or a quote that
    would end the docstring, is written as a ``\\u`` escape (any other backslash
    escape is D301), so the value is ``text`` exactly; a text that holds three
    double quotes is quoted with three single ones (D300).  Callers make the first
    paragraph a one-line summary ending with a period (D205, D400).
    """
    width = max(40, LINE_LENGTH - len(indent) - 7)  # the quotes, and an escaped closing quote
    quote = "'" if '"""' in text.strip() else '"'
    code = '\\u0027' if quote == "'" else '\\u0022'
    escaped = text.strip().replace('\\', '\\u005c').replace(quote * 3, quote * 2 + code)
    # control and bidi characters and the line separators too (see nodl.text_safety)
    escaped = python_escapes(escaped)
    paragraphs = [textwrap.fill(p, width, break_long_words=False, break_on_hyphens=False)
                  for p in escaped.split('\n\n')]
    body = '\n\n'.join(paragraphs)
    if body.endswith(quote):
        body = body[:-1] + code
    lines = body.splitlines() or ['']
    if len(lines) == 1:
        return f'{indent}{quote * 3}{lines[0]}{quote * 3}\n'
    out = f'{indent}{quote * 3}\n'
    for line in lines:
        out += f'{indent}{line.rstrip()}\n' if line.strip() else '\n'
    return out + f'{indent}{quote * 3}\n'


#: A string literal or comment start, as Python's tokenizer reads them: a triple quote opens a
#: string that may span lines; one-line strings and comments are skipped whole.
_PREFIX = '[rRbBuUfF]{0,2}'
_LEXEME = re.compile(
    _PREFIX + '("""|\'\'\')'                      # a triple quote: group 1
    + '|' + _PREFIX + r"'(?:\\.|[^'\\\n])*'"          # a one-line '...' string
    + '|' + _PREFIX + r'"(?:\\.|[^"\\\n])*"'          # a one-line "..." string
    + '|#[^\n]*')                                  # a comment
_CLOSE = {q: re.compile(r'(?:\\.|[^\\])*?' + q, re.S) for q in ('"""', "'''")}


def multiline_string_lines(text: str) -> set[int]:
    """The numbers of the lines (1-based) that a multi-line string literal of ``text`` continues
    past: its text, not code (a regular-expression scan, much faster than :mod:`tokenize`)."""
    inside: set[int] = set()
    pos = 0
    while True:
        match = _LEXEME.search(text, pos)
        if match is None:
            return inside
        pos = match.end()
        quote = match.group(1)
        if quote is None:
            continue
        close = _CLOSE[quote].match(text, pos)
        end = close.end() if close is not None else len(text)
        first = text.count('\n', 0, match.start()) + 1
        inside.update(range(first, first + text.count('\n', match.start(), end)))
        pos = end


def mark_long_lines(text: str) -> str:
    """``text`` (Python source) with ``  # noqa: E501`` after each line longer than
    :data:`LINE_LENGTH` that is not inside a string: lines that hold data from a definition
    (a long name, a long list of choices) and cannot be broken without changing what they say."""
    lines = text.split('\n')
    long = [n for n, line in enumerate(lines, 1) if len(line) > LINE_LENGTH]
    if not long:
        return text
    inside = multiline_string_lines(text)
    for number in long:
        if number not in inside:
            lines[number - 1] += '  # noqa: E501'
    return '\n'.join(lines)


def comment(text: str, indent: str = '') -> str:
    """``text`` as comment lines (each line prefixed with ``# ``); control and bidi characters
    are written as visible escapes (a comment has no escapes of its own)."""
    return ''.join(f'{indent}# {visible(line)}'.rstrip() + '\n'
                   for line in (text.strip().splitlines() or ['']))


def _bounds(a: Any) -> str:
    return f'{literal(a[0])} <= v <= {literal(a[1])}'


def _choices(a: Any) -> str:
    return literal(tuple(a))


#: Built-in validator name -> its Python expression over ``v`` for the normalized argument.
VALIDATOR_EXPRESSIONS: dict[str, Callable[[Any], str]] = {
    'bounds': _bounds,
    'lt': lambda a: f'v < {literal(a)}',
    'gt': lambda a: f'v > {literal(a)}',
    'lt_eq': lambda a: f'v <= {literal(a)}',
    'gt_eq': lambda a: f'v >= {literal(a)}',
    # equal and both bools or both not (the table's rule: 1 is not True, 1 is 1.0)
    'one_of': lambda a: f'any(v == x and isinstance(v, bool) is isinstance(x, bool) for x in {_choices(a)})',
    'not_empty': lambda a: 'len(v) > 0',
    'fixed_size': lambda a: f'len(v) == {literal(a)}',
    'size_gt': lambda a: f'len(v) > {literal(a)}',
    'size_lt': lambda a: f'len(v) < {literal(a)}',
    'unique': lambda a: 'len(set(v)) == len(v)',
    'subset_of': lambda a: f'all(x in {_choices(a)} for x in v)',
    'element_bounds': lambda a: f'all({literal(a[0])} <= x <= {literal(a[1])} for x in v)',
    'lower_element_bounds': lambda a: f'all(x >= {literal(a)} for x in v)',
    'upper_element_bounds': lambda a: f'all(x <= {literal(a)} for x in v)',
}


def validator_expression(name: str, argument: Any) -> str:
    """The Python expression over ``v`` that is true when the built-in ``name`` accepts ``v``."""
    return VALIDATOR_EXPRESSIONS[name](argument)
