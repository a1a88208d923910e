"""A system: node instances and the connections between them.

A :class:`Connection` is one topic (publishers and subscriptions), one
service (servers and clients) or one action (servers and clients), keyed by
its final name.  Entities the client library provides (``/rosout``,
``/parameter_events``, the parameter services) are included, as policies
need them; they carry their provider, so an analysis can leave them out.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import NamedTuple

from nodl.composition.entities import Entity, EntityKind, Provider
from nodl.composition.instance import InstanceEntity, NodeInstance, instances_named

__all__ = ['Connection', 'System']

#: communication -> (the offering side's word, the using side's word).
_SIDES = {'topic': ('publishers', 'subscriptions'), 'service': ('servers', 'clients'),
          'action': ('servers', 'clients')}


class Connection(NamedTuple):
    """Everything on one topic, service or action of a system."""

    #: ``topic``, ``service`` or ``action``.
    communication: str
    #: The final name.
    name: str
    #: Publishers (topic) or servers (service, action).
    offering: tuple[InstanceEntity, ...]
    #: Subscriptions (topic) or clients (service, action).
    using: tuple[InstanceEntity, ...]

    @property
    def publishers(self) -> tuple[InstanceEntity, ...]:
        """A topic's publishers."""
        return self.offering if self.communication == 'topic' else ()

    @property
    def subscriptions(self) -> tuple[InstanceEntity, ...]:
        """A topic's subscriptions."""
        return self.using if self.communication == 'topic' else ()

    @property
    def servers(self) -> tuple[InstanceEntity, ...]:
        """A service's or action's servers."""
        return self.offering if self.communication != 'topic' else ()

    @property
    def clients(self) -> tuple[InstanceEntity, ...]:
        """A service's or action's clients."""
        return self.using if self.communication != 'topic' else ()

    @property
    def endpoints(self) -> tuple[InstanceEntity, ...]:
        """Both sides."""
        return self.offering + self.using

    @property
    def types(self) -> list[str]:
        """The interface types used on it (more than one is a mismatch), sorted."""
        return sorted({e.entity.type_name for e in self.endpoints})

    @property
    def connected(self) -> bool:
        """True if both sides have at least one endpoint."""
        return bool(self.offering) and bool(self.using)

    def only_client_library(self) -> bool:
        """True if every endpoint on it is provided by a client library (``/rosout``, ...)."""
        return all(e.entity.provider is Provider.CLIENT_LIBRARY for e in self.endpoints)

    def __str__(self) -> str:
        offer, use = _SIDES[self.communication]
        return (f'{self.communication} {self.name}: {len(self.offering)} {offer}, '
                f'{len(self.using)} {use}')


def _connections(communication: str, names: Iterable[str],
                 offering: Mapping[str, InstanceEntity | list[InstanceEntity]],
                 using: Mapping[str, InstanceEntity | list[InstanceEntity]]
                 ) -> dict[str, Connection]:
    """The connections of ``communication`` called ``names``, by name in that order, from
    each side's endpoint (or list of endpoints) by name."""
    make = Connection._make
    made = {}
    for name in names:
        offers, uses = offering.get(name), using.get(name)
        # (written out rather than a helper: twice per connection)
        made[name] = make((
            communication, name,
            () if offers is None else tuple(offers) if type(offers) is list else (offers,),
            () if uses is None else tuple(uses) if type(uses) is list else (uses,)))
    return made


class System:
    """Node instances and the connections between them.

    A *lone server* is a service or action that one server offers and no client uses (every
    node's parameter services, most of a large system's connections): nothing to check on
    it.  Those are made into connections only when they are asked for.
    """

    def __init__(self, instances: Iterable[NodeInstance]) -> None:
        #: The instances, in the order given.
        self.instances: tuple[NodeInstance, ...] = tuple(instances)
        # (communication, offers) -> final name -> its endpoint(s) on that side: the endpoint
        # itself while it is the only one (most names have one per side), a list from the
        # second on.  A large system has tens of thousands of endpoints: no list, and no
        # (communication, name) pair, is made per endpoint, and each communication's names
        # are sorted as strings.
        sides: dict[tuple[str, bool], dict[str, InstanceEntity | list[InstanceEntity]]] = {}
        # kind -> its side's table, asked once per kind rather than per endpoint.
        table_of = {kind: sides.setdefault((kind.communication, kind.offers), {})
                    for kind in EntityKind if kind.communication is not None}
        # (kind, name) of each name a side has more than one endpoint of (noted when its list
        # is made: a name offered once and used by no client is a lone server, and that is
        # most names, which are not walked again to find it)
        repeated: list[tuple[EntityKind, str]] = []
        for instance in self.instances:
            for bound in instance.endpoints:
                _, entity, name = bound  # (unpacked: no attribute look-ups)
                table = table_of[entity.kind]
                found = table.get(name)
                if found is None:
                    table[name] = bound
                elif type(found) is list:
                    found.append(bound)
                else:
                    table[name] = [found, bound]  # type: ignore[list-item]
                    repeated.append((entity.kind, name))

        #: communication -> final name -> its connection, lone servers left out (names sorted
        #: as strings).
        self._by_name: dict[str, dict[str, Connection]] = {}
        #: communication -> its sides' tables, when it has lone servers (not made yet).
        self._lone: dict[str, tuple[dict[str, InstanceEntity | list[InstanceEntity]],
                                    dict[str, InstanceEntity | list[InstanceEntity]]]] = {}
        self._lone_count = 0
        for communication in sorted({communication for communication, _ in sides}):
            offering, using = sides[communication, True], sides[communication, False]
            if not offering and not using:
                continue
            if communication == 'topic':
                names = offering.keys() | using.keys()
            else:
                names = using.keys() | {name for kind, name in repeated
                                        if kind.offers and kind.communication == communication}
                lone = len(offering) - sum(1 for name in names if name in offering)
                if lone:
                    self._lone[communication] = (offering, using)
                    self._lone_count += lone
            self._by_name[communication] = _connections(communication, sorted(names),
                                                        offering, using)
        # Every connection, lone servers too, by communication then by name; and in that
        # order (made on first use).
        self._all: dict[str, dict[str, Connection]] | None = None
        self._ordered: tuple[Connection, ...] = ()

    def _complete(self) -> dict[str, dict[str, Connection]]:
        """Communication -> final name -> its connection, every one (lone servers made once)."""
        complete = self._all
        if complete is None:
            complete = {}
            for communication, made in self._by_name.items():
                if communication in self._lone:
                    offering, using = self._lone[communication]
                    names = sorted(offering.keys() | using.keys())
                    lone = _connections(communication, [name for name in names if name not in made],
                                        offering, using)
                    made = {name: made.get(name) or lone[name] for name in names}
                complete[communication] = made
            self._all = complete
            self._ordered = tuple(connection for connections in complete.values()
                                  for connection in connections.values())
        return complete

    def connections(self, communication: str | None = None, *,
                    include_client_library: bool = True,
                    lone_servers: bool = True) -> list[Connection]:
        """Every connection (of one communication: ``topic``, ``service`` or ``action``).

        With ``include_client_library=False``, endpoints the client library
        provides are left out, and connections left empty are dropped.  With
        ``lone_servers=False``, services and actions one server offers and no client
        uses are left out (a check that finds nothing on them spares making them).
        """
        # (the lone servers are made only when they could be among those asked for)
        tables = self._complete() if lone_servers and (
            communication is None or communication in self._lone) else self._by_name
        found: Iterable[Connection]
        if communication is not None:
            found = tables.get(communication, {}).values()
        elif lone_servers:
            found = self._ordered
        else:
            found = [connection for connections in tables.values()
                     for connection in connections.values()]
        if include_client_library:
            return list(found)
        out = []
        for connection in found:
            def keep(side: tuple[InstanceEntity, ...]) -> tuple[InstanceEntity, ...]:
                return tuple(e for e in side if e.entity.provider is not Provider.CLIENT_LIBRARY)

            connection = connection._replace(offering=keep(connection.offering),
                                             using=keep(connection.using))
            if not connection.endpoints:
                continue
            out.append(connection)
        return out

    @property
    def topics(self) -> list[Connection]:
        """The topic connections."""
        return self.connections('topic')

    @property
    def services(self) -> list[Connection]:
        """The service connections."""
        return self.connections('service')

    @property
    def actions(self) -> list[Connection]:
        """The action connections."""
        return self.connections('action')

    def connection(self, communication: str, name: str) -> Connection | None:
        """The connection of ``communication`` called ``name`` (final name), or None."""
        table = self._by_name.get(communication)
        found = table.get(name) if table is not None else None
        if found is None and name in self._lone.get(communication, ({},))[0]:
            return self._complete()[communication][name]  # a lone server
        return found

    def _bound(self, instance: NodeInstance | str, entity: Entity | InstanceEntity
               | tuple[EntityKind | str, str]) -> InstanceEntity:
        if isinstance(entity, InstanceEntity):
            return entity
        node = instance if isinstance(instance, NodeInstance) else self.instance(instance)
        if not isinstance(entity, Entity):
            entity = node.resolved.entity(*entity)
        for bound in node.entities:
            if bound.entity is entity:
                return bound
        raise KeyError(f'{entity} is not an entity of {node.fqn}')

    def peers(self, instance: NodeInstance | str,
              entity: Entity | InstanceEntity | tuple[EntityKind | str, str]) -> list[InstanceEntity]:
        """The endpoints on the other side of ``entity``'s connection.

        ``instance`` is an instance or its fully qualified name; ``entity`` an
        entity of its resolved node, an :class:`InstanceEntity`, or ``(kind,
        declared name)``.  A publisher's peers are the subscriptions of its
        topic, a client's the servers of its service, and so on; a parameter
        has none.
        """
        bound = self._bound(instance, entity)
        communication = bound.entity.kind.communication
        if communication is None:
            return []
        connection = self.connection(communication, bound.name)
        if connection is None:
            raise KeyError((communication, bound.name))
        return list(connection.using if bound.entity.kind.offers else connection.offering)

    def instance(self, fqn: str) -> NodeInstance:
        """The instance with the fully qualified name ``fqn`` (KeyError if none, or several)."""
        found = [i for i in self.instances if i.fqn == fqn]
        if len(found) != 1:
            raise KeyError(f'{len(found)} instances are called {fqn}')
        return found[0]

    def name_clashes(self) -> dict[str, list[NodeInstance]]:
        """Fully qualified names used by more than one instance."""
        return {fqn: group for fqn, group in instances_named(self.instances).items()
                if len(group) > 1}

    def __repr__(self) -> str:
        # (without making the lone servers)
        count = sum(len(connections) for connections in self._by_name.values()) + self._lone_count
        return f'System({len(self.instances)} instances, {count} connections)'
