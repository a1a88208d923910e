"""Ports: a node's endpoints with their final names, and whether two of them can be joined.

A port is one endpoint of a node instance (:class:`nodl.composition.instance.InstanceEntity`):
its kind (publisher, subscription, service server or client, action server or client), the
name its definition declares, the final name it has in the composition, its interface type
and QoS.  :func:`verdict` says whether two ports can be joined, and why not: the kinds must
pair (a publisher and a subscription, a server and a client of the same communication),
the types must be the same, and a publisher's QoS must be able to serve the subscription's
(:func:`nodl.qos_compat.check_qos_compatible`, the middleware's rules).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from nodl.composition.entities import InterfaceType
from nodl.qos_compat import check_qos_compatible

__all__ = ['PAIRS', 'Port', 'Verdict', 'find_port', 'ports_of', 'verdict']

#: The kinds that can be joined: offering side -> using side.
PAIRS = {'publisher': 'subscription', 'service_server': 'service_client',
         'action_server': 'action_client'}


@dataclass(frozen=True)
class Port:
    """One endpoint of a composed node."""

    #: The composition node's id.
    node: str
    #: ``publisher``, ``subscription``, ``service_server``, ``service_client``,
    #: ``action_server`` or ``action_client``.
    kind: str
    #: The name the definition declares (``scan``, ``~/status``).
    name: str
    #: Its final name in the composition (``/rover/scan``).
    final_name: str
    #: The interface type (``sensor_msgs/msg/LaserScan``).
    type: str
    #: The QoS the definition declares (topics; services when declared), NoDL keys.
    qos: dict[str, Any] | None
    #: Who provides it: ``client_library`` (the base: ``/rosout``, parameter services),
    #: ``other_code`` (a mixin) or ``implementation`` (the node's own).
    provider: str = 'implementation'
    #: The instance entity (for the library; not in :meth:`to_dict`).
    entity: Any = None

    @property
    def offers(self) -> bool:
        """True for the offering side (publisher, server)."""
        return self.kind in PAIRS

    @property
    def communication(self) -> str:
        """``topic``, ``service`` or ``action``."""
        return 'topic' if self.kind in ('publisher', 'subscription') else self.kind.split('_')[0]

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping."""
        return {'node': self.node, 'kind': self.kind, 'name': self.name,
                'final_name': self.final_name, 'type': self.type, 'qos': self.qos,
                'provider': self.provider}


@dataclass(frozen=True)
class Verdict:
    """Whether two ports can be joined: ``ok``, ``warning`` (joined, QoS left to the
    middleware) or ``error`` (refused), the code and reason, and the rule that makes the
    names meet (``node id``, ``from``, ``to``) when they can be joined."""

    verdict: str
    reason: str = ''
    code: str = ''
    #: True when the two final names are the same already.
    connected: bool = False

    @property
    def ok(self) -> bool:
        """True unless refused."""
        return self.verdict != 'error'

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping."""
        return {'verdict': self.verdict, 'reason': self.reason, 'code': self.code,
                'connected': self.connected}


def ports_of(node_id: str, launched: Any) -> list[Port]:
    """The ports of a launched node (:class:`nodl.system.launched.SystemNode`); none without an
    instance."""
    instance = getattr(launched, 'instance', None)
    if instance is None:
        return []
    out = []
    for bound in instance.endpoints:
        entity = bound.entity
        qos = entity.qos.to_dict() if entity.qos is not None else None
        out.append(Port(node_id, entity.kind.value, entity.name, bound.name, entity.type_name,
                        qos, entity.provider.value, bound))
    return out


def find_port(ports: list[Port], text: str) -> list[Port]:
    """The ports ``text`` names: the declared name, the final name, or the declared name
    without ``~/``; ``KIND/NAME`` (``publisher/scan``) picks one kind."""
    kind = None
    if '/' in text and text.split('/', 1)[0] in (*PAIRS, *PAIRS.values()):
        kind, text = text.split('/', 1)
    candidates = [p for p in ports if kind is None or p.kind == kind]
    for matches in ((p for p in candidates if p.name == text),
                    (p for p in candidates if p.final_name == text),
                    (p for p in candidates if p.name.lstrip('~/') == text.lstrip('~/')),
                    (p for p in candidates if p.final_name.rsplit('/', 1)[-1] == text)):
        found = list(matches)
        if found:
            return found
    return []


def _same_type(first: str, second: str, communication: str) -> bool:
    try:
        return InterfaceType.parse(first, communication) == InterfaceType.parse(second, communication)
    except ValueError:
        return first == second


def verdict(first: Port, second: Port) -> Verdict:
    """Whether ``first`` and ``second`` can be joined (see the module docstring)."""
    offering, using = (first, second) if first.offers else (second, first)
    if PAIRS.get(offering.kind) != using.kind:
        return Verdict('error', f'a {first.kind.replace("_", " ")} cannot be joined to a '
                       f'{second.kind.replace("_", " ")}: join a publisher to a subscription, '
                       'a service server to a client, or an action server to a client',
                       'NODL972')
    connected = offering.final_name == using.final_name
    if not _same_type(offering.type, using.type, offering.communication):
        return Verdict('error', f'the types differ: {offering.final_name} is {offering.type} '
                       f'but {using.final_name} is {using.type}', 'NODL973', connected)
    if offering.communication == 'topic':
        try:
            result = check_qos_compatible(offering.qos, using.qos)
        except (TypeError, ValueError) as exc:
            return Verdict('error', f'the QoS cannot be compared: {exc}', 'NODL974', connected)
        if result.verdict == 'error':
            return Verdict('error', f'the QoS cannot connect: {result.reason}', 'NODL974',
                           connected)
        if result.verdict == 'warning':
            return Verdict('warning', f'the QoS may not match: {result.reason}', 'NODL975',
                           connected)
    return Verdict('ok', '', '', connected)
