"""Wording shared by the whole toolkit: how values, kinds and suggestions are said.

One "did you mean" (:func:`did_you_mean`, :func:`close_matches`) for every
message that suggests a name: keys, codes, parameters, interface types, nodes.
It sits at the bottom of the layers (it imports nothing of the toolkit), so
that the catalogue of codes and the configuration can use it as well as the
validation, the frontends, the launch interpreter and the live layer.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

__all__ = ['show', 'article', 'kind_of', 'described', 'did_you_mean', 'close_matches', 'subject', 'one_of']


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


def close_matches(word: str, candidates: Iterable[str], *, most: int = 1, cutoff: float = 0.6,
                  prefix: bool = False) -> list[str]:
    """The candidates close to ``word``, best first, at most ``most``.

    The same word in another case first; with ``prefix``, the candidates
    ``word`` begins (``NODL21`` names ``NODL210``...), then those spelled
    alike; for a ROS name (holding ``/``), the candidates with its last
    segment (``/b/scan`` for ``/a/scan``); else difflib's closest (ratio
    ``cutoff`` or more).
    """
    options = list(candidates)
    lowered = {c.lower(): c for c in options}
    if word.lower() in lowered:
        return [lowered[word.lower()]]
    import difflib  # only when a suggestion is needed: it costs start-up time

    if prefix:
        starting = [c for c in options if c.startswith(word)]
        alike = difflib.get_close_matches(word, options, n=most, cutoff=cutoff)
        return (starting + [c for c in alike if c not in starting])[:most]
    if '/' in word:
        last = word.rpartition('/')[2]
        same_last = [c for c in options if c.rpartition('/')[2] == last]
        if same_last:
            return same_last[:most]
    return difflib.get_close_matches(word, options, n=most, cutoff=cutoff)


def did_you_mean(word: Any, candidates: Iterable[str], *, most: int = 1, cutoff: float = 0.6,
                 aside: bool = False) -> str:
    """``"; did you mean 'x'?"`` when candidates are close to ``word`` (:func:`close_matches`),
    else ``''``; with ``aside``, ``" (did you mean 'x' or 'y'?)"`` for the middle of a sentence."""
    if not isinstance(word, str):
        return ''
    close = close_matches(word, candidates, most=most, cutoff=cutoff)
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


def subject(path: Sequence[str | int]) -> str:
    """What a path in a document (a :data:`nodl.diagnostics.DocPath`) points at, for a
    message: its last key (``history``)."""
    if path and isinstance(path[-1], int):
        for part in reversed(path):
            if isinstance(part, str):
                return f'item {path[-1]} of {show(part)}'
    for part in reversed(path):
        if isinstance(part, str):
            return show(part)
    return 'the document'
