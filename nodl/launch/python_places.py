"""Where the arguments of a call in a Python launch file are written.

A Python launch file's actions know the line of their call (``Node(...)``); a finding
about one remapping rule of it should point at that rule.  :func:`keyword_places` reads
the file's syntax tree (parsed once per file version) and returns, for a keyword argument
of the call at a place, where each item of its list is written (a literal list or tuple,
also through a variable assigned once, ``*other`` and ``+``: a rule written once and given
to many nodes through ``remappings=common`` is at one place), or where the argument is
(any other expression).
"""

from __future__ import annotations

import ast
import os
from functools import lru_cache
from types import CodeType
from typing import Any

from nodl.launch.model import SourceLocation

__all__ = ['keyword_places', 'frame_location']

_TREES: dict[tuple[str, float, int], tuple[dict[tuple[int, int], ast.Call], ast.Module]] = {}
#: What :func:`_scope_of` and :func:`_bound` read from a tree, found once per tree (a launch
#: file that makes twenty nodes asks twenty times): by ``id`` of the tree, which the entry keeps.
_FOUND: dict[int, tuple[ast.Module, dict[Any, Any]]] = {}


def _parsed(path: str) -> tuple[dict[tuple[int, int], ast.Call], ast.Module]:
    """Every call of the file by its (line, column) (1-based), and the file's tree, parsed
    once per version."""
    try:
        stat = os.stat(path)
    except OSError:
        return {}, ast.Module(body=[], type_ignores=[])
    key = (path, stat.st_mtime, stat.st_size)
    found = _TREES.get(key)
    if found is None:
        try:
            with open(path, 'rb') as stream:
                tree = ast.parse(stream.read(), path)
        except (OSError, SyntaxError, ValueError):
            tree = ast.Module(body=[], type_ignores=[])
        calls = {(n.lineno, n.col_offset + 1): n for n in ast.walk(tree) if isinstance(n, ast.Call)}
        if len(_TREES) > 256:
            _TREES.clear()
            _FOUND.clear()
        found = _TREES[key] = (calls, tree)
    return found


def _memo(tree: ast.Module) -> dict[Any, Any]:
    """The findings kept for ``tree`` (see :data:`_FOUND`)."""
    entry = _FOUND.get(id(tree))
    if entry is None or entry[0] is not tree:
        if len(_FOUND) > 256:
            _FOUND.clear()
        entry = _FOUND[id(tree)] = (tree, {})
    return entry[1]


def _calls(path: str) -> dict[tuple[int, int], ast.Call]:
    return _parsed(path)[0]


_SCOPES = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)


def _scope_of(tree: ast.Module, line: int) -> ast.AST:
    """The innermost function whose lines hold ``line`` (the module if none does)."""
    memo = _memo(tree)
    scopes = memo.get('scopes')
    if scopes is None:  # (in ast.walk's order, as the choice below depends on it)
        scopes = memo['scopes'] = [node for node in ast.walk(tree) if isinstance(node, _SCOPES)]
    scope: ast.AST = tree
    for node in scopes:
        if node.lineno <= line <= (node.end_lineno or node.lineno) and (
                scope is tree or node.lineno >= getattr(scope, 'lineno', 0)):
            scope = node
    return scope


def _bound(tree: ast.Module, scope: ast.AST, name: str) -> ast.expr | None:
    """The value ``name`` is bound to in ``scope`` (else in the module) when it is assigned
    exactly once there (``common = [...]``); None when that is not plain to see."""
    if isinstance(scope, _SCOPES) and name in {a.arg for a in (
            *scope.args.posonlyargs, *scope.args.args, *scope.args.kwonlyargs,
            *(x for x in (scope.args.vararg, scope.args.kwarg) if x is not None))}:
        return None  # a parameter: its value is the caller's
    memo = _memo(tree)
    for where in (scope, tree) if scope is not tree else (tree,):
        assigned = memo.get(id(where))
        if assigned is None:
            assigned = memo[id(where)] = _assignments(where)
        values = assigned.get(name)
        if values:
            return values[0] if len(values) == 1 else None
    return None


_UNCLEAR = ast.Constant(None)  # a value that is not plain to see: no places are read from it


def _assignments(where: ast.AST) -> dict[str, list[ast.expr]]:
    """The values each name is bound to by the statements of ``where`` (a function, or the
    module), outside the functions and classes they define: a name assigned together with
    another target, annotated or changed is bound to a value that is not plain to see."""
    out: dict[str, list[ast.expr]] = {}
    body = where.body if isinstance(where, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef)) else []
    for node in (n for statement in body for n in _own_nodes(statement)):
        if isinstance(node, ast.Assign):
            value = node.value if len(node.targets) == 1 else _UNCLEAR
            for name in {t.id for t in node.targets if isinstance(t, ast.Name)}:
                out.setdefault(name, []).append(value)
        elif isinstance(node, (ast.AnnAssign, ast.AugAssign)) and isinstance(node.target, ast.Name):
            out.setdefault(node.target.id, []).append(_UNCLEAR)  # annotated or changed
    return out


def _own_nodes(statement: ast.stmt) -> list[ast.AST]:
    """The nodes of ``statement`` outside the functions and classes it defines."""
    out: list[ast.AST] = []
    todo: list[ast.AST] = [statement]
    while todo:
        node = todo.pop()
        out.append(node)
        todo.extend(c for c in ast.iter_child_nodes(node)
                    if not isinstance(c, (*_SCOPES, ast.ClassDef)))
    return out


def _item_places(file: str, tree: ast.Module, scope: ast.AST, value: ast.expr,
                 depth: int = 0) -> list[SourceLocation] | None:
    """Where each item of the list ``value`` stands for is written: the items of a list or
    tuple written out, through ``*other`` items, ``a + b`` and a variable assigned once
    (``remappings=common``, ``common = [...]`` above); None when that is not plain to see."""
    if depth > 20:
        return None
    if isinstance(value, (ast.List, ast.Tuple)):
        out: list[SourceLocation] = []
        for element in value.elts:
            if isinstance(element, ast.Starred):
                inner = _item_places(file, tree, scope, element.value, depth + 1)
                if inner is None:
                    return None
                out += inner
            else:
                out.append(SourceLocation(file, element.lineno, element.col_offset + 1))
        return out
    if isinstance(value, ast.BinOp) and isinstance(value.op, ast.Add):
        left = _item_places(file, tree, scope, value.left, depth + 1)
        right = _item_places(file, tree, scope, value.right, depth + 1)
        return None if left is None or right is None else left + right
    if isinstance(value, ast.Name):
        bound = _bound(tree, scope, value.id)
        if bound is None:
            return None
        return _item_places(file, tree, scope if _in(scope, bound) else tree, bound, depth + 1)
    return None


def _in(scope: ast.AST, node: ast.AST) -> bool:
    return isinstance(scope, _SCOPES) and scope.lineno <= getattr(node, 'lineno', 0) <= (
        scope.end_lineno or scope.lineno)


def keyword_places(call: SourceLocation, keyword: str) -> list[SourceLocation] | SourceLocation | None:
    """For the call written at ``call``: the places of the items of its ``keyword`` argument
    (a list or tuple written out), else the argument's place, else None (no such call or
    keyword)."""
    calls, tree = _parsed(call.file) if call.line else ({}, None)
    node = calls.get((call.line, call.column))
    if node is None or tree is None:
        return None
    for item in node.keywords:
        if item.arg != keyword:
            continue
        value = item.value
        places = _item_places(call.file, tree, _scope_of(tree, call.line), value)
        if places is not None:
            return places
        return SourceLocation(call.file, value.lineno, value.col_offset + 1)
    return None


def frame_location(path: str, frame: Any) -> SourceLocation:
    """Where the innermost frame of the launch file ``path`` from ``frame`` outwards is (its
    line, and its column where the interpreter records one); line 0 if none is."""
    while frame is not None:
        if frame.f_code.co_filename == path:
            columns = _columns(frame.f_code)
            index = frame.f_lasti // 2
            return SourceLocation(path, frame.f_lineno, columns[index] if index < len(columns) else 1)
        frame = frame.f_back
    return SourceLocation(path, 0, 0)


@lru_cache(maxsize=256)  # every action of a launch file asks its code object (thousands of instructions)
def _columns(code: CodeType) -> tuple[int, ...]:
    """The 1-based column of each instruction of ``code`` (1 where none is recorded)."""
    positions = getattr(code, 'co_positions', None)  # (Python 3.11)
    if positions is None:
        return ()
    return tuple((start or 0) + 1 for _, _, start, _ in positions())
