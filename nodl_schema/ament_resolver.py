"""``nodl://<package>/<name>``: a document registered in the ament index."""

from __future__ import annotations

from pathlib import Path

from nodl.composition.resolvers import ResolutionError as NodlResolutionError
from nodl.registry import registrations
from nodl.vocabulary import INTERFACE_RESOURCE, resource_name
from nodl_schema.composition import ResolutionError, Resolver

__all__ = ['AmentIndexResolver']


class AmentIndexResolver(Resolver):
    """Resolves ``nodl://<package>/<name>`` through the ament index.

    The reference implementation's ``ament_nodl_register`` installs a document
    as the index entry ``nodl/<package>__<name>`` (the entry's file is the
    document); that is looked up first, with ``ament_index_python``.  An
    interface definition registered by the toolkit (``nodl_interfaces``) is
    found after it, as the installed file the entry points at.
    """

    prefix = 'nodl://'
    ament_resource_type = 'nodl'

    def handles(self, ref: str) -> bool:
        """True for a ``nodl://`` reference."""
        return ref.startswith(self.prefix)

    def resolve(self, ref: str, origin: Path | None = None) -> Path:
        """The registered document's file; :class:`ResolutionError` if nothing is registered."""
        package, _, name = ref[len(self.prefix):].partition('/')
        if not package or not name:
            raise ResolutionError(f'invalid reference {ref!r}: expected nodl://<package>/<name>')
        key = resource_name(package, name)
        found = self._reference_entry(package, name)
        if found is not None:
            return found
        own = self._toolkit_entry(package, name)
        if own is not None:
            return own
        raise ResolutionError(
            f'NoDL document {ref!r} is not in the ament index (no resource '
            f'{self.ament_resource_type}/{key} or {INTERFACE_RESOURCE}/{key}): is the package '
            'that registers it built and its install/setup.bash sourced?')

    def _reference_entry(self, package: str, name: str) -> Path | None:
        key = resource_name(package, name)
        try:
            from ament_index_python import resources
            from ament_index_python.constants import RESOURCE_INDEX_SUBFOLDER
        except ImportError:  # without ROS's package: the toolkit's registry of the same index
            from nodl.registry import registrations

            entry = registrations.interface_entry(package, name, self.ament_resource_type)
            return Path(entry.path) if entry is not None else None
        prefix = resources.has_resource(self.ament_resource_type, key)
        if not prefix:
            return None
        path = Path(prefix, RESOURCE_INDEX_SUBFOLDER, self.ament_resource_type, key)
        if not path.is_file():
            raise ResolutionError(f'the index entry {path} is registered but is not a readable '
                                  'file: is the package fully installed?')
        return path

    @staticmethod
    def _toolkit_entry(package: str, name: str) -> Path | None:
        entry = registrations.interface_entry(package, name)
        if entry is None:
            return None
        try:
            return Path(registrations.read_registered(entry, package).file)
        except NodlResolutionError as error:
            raise ResolutionError(str(error)) from None
