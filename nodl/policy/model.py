"""The policy model: enclaves, profiles and grants, each grant with where it comes from.

A :class:`Policy` is what an SROS 2 policy document (``policy.xsd`` version
0.2.0) holds: enclaves (one certificate each), each with the profiles of the
nodes that run in it; a profile grants its node permissions on topics,
services and actions.  Every :class:`Grant` keeps the final name it grants
(what the node really uses) and its :class:`Source` list (the definition file
and line, the layer, the launch entry), so that the written policy can say
why each permission is there.

The permission vocabulary is one table, :data:`PERMISSIONS`: a grant of any
other kind cannot be built.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import NamedTuple

from nodl.composition.entities import EntityKind
from nodl.naming import join_name

__all__ = ['POLICY_VERSION', 'PermissionList', 'PERMISSIONS', 'ACCESS_OF_KIND', 'permission_list',
           'Source', 'Grant', 'Profile', 'Enclave', 'Policy']

#: The policy format version SROS 2 reads (``<policy version="0.2.0">``).
POLICY_VERSION = '0.2.0'


class PermissionList(NamedTuple):
    """One kind of permission list of a profile: ``<topics publish="ALLOW" subscribe="...">``."""

    #: ``topic``, ``service`` or ``action``.
    communication: str
    #: The list element (``topics``).
    element: str
    #: The element of each name in it (``topic``).
    item: str
    #: The access of the offering side (publisher, server): ``publish``, ``reply``, ``execute``.
    offer: str
    #: The access of the using side (subscription, client): ``subscribe``, ``request``, ``call``.
    use: str

    @property
    def accesses(self) -> tuple[str, str]:
        """Both access attributes, in the order the policy writes them."""
        return (self.offer, self.use)


#: The permission lists a profile can hold, in the order the writer emits them (sorted by
#: element name, as SROS 2's own ``policy.xsl`` orders them).
PERMISSIONS: tuple[PermissionList, ...] = (
    PermissionList('action', 'actions', 'action', 'execute', 'call'),
    PermissionList('service', 'services', 'service', 'reply', 'request'),
    PermissionList('topic', 'topics', 'topic', 'publish', 'subscribe'),
)

_BY_COMMUNICATION = {p.communication: p for p in PERMISSIONS}
_BY_ELEMENT = {p.element: p for p in PERMISSIONS}

#: The rule qualifiers a permission list may carry.
QUALIFIERS = ('ALLOW', 'DENY')


def permission_list(communication_or_element: str) -> PermissionList:
    """The permission list of ``topic``/``topics`` (service, action); ValueError otherwise."""
    found = _BY_COMMUNICATION.get(communication_or_element) or _BY_ELEMENT.get(communication_or_element)
    if found is None:
        raise ValueError(f'unknown permission kind {communication_or_element!r}; expected one of: '
                         + ', '.join(p.element for p in PERMISSIONS))
    return found


def access_for(communication: str, offers: bool) -> str:
    """The access an endpoint needs: a publisher ``publish``, a service client ``request``, ..."""
    kind = permission_list(communication)
    return kind.offer if offers else kind.use


#: Entity kind value (``publisher``, ``service_client``, ...) -> (communication, access).
ACCESS_OF_KIND: dict[str, tuple[str, str]] = {}


def _fill_access_table() -> None:
    for kind in EntityKind:
        if kind.communication is not None:
            ACCESS_OF_KIND[kind.value] = (kind.communication, access_for(kind.communication, kind.offers))


_fill_access_table()


class Source(NamedTuple):
    """Why a grant is there: what declares it and where, and the launch entry if any."""

    #: In words: ``publisher 'chatter' (main)``, ``client library rclpy (base:node)``, ``use_sim_time``.
    what: str
    #: ``file:line:column`` of the declaration ('' for the client library's own entities).
    where: str = ''
    #: ``file:line:column`` of the launch entry that started the node ('' if none).
    launch: str = ''

    def __str__(self) -> str:
        parts = [self.what]
        if self.where:
            parts.append(self.where)
        if self.launch:
            parts.append(f'launched at {self.launch}')
        return ', '.join(parts)


@dataclass
class Grant:
    """One permission of a profile on one final name."""

    communication: str
    access: str
    #: The final (fully qualified) name the node uses.
    name: str
    sources: list[Source] = field(default_factory=list)

    def __post_init__(self) -> None:
        kind = permission_list(self.communication)
        if self.access not in kind.accesses:
            raise ValueError(f'unknown {kind.element} permission {self.access!r}; expected one of: '
                             + ', '.join(kind.accesses))

    @property
    def key(self) -> tuple[str, str, str]:
        """``(communication, access, final name)``."""
        return (self.communication, self.access, self.name)


@dataclass
class Profile:
    """The permissions of one node: ``<profile ns=... node=...>``."""

    #: The node's final namespace (``/`` or ``/robot``).
    namespace: str
    #: The node's final name.
    node: str
    grants: dict[tuple[str, str, str], Grant] = field(default_factory=dict)
    #: Remarks written as comments at the top of the profile (gaps, what it is made from).
    notes: list[str] = field(default_factory=list)
    #: The definition file ('' if none).
    definition: str = ''
    #: The client library and distribution the base grants follow (``rclpy, kilted``).
    base: str = ''
    #: The launch entry that started the node (``file:line:column``), if any.
    launch: str = ''

    @property
    def fqn(self) -> str:
        """``/namespace/node``."""
        return join_name(self.namespace, self.node)

    def grant(self, communication: str, access: str, name: str, source: Source | None = None) -> Grant:
        """Add (or extend) the grant of ``access`` on ``name``; returns it."""
        key = (communication, access, name)
        found = self.grants.get(key)
        if found is None:
            found = self.grants[key] = Grant(communication, access, name)
        if source is not None and source not in found.sources:
            found.sources.append(source)
        return found

    def sorted_grants(self) -> list[Grant]:
        """The grants in the canonical order: permission list, access, name."""
        order = {(p.communication, a): (i, j) for i, p in enumerate(PERMISSIONS)
                 for j, a in enumerate(p.accesses)}
        return sorted(self.grants.values(), key=lambda g: (order[(g.communication, g.access)], g.name))

    def names(self) -> set[tuple[str, str, str]]:
        """Every ``(communication, access, final name)`` granted."""
        return set(self.grants)


@dataclass
class Enclave:
    """One enclave (``<enclave path=...>``): the nodes that share a security identity."""

    path: str
    profiles: list[Profile] = field(default_factory=list)

    def sorted_profiles(self) -> list[Profile]:
        """Profiles ordered by namespace, then node name."""
        return sorted(self.profiles, key=lambda p: (p.namespace, p.node))


@dataclass
class Policy:
    """A whole policy: enclaves of profiles."""

    enclaves: list[Enclave] = field(default_factory=list)
    #: Remarks for the top of the document (what it was generated from).
    notes: list[str] = field(default_factory=list)
    _by_path: dict[str, Enclave] = field(default_factory=dict, init=False, repr=False, compare=False)

    def enclave(self, path: str) -> Enclave:
        """The enclave at ``path``, created if needed."""
        found = self._by_path.get(path)
        if found is None or found.path != path or len(self._by_path) != len(self.enclaves):
            self._by_path = {e.path: e for e in reversed(self.enclaves)}  # (the list was changed)
            found = self._by_path.get(path)
        if found is None:
            found = self._by_path[path] = Enclave(path)
            self.enclaves.append(found)
        return found

    def sorted_enclaves(self) -> list[Enclave]:
        """Enclaves ordered by path."""
        return sorted(self.enclaves, key=lambda e: e.path)

    def profiles(self) -> Iterator[tuple[Enclave, Profile]]:
        """Every profile with its enclave, in canonical order."""
        for enclave in self.sorted_enclaves():
            for profile in enclave.sorted_profiles():
                yield enclave, profile

    def profile(self, fqn: str) -> Profile | None:
        """The (first) profile of the node ``fqn``, or None."""
        return next((p for _, p in self.profiles() if p.fqn == fqn), None)
