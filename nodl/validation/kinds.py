"""The three kinds of NoDL document, and how a document's kind is detected."""

from __future__ import annotations

from typing import TYPE_CHECKING

from nodl.vocabulary import INCLUDE_KEYS, INTERFACE_KEYS, NODE_KEYS, Kind

if TYPE_CHECKING:
    from typing import Any

__all__ = ['Kind', 'detect_kind', 'KIND_REASONS', 'NODE_KEYS', 'INTERFACE_KEYS', 'INCLUDE_KEYS']


#: Why :func:`detect_kind` decides on each kind, for messages.
KIND_REASONS = {
    Kind.PARAMETER: 'it has no nodl_version',
    Kind.INTERFACE: 'it has nodl_version and no base, main or mixins',
    Kind.NODE: 'it has base, main or mixins',
}


def detect_kind(data: Any) -> Kind:
    """Which kind of document ``data`` is, as spec 004 and the reference implementation decide.

    A document with ``nodl_version`` is a node definition if it has any of
    ``base``, ``main`` or ``mixins`` (or the ``include`` dialect's
    :data:`INCLUDE_KEYS`), else an interface definition.  A
    document without ``nodl_version`` is a parameter definition -- unless it
    plainly is an interface or node definition that forgot its version (it
    has no ``type`` but has their keys), so that the diagnostic says
    "missing nodl_version" rather than "unknown key publishers".
    """
    if not isinstance(data, dict):
        # Not a mapping at all (the frontend reports that); the default kind.
        return Kind.PARAMETER
    if 'nodl_version' in data or 'type' not in data:
        if any(key in data for key in NODE_KEYS) or any(key in data for key in INCLUDE_KEYS):
            return Kind.NODE
        if 'nodl_version' in data or any(key in data for key in INTERFACE_KEYS):
            return Kind.INTERFACE
    return Kind.PARAMETER
