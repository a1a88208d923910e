"""A small reader of the ament resource index.

The index is a folder tree under each prefix of ``AMENT_PREFIX_PATH``:
``<prefix>/share/ament_index/resource_index/<type>/<name>``, whose content is
free text chosen by the resource type.  The first prefix that has a resource
wins, as with ``ament_index_python``.  Reading it needs no ROS package.
"""

from __future__ import annotations

import os
from typing import NamedTuple

__all__ = ['Resource', 'prefix_paths', 'get_resource', 'get_resources', 'package_share_directory',
           'resource_file']

_INDEX = os.path.join('share', 'ament_index', 'resource_index')


class Resource(NamedTuple):
    """One resource: its content and the prefix it was found in."""

    content: str
    prefix: str
    path: str


def prefix_paths(environ: dict[str, str] | None = None) -> list[str]:
    """The prefixes of ``AMENT_PREFIX_PATH``, in order, without duplicates."""
    value = (environ if environ is not None else os.environ).get('AMENT_PREFIX_PATH', '')
    seen: list[str] = []
    for part in value.split(os.pathsep):
        if part and part not in seen:
            seen.append(part)
    return seen


def resource_file(prefix: str, resource_type: str, name: str) -> str:
    """Where a resource lives (or would live) under ``prefix``."""
    return os.path.join(prefix, _INDEX, resource_type, name)


def get_resource(resource_type: str, name: str,
                 prefixes: list[str] | None = None) -> Resource | None:
    """The first resource ``resource_type/name`` found, or None."""
    for prefix in prefixes if prefixes is not None else prefix_paths():
        path = resource_file(prefix, resource_type, name)
        if os.path.isfile(path):
            with open(path, encoding='utf-8') as f:
                return Resource(f.read(), prefix, path)
    return None


def get_resources(resource_type: str, prefixes: list[str] | None = None) -> dict[str, str]:
    """Every resource name of ``resource_type`` -> the prefix it is found in (first wins)."""
    found: dict[str, str] = {}
    for prefix in prefixes if prefixes is not None else prefix_paths():
        folder = os.path.join(prefix, _INDEX, resource_type)
        try:
            names = sorted(os.listdir(folder))
        except OSError:
            continue
        for name in names:
            if not name.startswith('.') and os.path.isfile(os.path.join(folder, name)):
                found.setdefault(name, prefix)
    return found


def package_share_directory(package: str, prefixes: list[str] | None = None) -> str | None:
    """``<prefix>/share/<package>`` of a package in the index, or None."""
    resource = get_resource('packages', package, prefixes)
    return os.path.join(resource.prefix, 'share', package) if resource else None
