"""The ``file`` resolver: mixin paths relative to the node file.

A relative path may not leave the package it is in (the nearest folder with
a package.xml above the node file; without one, the node file's folder), so
that an installed package never depends on files outside itself.
"""

from __future__ import annotations

import os

from nodl.composition.resolvers import (
    ResolutionError,
    ResolveContext,
    Resolved,
    ResolverExtension,
)
from nodl.frontends.source import read_limited

__all__ = ['PathResolver']


class PathResolver(ResolverExtension):
    """Resolves ``some/file.nodl.yaml`` and ``file://some/file.nodl.yaml``."""

    def resolve(self, reference: str, context: ResolveContext) -> Resolved:
        """Read the file the reference names, relative to the node file."""
        path = reference[len('file://'):] if reference.startswith('file://') else reference
        if os.path.isabs(path):
            raise ResolutionError(f'{path!r} is an absolute path; mixin paths are relative to the '
                                  'node file')
        if context.node_file is None:
            raise ResolutionError('a relative mixin path needs the location of the node file; '
                                  'load the node definition from a file')
        base = os.path.dirname(os.path.abspath(context.node_file))
        target = os.path.normpath(os.path.join(base, path))
        boundary = os.path.realpath(context.boundary or base)
        # Real paths: a symbolic link inside the package must not lead out of it.
        if os.path.commonpath([boundary, os.path.realpath(target)]) != boundary:
            raise ResolutionError(f'{reference!r} leaves the package directory {boundary}; '
                                  'a mixin path must stay inside its package (use '
                                  'nodl://<package>/<name> for another package)', [target])
        if not os.path.isfile(target):
            raise ResolutionError(f'no file {target}', [target])
        try:
            return Resolved(read_limited(target), target)
        except OSError as exc:
            raise ResolutionError(f'cannot read {target}: {exc.strerror}', [target]) from None
