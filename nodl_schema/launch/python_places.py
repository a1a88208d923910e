"""Where the arguments of a call in a Python launch file are written.

A Python launch file's actions know the line of their call (``Node(...)``); a finding
about one remapping rule of it should point at that rule.  :func:`keyword_places` reads
the file's syntax tree (parsed once per file version) and returns, for a keyword argument
of the call at a place, where each item of its list is written (a literal list or tuple),
or where the argument is (any other expression).
"""

from __future__ import annotations

import ast
import os
from typing import Any

from nodl_schema.launch.model import SourceLocation

__all__ = ['keyword_places', 'frame_location']

_TREES: dict[tuple[str, float, int], dict[tuple[int, int], ast.Call]] = {}


def _calls(path: str) -> dict[tuple[int, int], ast.Call]:
    """Every call of the file by its (line, column) (1-based), parsed once per version."""
    try:
        stat = os.stat(path)
    except OSError:
        return {}
    key = (path, stat.st_mtime, stat.st_size)
    found = _TREES.get(key)
    if found is None:
        try:
            with open(path, 'rb') as stream:
                tree = ast.parse(stream.read(), path)
        except (OSError, SyntaxError, ValueError):
            tree = ast.Module(body=[], type_ignores=[])
        found = {(n.lineno, n.col_offset + 1): n for n in ast.walk(tree) if isinstance(n, ast.Call)}
        if len(_TREES) > 256:
            _TREES.clear()
        _TREES[key] = found
    return found


def keyword_places(call: SourceLocation, keyword: str) -> list[SourceLocation] | SourceLocation | None:
    """For the call written at ``call``: the places of the items of its ``keyword`` argument
    (a list or tuple written out), else the argument's place, else None (no such call or
    keyword)."""
    node = _calls(call.file).get((call.line, call.column)) if call.line else None
    if node is None:
        return None
    for item in node.keywords:
        if item.arg != keyword:
            continue
        value = item.value
        if isinstance(value, (ast.List, ast.Tuple)) and not any(isinstance(e, ast.Starred) for e in value.elts):
            return [SourceLocation(call.file, e.lineno, e.col_offset + 1) for e in value.elts]
        return SourceLocation(call.file, value.lineno, value.col_offset + 1)
    return None


def frame_location(path: str, frame: Any) -> SourceLocation:
    """Where the innermost frame of the launch file ``path`` from ``frame`` outwards is (its
    line, and its column where the interpreter records one); line 0 if none is."""
    while frame is not None:
        if frame.f_code.co_filename == path:
            column = 1
            try:
                positions = list(frame.f_code.co_positions())[frame.f_lasti // 2]
                column = (positions[2] or 0) + 1
            except (AttributeError, IndexError):
                pass
            return SourceLocation(path, frame.f_lineno, column)
        frame = frame.f_back
    return SourceLocation(path, 0, 0)
