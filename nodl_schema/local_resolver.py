"""``local://<path>``: a document beside the including one, by a path relative to it."""

from __future__ import annotations

from pathlib import Path

from nodl_schema.composition import ResolutionError, Resolver

__all__ = ['LocalResolver']


class LocalResolver(Resolver):
    """Resolves ``local://<relative path>`` against the folder of the including document."""

    prefix = 'local://'

    def handles(self, ref: str) -> bool:
        """True for a ``local://`` reference."""
        return ref.startswith(self.prefix)

    def resolve(self, ref: str, origin: Path | None = None) -> Path:
        """The file ``ref`` names, relative to ``origin`` (the including document, an absolute path).

        Without an absolute ``origin`` there is nothing to be relative to: that is a
        programming error (:class:`AssertionError`, as in the reference API).  A file
        that is not there is a :class:`ResolutionError`.
        """
        if origin is None:
            raise AssertionError(f'{ref!r} is relative to the including document: pass its path '
                                 'as origin')
        if not origin.is_absolute():
            raise AssertionError(f'origin {str(origin)!r} of {ref!r} must be an absolute path')
        path = origin.parent / ref[len(self.prefix):]
        if not path.is_file():
            raise ResolutionError(f'{ref!r} (included by {origin}) names {path}, which is not a '
                                  'file')
        return path

    def normalize(self, ref: str, origin: Path | None = None) -> str:
        """``local://`` and the absolute path of the file: one spelling per file."""
        return self.prefix + str(self.resolve(ref, origin).resolve())
