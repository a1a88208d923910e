"""The NoDL v2 JSON Schema family, shipped as package data.

``parameter.schema.json``, ``interface.schema.json`` and ``node.schema.json``
are the source of truth for the structure of each kind of document: the
validator interprets them directly, and ``nodl schema KIND`` prints them
(bundled, so that an editor can use one file on its own).
"""

from __future__ import annotations

import copy
import json
import os
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pathlib import Path
    from typing import Any

from nodl.vocabulary import Kind

__all__ = ['KINDS', 'schema_path', 'load_schema', 'bundled_schema']

#: The kinds of NoDL document, each with a schema file (the vocabulary's :class:`Kind`).
KINDS: tuple[str, ...] = tuple(kind.value for kind in Kind)

_HERE = os.path.dirname(os.path.abspath(__file__))


def _file_name(kind: str) -> str:
    if kind not in KINDS:
        raise ValueError(f"unknown schema kind '{kind}'; expected one of: {', '.join(KINDS)}")
    return f'{kind}.schema.json'


def schema_path(kind: str) -> Path:
    """The path of the shipped schema file for ``kind``."""
    return Path(_HERE, _file_name(kind))


@cache
def _load(file_name: str) -> dict[str, Any]:
    with open(os.path.join(_HERE, file_name), encoding='utf-8') as f:
        schema: dict[str, Any] = json.load(f)
    return schema


def load_schema(kind: str) -> dict[str, Any]:
    """The schema for ``kind`` exactly as shipped (a fresh copy)."""
    return copy.deepcopy(_load(_file_name(kind)))


def load_schema_file(file_name: str) -> dict[str, Any]:
    """A shipped schema by file name (shared, do not modify)."""
    return _load(file_name)


def bundled_schema(kind: str) -> dict[str, Any]:
    """The schema for ``kind`` with references to sibling files inlined.

    The result is self-contained: every ``$ref`` points into its own
    ``definitions``, so editors and other validators can use it alone.
    """
    result = load_schema(kind)
    definitions: dict[str, Any] = result.setdefault('definitions', {})
    imported = {_file_name(kind)}
    while True:
        missing = {name for name in _external_files(result) if name not in imported}
        if not missing:
            break
        for file_name in sorted(missing):
            imported.add(file_name)
            for name, definition in copy.deepcopy(_load(file_name)).get('definitions', {}).items():
                definitions.setdefault(name, definition)
    _localize(result)
    return result


def _external_refs(node: Any) -> list[dict[str, Any]]:
    """The objects under ``node`` whose ``$ref`` points into another file."""
    found: list[dict[str, Any]] = []
    stack = [node]
    while stack:
        item = stack.pop()
        if isinstance(item, dict):
            ref = item.get('$ref')
            if isinstance(ref, str) and not ref.startswith('#'):
                found.append(item)
            stack.extend(item.values())
        elif isinstance(item, list):
            stack.extend(item)
    return found


def _external_files(node: Any) -> set[str]:
    return {item['$ref'].partition('#')[0] for item in _external_refs(node)}


def _localize(node: Any) -> None:
    for item in _external_refs(node):
        item['$ref'] = '#' + item['$ref'].partition('#')[2]
