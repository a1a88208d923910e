"""Packages that ship only legacy (XML) NoDL files.

Until the legacy frontend lands this finds nothing; it keeps the look-up
code in one place.
"""

from __future__ import annotations

from nodl_schema.index.registry import Registration

__all__ = ['legacy_registrations']


def legacy_registrations(package: str | None, prefixes: list[str]) -> list[Registration]:
    """Legacy node definitions found through ``nodl_desc`` markers and package.xml exports."""
    return []
