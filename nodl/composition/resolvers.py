"""Mixin references and the resolvers that turn them into documents.

A reference is ``<scheme>://...`` or a path relative to the node file (the
``file`` scheme).  Each scheme has a resolver, registered as an entry point
in the ``nodl.resolvers`` group (name = scheme); the built-in ``nodl`` and
``file`` resolvers are registered the same way as third-party ones.

A resolver returns the text of an interface definition and where it came
from, or raises :class:`ResolutionError` saying what it searched.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from typing import NamedTuple, Protocol

from nodl.plugins import (
    EXTENSION_POINTS,
    ExtensionPoint,
    PluginError,
    instantiate_extensions,
)

__all__ = ['RESOLVER_GROUP', 'ResolveContext', 'Resolved', 'ResolutionError', 'Resolver',
           'ResolverExtension',
           'scheme_of', 'load_resolvers']

RESOLVER_GROUP = 'nodl.resolvers'
_SCHEME = re.compile(r'([A-Za-z][A-Za-z0-9+.-]*)://')


class ResolveContext(NamedTuple):
    """What a resolver may need to know about the referring node file."""

    #: The node definition's file, or None when it was given as text.
    node_file: str | None
    #: The folder references may not leave (the package root), or None.
    boundary: str | None
    #: The ament prefixes ``nodl://`` references are looked up in, in order; None:
    #: those of ``AMENT_PREFIX_PATH`` (what a caller's ``prefixes=`` is passed on as).
    prefixes: tuple[str, ...] | None = None


class Resolved(NamedTuple):
    """A resolved reference: the document and the file it came from.

    ``text`` may be ``bytes`` as read from disk: the loader then applies the
    same size and UTF-8 checks as to any other document.
    """

    text: str | bytes
    file: str


class ResolutionError(Exception):
    """A reference that cannot be resolved; ``searched`` lists where we looked."""

    def __init__(self, message: str, searched: list[str] | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.searched = list(searched or [])


class Resolver(Protocol):
    """The protocol of a resolver plugin (what :func:`compose` calls)."""

    def resolve(self, reference: str, context: ResolveContext) -> Resolved:
        """Return the referenced document, or raise ResolutionError."""
        ...  # pragma: no cover


class ResolverExtension(ExtensionPoint):
    """Base class of resolvers (the ``nodl.resolvers`` extension point).

    Registered under the URI scheme it resolves (``nodl``, ``file``, ...);
    instantiated without arguments.
    """

    #: Version 1.0: ``resolve(reference, context) -> Resolved``.
    EXTENSION_POINT_VERSION = EXTENSION_POINTS[RESOLVER_GROUP].version

    def resolve(self, reference: str, context: ResolveContext) -> Resolved:
        """Return the referenced document, or raise ResolutionError saying what was searched."""
        raise NotImplementedError


def scheme_of(reference: str) -> str:
    """``nodl`` for ``nodl://...``; ``file`` for a plain (relative) path."""
    match = _SCHEME.match(reference)
    return match.group(1).lower() if match else 'file'


def load_resolvers(on_error: Callable[[PluginError], None] | None = None) -> dict[str, Resolver]:
    """Instantiate every resolver plugin, keyed by scheme (a broken one is reported and skipped)."""
    resolvers: dict[str, Resolver] = instantiate_extensions(RESOLVER_GROUP, on_error=on_error)
    return resolvers


def package_root(start: str) -> str | None:
    """The nearest folder at or above ``start`` that holds a package.xml."""
    folder = os.path.abspath(start)
    while True:
        if os.path.isfile(os.path.join(folder, 'package.xml')):
            return folder
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent
