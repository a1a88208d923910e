"""Names from a definition turned into identifiers of a target language, collision-free.

ROS names (``~/cmd_vel``, ``/scan``, ``camera.frame_id``) are not identifiers.
Every generator turns them into identifiers through this module, so the two
languages agree on the shape of a name and on how a collision is broken:

* :func:`snake_case` turns a name into a lowercase identifier fragment:
  every run of characters that are not letters or digits becomes one ``_``,
  ``camelCase`` becomes ``camel_case``, leading and trailing ``_`` go;
* :func:`pascal_case` turns a name into a class name (``laser_driver`` ->
  ``LaserDriver``);
* :class:`IdentifierScope` hands out identifiers within one scope (the members
  of a class, the fields of a struct).  A candidate that is a keyword of the
  language gets a trailing ``_``; one that is already taken (by a reserved
  name or an earlier assignment) gets ``_2``, ``_3``...  Within one
  :meth:`IdentifierScope.assign` call, names already equal to their
  identifier are served first, then the others in sorted order, so the
  result depends only on the set of names and the order of the calls,
  never on the order the names were written in.

Everything here is pure and deterministic: regenerating is byte-identical.
"""

from __future__ import annotations

import keyword
import re
from collections.abc import Iterable, Mapping

__all__ = [
    'CPP_KEYWORDS',
    'PYTHON_KEYWORDS',
    'KEYWORDS',
    'IdentifierScope',
    'snake_case',
    'pascal_case',
    'is_identifier',
]

#: Python's keywords (soft keywords such as ``match`` are valid identifiers) and
#: the names a generated module must not shadow inside a class body.
PYTHON_KEYWORDS: frozenset[str] = frozenset(keyword.kwlist) | frozenset({'self', 'cls'})

#: C++20 keywords and alternative tokens, plus names that would shadow what the
#: generated code uses unqualified.
CPP_KEYWORDS: frozenset[str] = frozenset('''
alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t
char32_t class compl concept const consteval constexpr constinit const_cast continue co_await
co_return co_yield decltype default delete do double dynamic_cast else enum explicit export
extern false float for friend goto if inline int long mutable namespace new noexcept not not_eq
nullptr operator or or_eq private protected public register reinterpret_cast requires return
short signed sizeof static static_assert static_cast struct switch template this thread_local
throw true try typedef typeid typename union unsigned using virtual void volatile wchar_t while
xor xor_eq final override import module std rclcpp NULL
'''.split())  # noqa: SIM905  (a word list reads better as words)

#: Keywords by target language (the ``--language`` values).
KEYWORDS: Mapping[str, frozenset[str]] = {'python': PYTHON_KEYWORDS, 'cpp': CPP_KEYWORDS}

_NOT_ALNUM = re.compile(r'[^0-9A-Za-z]+')
_CAMEL = re.compile(r'(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])')
_IDENTIFIER = re.compile(r'[A-Za-z_][0-9A-Za-z_]*')


def is_identifier(text: str) -> bool:
    """True if ``text`` is an ASCII identifier (valid in Python and C++ alike)."""
    return _IDENTIFIER.fullmatch(text) is not None


def snake_case(name: str) -> str:
    """The lowercase identifier fragment of ``name`` (may start with a digit; never empty).

    ``~/cmd_vel`` -> ``cmd_vel``; ``/robot/laserScan`` -> ``robot_laser_scan``;
    ``camera.frame_id`` -> ``camera_frame_id``; a name with no letter or digit -> ``_``.
    """
    words = [w for w in _NOT_ALNUM.split(name) if w]
    parts = [_CAMEL.sub('_', w).lower() for w in words]
    return '_'.join(parts) or '_'


def pascal_case(name: str) -> str:
    """The class-name form of ``name``: ``laser_driver`` -> ``LaserDriver``, ``3d`` -> ``N3d``.

    A word keeps its inner capitals (``myROSNode`` -> ``MyROSNode``).
    """
    words = [w for w in _NOT_ALNUM.split(name) if w]
    text = ''.join(w[0].upper() + w[1:] for w in words) or 'Node'
    return 'N' + text if text[0].isdigit() else text


class IdentifierScope:
    """One scope of identifiers: hands out collision-free, keyword-free identifiers.

    ``reserved`` are identifiers already in use in the scope (methods of the
    base class, generated helpers); ``keywords`` the target language's
    keywords (:data:`KEYWORDS`).
    """

    def __init__(self, reserved: Iterable[str] = (), keywords: Iterable[str] = PYTHON_KEYWORDS) -> None:
        self.keywords = frozenset(keywords)
        self.taken: set[str] = set(reserved)

    def claim(self, identifier: str) -> None:
        """Mark ``identifier`` as used (it is handed out to no one else)."""
        self.taken.add(identifier)

    def unique(self, candidate: str) -> str:
        """``candidate`` made valid (digit start, keyword) and unused, then claimed."""
        if not candidate or candidate[0].isdigit():
            candidate = '_' + candidate
        if candidate in self.keywords:
            candidate += '_'
        result, n = candidate, 2
        while result in self.taken or result in self.keywords:
            result = f'{candidate}_{n}'
            n += 1
        self.taken.add(result)
        return result

    def assign(self, names: Iterable[str], template: str = '{}') -> dict[str, str]:
        """Map each name to a unique identifier ``template.format(snake_case(name))``.

        The result is ordered by name.  A name whose identifier is the name
        itself wins a collision over one that had to be rewritten; otherwise
        the smaller name (in sorted order) wins and the other gets ``_2``...
        """
        distinct = sorted(set(names))
        plain = [n for n in distinct if template.format(snake_case(n)) == template.format(n)]
        rewritten = [n for n in distinct if n not in plain]
        result = {n: self.unique(template.format(snake_case(n))) for n in plain + rewritten}
        return {n: result[n] for n in distinct}
