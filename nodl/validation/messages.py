"""Wording shared by the checks: how values, types and suggestions are said."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import Any

from nodl.diagnostics import DocPath

__all__ = ['show', 'kind_of', 'described', 'did_you_mean', 'close_matches', 'subject', 'one_of']


def show(value: Any, limit: int = 40) -> str:
    """A short rendering of a value as a user wrote it."""
    if isinstance(value, str):
        if not value.isprintable():
            # A diagnostic is one line: show control characters escaped.
            value = ''.join(c if c.isprintable() else repr(c)[1:-1] for c in value)
        text = f"'{value}'"
    elif value is None:
        text = 'null'
    elif isinstance(value, bool):
        text = 'true' if value else 'false'
    elif isinstance(value, dict):
        text = 'a mapping'
    else:
        text = str(value)
    return text if len(text) <= limit else text[:limit - 3] + '...'


def article(word: object) -> str:
    """``word`` with its indefinite article: 'an int', 'a string', 'an interface'."""
    text = str(word)
    return f"{'an' if text[:1] in 'aeiou' else 'a'} {text}"


def kind_of(value: Any) -> str:
    """The YAML/JSON kind of a value, with an article."""
    if value is None:
        return 'null'
    if isinstance(value, bool):
        return 'a boolean'
    if isinstance(value, int):
        return 'an integer'
    if isinstance(value, float):
        return 'a number'
    if isinstance(value, str):
        return 'a string'
    if isinstance(value, list):
        return 'a list'
    if isinstance(value, dict):
        return 'a mapping'
    return type(value).__name__


def described(value: Any) -> str:
    """The kind of a value and the value: ``a string ('x')``; ``a mapping`` and ``null`` alone."""
    if value is None or isinstance(value, dict):
        return kind_of(value)
    return f'{kind_of(value)} ({show(value)})'


def close_matches(word: str, candidates: Iterable[str], *, most: int = 1) -> list[str]:
    """The candidates close to ``word``, best first, at most ``most``.

    The same word in another case first; for a ROS name (holding ``/``), the
    candidates with its last segment (``/b/scan`` for ``/a/scan``); else
    difflib's closest (ratio 0.6 or more).
    """
    options = list(candidates)
    lowered = {c.lower(): c for c in options}
    if word.lower() in lowered:
        return [lowered[word.lower()]]
    if '/' in word:
        last = word.rpartition('/')[2]
        same_last = [c for c in options if c.rpartition('/')[2] == last]
        if same_last:
            return same_last[:most]
    import difflib  # only when a suggestion is needed: it costs start-up time

    return difflib.get_close_matches(word, options, n=most, cutoff=0.6)


def did_you_mean(word: Any, candidates: Iterable[str], *, most: int = 1,
                 aside: bool = False) -> str:
    """``"; did you mean 'x'?"`` when candidates are close to ``word`` (:func:`close_matches`),
    else ``''``; with ``aside``, ``" (did you mean 'x' or 'y'?)"`` for the middle of a sentence."""
    if not isinstance(word, str):
        return ''
    close = close_matches(word, candidates, most=most)
    if not close:
        return ''
    question = 'did you mean ' + ' or '.join(f"'{c}'" for c in close) + '?'
    return f' ({question})' if aside else f'; {question}'


def one_of(options: Iterable[Any]) -> str:
    """``"a, b or c"`` for a message."""
    items = [str(o) for o in options]
    if len(items) <= 1:
        return ''.join(items)
    return ', '.join(items[:-1]) + ' or ' + items[-1]


def subject(path: DocPath) -> str:
    """What a path points at, for a message: its last key (``history``)."""
    if path and isinstance(path[-1], int):
        for part in reversed(path):
            if isinstance(part, str):
                return f'item {path[-1]} of {show(part)}'
    for part in reversed(path):
        if isinstance(part, str):
            return show(part)
    return 'the document'
