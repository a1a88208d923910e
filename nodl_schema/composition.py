"""References between documents (``include``) and the merging of documents, as the reference API has them.

A reference is a ``<scheme>://<body>`` URI.  A :class:`Resolver` says which
references it handles and gives the path of the document one names; the
registered resolvers are searched from the most recently registered one, so
a registration shadows an earlier one for the same scheme until it is
removed.  :func:`merge_documents` combines documents strictly: one name
declared twice in one category is a :class:`MergeError`.
"""

from __future__ import annotations

import abc
import contextlib
from typing import TYPE_CHECKING

from nodl.composition.resolvers import scheme_of

if TYPE_CHECKING:
    from collections.abc import Iterator
    from pathlib import Path
    from typing import Any

    from nodl_schema.models import NodlDocument, ParameterDefinition

from nodl.composition.resolvers import ResolutionError as _NodlResolutionError

__all__ = ['ResolutionError', 'MergeError', 'Resolver', 'register_resolver', 'unregister_resolver',
           'get_resolvers', 'resolver_registered', 'resolver_for', 'resolve', 'merge_documents',
           'ENTITY_LIST_FIELDS']


class ResolutionError(_NodlResolutionError):
    """A reference that cannot be resolved: no resolver handles it, its document is not
    there, or a document is included twice (a cycle, or two paths to one document)."""


class MergeError(Exception):
    """Documents that cannot be merged: one name declared twice in one category."""


class Resolver(abc.ABC):
    """Handles one form of reference (usually a URI scheme) and finds the document it names."""

    @abc.abstractmethod
    def handles(self, ref: str) -> bool:
        """Whether ``ref`` is a reference of this resolver's form."""

    @abc.abstractmethod
    def resolve(self, ref: str, origin: Path | None = None) -> Path:
        """The path of the document ``ref`` names; ``origin`` is the including document, if any.

        Called only for a ``ref`` that :meth:`handles` accepts.  Raises
        :class:`ResolutionError` for a reference that names no document.
        """

    def normalize(self, ref: str, origin: Path | None = None) -> str:
        """``ref`` in a form that compares equal for every spelling of one document (default: as is)."""
        return ref


_registered: list[Resolver] = []


def register_resolver(resolver: Resolver) -> Resolver:
    """Register ``resolver`` until :func:`unregister_resolver` (prefer :func:`resolver_registered`
    for a registration with a scope); returns it."""
    if not isinstance(resolver, Resolver):
        raise TypeError(f'{resolver!r} is not a Resolver (subclass nodl_schema.Resolver)')
    _registered.append(resolver)
    return resolver


def unregister_resolver(resolver: Resolver) -> None:
    """Remove the latest registration of ``resolver``; :class:`LookupError` if it has none."""
    for index in reversed(range(len(_registered))):
        if _registered[index] is resolver:
            del _registered[index]
            return
    raise LookupError(f'{resolver!r} is not registered')


def get_resolvers() -> list[Resolver]:
    """The registered resolvers, oldest first (the registry itself, not a copy)."""
    return _registered


@contextlib.contextmanager
def resolver_registered(resolver: Resolver) -> Iterator[Resolver]:
    """Register ``resolver`` for a ``with`` block; it is removed at the end, even on an exception."""
    register_resolver(resolver)
    try:
        yield resolver
    finally:
        unregister_resolver(resolver)


def resolver_for(ref: str) -> Resolver | None:
    """The most recently registered resolver that handles ``ref`` (None if none does)."""
    return next((r for r in reversed(_registered) if r.handles(ref)), None)


def resolve(ref: str, origin: Path | None = None) -> Path:
    """The path of the document ``ref`` names.

    Raises :class:`ResolutionError` when no registered resolver handles ``ref``;
    what the resolver raises is passed on as it is.
    """
    resolver = resolver_for(ref)
    if resolver is None:
        raise ResolutionError(f'No registered resolver handles reference {ref!r} (scheme '
                              f'{scheme_of(ref)!r}); register one with '
                              'nodl_schema.register_resolver()')
    return resolver.resolve(ref, origin)


#: The categories of entities that are lists of named entries (parameters are a mapping).
ENTITY_LIST_FIELDS = ('publishers', 'subscriptions', 'service_servers', 'service_clients',
                      'action_servers', 'action_clients')


def _describe(index: int) -> str:
    return 'the including document' if index == 0 else f'included document {index}'


def _duplicate(category: str, name: str, first: int, second: int) -> MergeError:
    return MergeError(f'{category} {name!r} is declared twice: by {_describe(first)} and by '
                      f'{_describe(second)}; rename one, or include it only once')


def merge_documents(docs: list[NodlDocument]) -> NodlDocument:
    """One document with the entities of all of ``docs`` (``docs[0]`` the including one).

    ``nodl_version`` and ``description`` are the first document's; the result
    has no ``include``.  Raises :class:`MergeError` for a name declared twice in
    one category, and :class:`ValueError` for no documents.
    """
    from nodl_schema.models import NodlDocument

    if not docs:
        raise ValueError('merge_documents needs at least one document')
    parameters: dict[str, ParameterDefinition] = {}
    owner: dict[str, int] = {}
    for index, doc in enumerate(docs):
        for name, parameter in (doc.parameters or {}).items():
            if name in owner:
                raise _duplicate('parameter', name, owner[name], index)
            parameters[name] = parameter
            owner[name] = index
    fields: dict[str, Any] = {}
    for field in ENTITY_LIST_FIELDS:
        entities: list[Any] = []
        seen: dict[str, int] = {}
        for index, doc in enumerate(docs):
            for entity in getattr(doc, field) or ():
                if entity.name in seen:
                    raise _duplicate(field[:-1].replace('_', ' '), entity.name, seen[entity.name],
                                     index)
                seen[entity.name] = index
                entities.append(entity)
        fields[field] = entities or None
    root = docs[0]
    return NodlDocument(nodl_version=root.nodl_version, description=root.description,
                        include=None, parameters=parameters or None, **fields)
