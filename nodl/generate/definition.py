"""A definition named on a command line (``FILE`` or ``PACKAGE EXECUTABLE``), resolved.

Shared by ``nodl generate``, ``nodl params`` and the runtime: each takes a
node definition as a file or as an installed package's executable.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic
from nodl.system import ResolvedNode

if TYPE_CHECKING:
    from nodl.registry.overlay import Definitions

__all__ = ['resolve_target', 'target_name']


def resolve_target(target: Sequence[str] | str, client_library: str | None = None,
                   prefixes: list[str] | None = None, definitions: Definitions | None = None
                   ) -> tuple[ResolvedNode | None, list[Diagnostic], str]:
    """Resolve ``FILE`` or ``PACKAGE EXECUTABLE``: ``(node or None, diagnostics, source file)``
    (:func:`nodl.targets.resolve.resolve_target`, which also says where the
    definition came from).

    The registration is looked up in the definitions folders ``definitions`` (and those in
    force), then ``prefixes`` (default: ``AMENT_PREFIX_PATH``); so are ``nodl://`` mixins.
    OSError for a file that cannot be read; ValueError for an unknown client library.
    """
    from nodl.targets.resolve import resolve_target as resolve

    found = resolve(target, client_library=client_library, prefixes=prefixes,
                    definitions=definitions)
    return found.node, found.diagnostics, found.source


def target_name(target: Sequence[str] | str) -> str:
    """The executable (``PACKAGE EXECUTABLE``) or the file name the defaults are derived from."""
    parts = [target] if isinstance(target, str) else list(target)
    return parts[-1]
