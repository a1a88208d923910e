"""Version skew: a running node built against another definition of a type than the installed one.

The middleware reports each topic endpoint's type hash (RIHS01).  It is
compared with the hash of the installed definition of the same type name
(computed by :mod:`nodl.interface_types.hashes` from the files the
ament index lists).  When they differ, the node's ``~/get_type_description``
service (rclcpp and rclpy nodes serve it by default) is asked for the
definition it was built with, and the differing fields are named.

Actions are checked through their hidden parts: the feedback topic
(``<action>/_action/feedback``, the action's ``FeedbackMessage``), the status
topic (``action_msgs/msg/GoalStatusArray``) and the goal and result services.
Services (and those action services) have no hash in rclpy's graph API; the
DDS middlewares report one for the request and reply topics beneath a service
(``rq/<service>Request``, ``rr/<service>Reply``), which is used when found.
Otherwise the node's ``~/get_type_description`` is asked for the service type
under the installed hash: it answers only for a type it uses, so a refusal is
a skew.  A node offering neither is said once (NODL422), not per service.
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Any

from nodl.composition.entities import Location
from nodl.interface_types.hashes import (
    description_differences,
    type_description,
    type_hash,
)
from nodl.interface_types.tree import InterfaceFileError
from nodl.live.conformance import LiveDiagnostic, Remaps, final_name
from nodl.live.observe import ACTION_INFIX, ObservedEndpoint, ObservedNode
from nodl.vocabulary import (
    ACTION_SECTIONS,
    SECTION_KEYS,
    SERVICE_SECTIONS,
    TOPIC_SECTIONS,
)

if TYPE_CHECKING:
    from nodl.composition.resolved import ResolvedNode
    from nodl.interface_types.resolve import InterfaceIndex

__all__ = ['type_skew', 'declared_locations', 'running_description', 'TypeDescriptions']

#: Seconds the node's ``~/get_type_description`` is given to answer (each question).
ANSWER_TIMEOUT = 2.0


def declared_locations(resolved: ResolvedNode, observed: ObservedNode,
                       remaps: Remaps = None) -> dict[tuple[str, str], Location]:
    """``(section, final name)`` -> where the endpoint is declared (topics, services, actions)."""
    where = {id(e.definition): e.location for e in resolved.entities}
    out: dict[tuple[str, str], Location] = {}
    for section in SECTION_KEYS:
        if section == 'parameters':
            continue
        for entity in resolved.interface.endpoints(section):
            location = where.get(id(entity))
            if location is not None:
                out[(section, final_name(entity.name, section, observed, remaps))] = location
    return out


def _reported_hash(session: Any, topic: str, observed: ObservedNode, publishers: bool,
                   no_mangle: bool = False) -> str | None:
    try:
        infos = (session.get_publishers_info_by_topic(topic, no_mangle=no_mangle) if publishers
                 else session.get_subscriptions_info_by_topic(topic, no_mangle=no_mangle))
    except Exception:  # a name the middleware refuses: nothing reported
        return None
    for info in infos:
        if info.node_name == observed.name and info.node_namespace == observed.namespace:
            text = str(info.topic_type_hash)
            return text if text.startswith('RIHS01_') else None
    return None


#: The middlewares that carry a service over the DDS topics ``rq/<service>Request`` and
#: ``rr/<service>Reply`` (whose type hashes the graph reports).
SERVICE_TOPIC_MIDDLEWARES = ('rmw_fastrtps_cpp', 'rmw_fastrtps_dynamic_cpp', 'rmw_cyclonedds_cpp',
                             'rmw_connextdds')


def _service_hashes(session: Any, service: str, observed: ObservedNode,
                    server: bool) -> dict[str, str] | None:
    """``{'Request': hash, 'Response': hash}`` of a service endpoint, from the DDS topics
    beneath it (a server reads requests and writes replies; a client the reverse); None
    when the middleware reports no such topics (not a DDS middleware, or no hash)."""
    from rclpy.utilities import get_rmw_implementation_identifier

    if get_rmw_implementation_identifier() not in SERVICE_TOPIC_MIDDLEWARES:
        return None
    request = _reported_hash(session, f'rq{service}Request', observed, not server, True)
    response = _reported_hash(session, f'rr{service}Reply', observed, server, True)
    if request is None or response is None:
        return None
    return {'Request': request, 'Response': response}


class TypeDescriptions:
    """A running node's ``~/get_type_description``, asked over one client.

    The service looks a type up by its hash: it describes the types the node
    uses, and refuses one it does not use (another hash).
    """

    def __init__(self, session: Any, observed: ObservedNode,
                 timeout: float = ANSWER_TIMEOUT) -> None:
        self.session = session
        self.timeout = timeout
        #: The service's name.
        self.service = f'{observed.fully_qualified_name}/get_type_description'
        #: True when the node was seen serving it.
        self.served = any(e.name == self.service for e in observed.service_servers)
        self._client: Any = None
        self._silent = False

    def ask(self, type_name: str, type_hash: str) -> tuple[str, dict[str, Any] | None]:
        """``('described', description)`` (shaped like the generator's), ``('refused', None)``
        when the node uses no type of that name and hash, ``('silent', None)`` when it serves
        no descriptions or does not answer."""
        if not self.served or self._silent:
            return 'silent', None
        from type_description_interfaces.srv import GetTypeDescription  # type: ignore[import-untyped]

        executor = self.session.nodl_executor
        deadline = time.monotonic() + self.timeout
        if self._client is None:
            self._client = self.session.create_client(GetTypeDescription, self.service)
        while not self._client.service_is_ready() and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.05)
        if not self._client.service_is_ready():
            self._silent = True
            return 'silent', None
        future = self._client.call_async(GetTypeDescription.Request(
            type_name=type_name, type_hash=type_hash, include_type_sources=False))
        while not future.done() and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.05)
        answer = future.result() if future.done() else None
        if answer is None:
            self._silent = True  # one unanswered question is enough: do not wait on each
            return 'silent', None
        if not answer.successful:
            return 'refused', None
        return 'described', {
            'type_description': _individual(answer.type_description.type_description),
            'referenced_type_descriptions': [
                _individual(r) for r in answer.type_description.referenced_type_descriptions]}

    def close(self) -> None:
        """Destroy the client (if one was made)."""
        if self._client is not None:
            self.session.destroy_client(self._client)
            self._client = None


def running_description(session: Any, observed: ObservedNode, type_name: str, type_hash: str,
                        timeout: float = ANSWER_TIMEOUT) -> dict[str, Any] | None:
    """The node's own description of a type (from ``~/get_type_description``), as a dict
    shaped like the generator's; None when the node serves none, refuses or does not answer."""
    asker = TypeDescriptions(session, observed, timeout)
    asker.served = True  # asked whether or not the observation listed the service
    try:
        return asker.ask(type_name, type_hash)[1]
    finally:
        asker.close()


def _individual(message: Any) -> dict[str, Any]:
    return {'type_name': message.type_name, 'fields': [
        {'name': f.name, 'default_value': f.default_value,
         'type': {'type_id': f.type.type_id, 'capacity': f.type.capacity,
                  'string_capacity': f.type.string_capacity,
                  'nested_type_name': f.type.nested_type_name}}
        for f in message.fields]}


class _Unreadable(Exception):
    """The installed definition of a type cannot be read (the reason is the message)."""


def _installed(index: InterfaceIndex, name: str) -> str | None:
    """The installed hash of ``name``; None when it is not installed here (nothing to
    compare with: ``validate --types`` says so); _Unreadable for a malformed file."""
    try:
        return type_hash(index, name)
    except InterfaceFileError as exc:
        raise _Unreadable(str(exc)) from None
    except LookupError:
        return None


def _fields(index: InterfaceIndex, asker: TypeDescriptions, type_name: str, reported: str) -> str:
    """The differing fields in words, from the node's own description of ``type_name``."""
    status, running = asker.ask(type_name, reported)
    if running is None:
        return ('the node serves no description of it (~/get_type_description), so the '
                'differing fields are unknown')
    lines = description_differences(type_description(index, type_name), running)
    return '; '.join(lines) if lines else 'the fields agree; their order or defaults differ'


def _advice(type_name: str) -> str:
    return (f'rebuild it against the installed {type_name.split("/")[0]}, or install the version '
            'it was built with')


def _topic(index: InterfaceIndex, asker: TypeDescriptions, session: Any, observed: ObservedNode,
           section: str, endpoint: ObservedEndpoint, where: Location | None) -> LiveDiagnostic | None:
    reported = _reported_hash(session, endpoint.name, observed, section == 'publishers')
    try:
        installed = _installed(index, endpoint.type)
    except _Unreadable as exc:
        return LiveDiagnostic('skew_unverifiable', section, endpoint.name,
                              f"{endpoint.name}: the installed definition of '{endpoint.type}' cannot "
                              f'be read ({exc}), so its hash is not compared', location=where)
    if installed is None:
        return None
    if reported is None:
        return LiveDiagnostic('skew_unverifiable', section, endpoint.name,
                              f'{endpoint.name}: the middleware reports no type hash', location=where)
    if reported == installed:
        return None
    return LiveDiagnostic(
        'version_skew', section, endpoint.name,
        f"{endpoint.name}: the node uses another definition of '{endpoint.type}' than the "
        f'installed one ({_fields(index, asker, endpoint.type, reported)}); '
        f'{_advice(endpoint.type)}', declared=installed, observed=reported, location=where)


def _service_parts(index: InterfaceIndex, asker: TypeDescriptions, session: Any,
                   observed: ObservedNode, service: str, type_name: str,
                   server: bool) -> list[str] | None:
    """What differs of a service type (``type_name``) at ``service``, in words (empty: the
    same); None when it cannot be compared.  _Unreadable for a malformed installed file."""
    installed = _installed(index, type_name)
    if installed is None:
        return []
    parts = _service_hashes(session, service, observed, server)
    if parts is not None:
        out = []
        for part, reported in parts.items():
            wanted = _installed(index, f'{type_name}_{part}')
            if wanted is not None and wanted != reported:
                out.append(f'its {part.lower()} ({type_name}_{part}) differs')
        if out:
            out.append('the graph reports no description of a service\'s parts, so the '
                       'differing fields are not named')
        return out
    status, _ = asker.ask(type_name, installed)
    if status == 'silent':
        return None
    if status == 'refused':
        return [f'its ~/get_type_description knows no {type_name} of the installed hash '
                f'{installed}']
    return []


def _service(index: InterfaceIndex, asker: TypeDescriptions, session: Any, observed: ObservedNode,
             section: str, endpoint: ObservedEndpoint, where: Location | None,
             unchecked: list[str]) -> LiveDiagnostic | None:
    try:
        parts = _service_parts(index, asker, session, observed, endpoint.name, endpoint.type,
                               section == 'service_servers')
    except _Unreadable as exc:
        return LiveDiagnostic('skew_unverifiable', section, endpoint.name,
                              f"{endpoint.name}: the installed definition of '{endpoint.type}' cannot "
                              f'be read ({exc}), so its hash is not compared', location=where)
    if parts is None:
        unchecked.append(endpoint.name)
        return None
    if not parts:
        return None
    return LiveDiagnostic('version_skew', section, endpoint.name,
                          f"{endpoint.name}: the node uses another definition of '{endpoint.type}' "
                          f"than the installed one ({'; '.join(parts)}); {_advice(endpoint.type)}",
                          location=where)


def _action(index: InterfaceIndex, asker: TypeDescriptions, session: Any, observed: ObservedNode,
            section: str, endpoint: ObservedEndpoint, where: Location | None,
            unchecked: list[str]) -> LiveDiagnostic | None:
    """The action's feedback and status topics (hashes in the graph), its goal and result
    services (as services are checked); one difference naming every part that differs."""
    server = section == 'action_servers'
    action, name = endpoint.type, endpoint.name
    found: list[str] = []
    compared = False
    try:
        for topic, type_name, what in (
                ('feedback', f'{action}_FeedbackMessage', 'feedback'),
                ('status', 'action_msgs/msg/GoalStatusArray', 'status')):
            installed = _installed(index, type_name)
            reported = _reported_hash(session, f'{name}{ACTION_INFIX}{topic}', observed, server)
            if installed is None or reported is None:
                continue
            compared = True
            if reported != installed:
                found.append(f'its {what} ({type_name}) differs: '
                             f'{_fields(index, asker, type_name, reported)}')
        for service, part in (('send_goal', 'SendGoal'), ('get_result', 'GetResult')):
            parts = _service_parts(index, asker, session, observed,
                                   f'{name}{ACTION_INFIX}{service}', f'{action}_{part}', server)
            if parts is None:
                unchecked.append(f'{name} ({"goal" if part == "SendGoal" else "result"})')
                continue
            compared = True
            found += parts
    except _Unreadable as exc:
        return LiveDiagnostic('skew_unverifiable', section, name,
                              f"{name}: the installed definition of '{action}' cannot be read "
                              f'({exc}), so its hash is not compared', location=where)
    if not compared and _installed(index, action) is not None:
        return LiveDiagnostic('skew_unverifiable', section, name,
                              f'{name}: the middleware reports no type hash for any part of the action',
                              location=where)
    if not found:
        return None
    return LiveDiagnostic('version_skew', section, name,
                          f"{name}: the node uses another definition of '{action}' than the installed "
                          f"one ({'; '.join(found)}); {_advice(action)}", location=where)


def type_skew(session: Any, observed: ObservedNode, index: InterfaceIndex,
              locations: dict[tuple[str, str], Location] | None = None) -> list[LiveDiagnostic]:
    """A ``version_skew`` difference (NODL420) for each endpoint of ``observed`` whose type
    is not the installed definition: topics by their reported hash, naming the differing
    fields; actions by their feedback and status topics and goal and result services;
    services by the hashes beneath them or the node's ``~/get_type_description``.

    A ``skew_unverifiable`` one (NODL421, info) where an endpoint cannot be compared (no
    hash reported, or an installed file that cannot be read); one ``services_unverifiable``
    (NODL422, info) for all the services (and action goals and results) the node gives no
    way to compare.  A type that is not installed here is not compared.
    """
    asker = TypeDescriptions(session, observed)
    out: list[LiveDiagnostic] = []
    unchecked: list[str] = []
    try:
        for section in TOPIC_SECTIONS + ACTION_SECTIONS + SERVICE_SECTIONS:
            for endpoint in getattr(observed, section):
                where = (locations or {}).get((section, endpoint.name))
                if section in TOPIC_SECTIONS:
                    found = _topic(index, asker, session, observed, section, endpoint, where)
                elif section in ACTION_SECTIONS:
                    found = _action(index, asker, session, observed, section, endpoint, where,
                                    unchecked)
                else:
                    found = _service(index, asker, session, observed, section, endpoint, where,
                                     unchecked)
                if found is not None:
                    out.append(found)
    finally:
        asker.close()
    if unchecked:
        own = observed.fully_qualified_name + '/'  # the base's services (parameters...) last
        unchecked.sort(key=lambda n: n.startswith(own))
        shown = ', '.join(unchecked[:12]) + (f' and {len(unchecked) - 12} more'
                                              if len(unchecked) > 12 else '')
        out.append(LiveDiagnostic(
            'services_unverifiable', 'service_servers', observed.fully_qualified_name,
            f'{observed.fully_qualified_name}: the service types of this node cannot be compared '
            'with the installed definitions (the middleware reports no hash for services, and '
            f'the node serves no ~/get_type_description): {shown}'))
    return out
