"""A definition named on a command line (``FILE`` or ``PACKAGE EXECUTABLE``), resolved.

Shared by ``nodl generate``, ``nodl params`` and the runtime: each takes a
node definition as a file or as an installed package's executable.
"""

from __future__ import annotations

import os
from typing import Sequence

from nodl_schema.diagnostics import Diagnostic
from nodl_schema.system import ResolvedNode

__all__ = ['resolve_target', 'target_name']


def resolve_target(target: Sequence[str] | str, client_library: str | None = None,
                   prefixes: list[str] | None = None
                   ) -> tuple[ResolvedNode | None, list[Diagnostic], str]:
    """Resolve ``FILE`` or ``PACKAGE EXECUTABLE``: ``(node or None, diagnostics, source file)``.

    The registration and ``nodl://`` mixins are looked up in ``prefixes`` (default:
    ``AMENT_PREFIX_PATH``).  OSError for a file that cannot be read; ValueError for an unknown client library.
    """
    parts = [target] if isinstance(target, str) else list(target)
    if len(parts) == 2:
        from nodl_schema.system import resolve_registered

        return resolve_registered(parts[0], parts[1], client_library=client_library,
                                  prefixes=prefixes)
    if len(parts) != 1:
        raise ValueError('give a definition FILE or PACKAGE EXECUTABLE')
    from pathlib import Path

    from nodl_schema.loading import check_source
    from nodl_schema.system.resolved import resolve_report
    from nodl_schema.validation.kinds import Kind

    path = parts[0]
    if not os.path.isfile(path):
        raise OSError(f'{path}: no such file')
    report = check_source(Path(path), kind=Kind.NODE, file=path)
    node, diagnostics = resolve_report(report, client_library=client_library, prefixes=prefixes)
    return node, diagnostics, path


def target_name(target: Sequence[str] | str) -> str:
    """The executable (``PACKAGE EXECUTABLE``) or the file name the defaults are derived from."""
    parts = [target] if isinstance(target, str) else list(target)
    return parts[-1]
