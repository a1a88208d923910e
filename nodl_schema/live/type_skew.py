"""Version skew: a running node built against another definition of a type than the installed one.

The middleware reports each topic endpoint's type hash (RIHS01).  It is
compared with the hash of the installed definition of the same type name
(computed by :mod:`nodl_schema.interface_types.hashes` from the files the
ament index lists).  When they differ, the node's ``~/get_type_description``
service (rclcpp and rclpy nodes serve it by default) is asked for the
definition it was built with, and the differing fields are named.
"""

from __future__ import annotations

from typing import Any

from nodl_schema.live.conformance import Difference, Remaps, final_name
from nodl_schema.live.observe import ObservedNode
from nodl_schema.system.entities import Location
from nodl_schema.vocabulary import TOPIC_SECTIONS

TYPE_CHECKING = False
if TYPE_CHECKING:
    from nodl_schema.interface_types.resolve import InterfaceIndex
    from nodl_schema.system.resolved import ResolvedNode

__all__ = ['type_skew', 'declared_locations', 'running_description']


def declared_locations(resolved: ResolvedNode, observed: ObservedNode,
                       remaps: Remaps = None) -> dict[tuple[str, str], Location]:
    """``(section, final name)`` -> where the endpoint is declared."""
    where = {id(e.definition): e.location for e in resolved.entities}
    out: dict[tuple[str, str], Location] = {}
    for section in TOPIC_SECTIONS:
        for entity in resolved.interface.endpoints(section):
            location = where.get(id(entity))
            if location is not None:
                out[(section, final_name(entity.name, section, observed, remaps))] = location
    return out


def _reported_hash(session: Any, topic: str, observed: ObservedNode, publishers: bool) -> str | None:
    infos = (session.get_publishers_info_by_topic(topic) if publishers
             else session.get_subscriptions_info_by_topic(topic))
    for info in infos:
        if info.node_name == observed.name and info.node_namespace == observed.namespace:
            text = str(info.topic_type_hash)
            return text if text.startswith('RIHS01_') else None
    return None


def running_description(session: Any, observed: ObservedNode, type_name: str, type_hash: str,
                        timeout: float = 2.0) -> dict[str, Any] | None:
    """The node's own description of a type (from ``~/get_type_description``), as a dict
    shaped like the generator's; None when the node serves none or does not answer."""
    import time

    from type_description_interfaces.srv import GetTypeDescription  # type: ignore[import-untyped]

    service = f'{observed.fully_qualified_name}/get_type_description'
    client = session.create_client(GetTypeDescription, service)
    try:
        deadline = time.monotonic() + timeout
        while not client.service_is_ready() and time.monotonic() < deadline:
            session.nodl_executor.spin_once(timeout_sec=0.05)
        if not client.service_is_ready():
            return None
        future = client.call_async(GetTypeDescription.Request(
            type_name=type_name, type_hash=type_hash, include_type_sources=False))
        while not future.done() and time.monotonic() < deadline:
            session.nodl_executor.spin_once(timeout_sec=0.05)
        answer = future.result() if future.done() else None
        if answer is None or not answer.successful:
            return None
        return {'type_description': _individual(answer.type_description.type_description),
                'referenced_type_descriptions': [
                    _individual(r) for r in answer.type_description.referenced_type_descriptions]}
    finally:
        session.destroy_client(client)


def _individual(message: Any) -> dict[str, Any]:
    return {'type_name': message.type_name, 'fields': [
        {'name': f.name, 'default_value': f.default_value,
         'type': {'type_id': f.type.type_id, 'capacity': f.type.capacity,
                  'string_capacity': f.type.string_capacity,
                  'nested_type_name': f.type.nested_type_name}}
        for f in message.fields]}


def type_skew(session: Any, observed: ObservedNode, index: InterfaceIndex,
              locations: dict[tuple[str, str], Location] | None = None) -> list[Difference]:
    """A ``version_skew`` difference (NODL420) for each topic endpoint of ``observed`` whose
    reported type hash is not the installed definition's, naming the differing fields;
    a ``skew_unverifiable`` one (NODL421, info) where the hashes cannot be compared (no hash
    reported, or an installed file that cannot be read).  A type that is not installed
    here is not compared."""
    from nodl_schema.interface_types.hashes import description_differences, type_description, type_hash
    from nodl_schema.interface_types.tree import InterfaceFileError

    out: list[Difference] = []
    for section in TOPIC_SECTIONS:
        for endpoint in getattr(observed, section):
            where = (locations or {}).get((section, endpoint.name))
            reported = _reported_hash(session, endpoint.name, observed, section == 'publishers')
            try:
                installed = type_hash(index, endpoint.type)
            except InterfaceFileError as exc:
                out.append(Difference('skew_unverifiable', section, endpoint.name,
                                      f"{endpoint.name}: the installed definition of "
                                      f"'{endpoint.type}' cannot be read ({exc}), so its hash is "
                                      'not compared', location=where))
                continue
            except LookupError:
                continue  # not installed here: nothing to compare with (validate --types says so)
            if reported is None:
                out.append(Difference('skew_unverifiable', section, endpoint.name,
                                      f'{endpoint.name}: the middleware reports no type hash',
                                      location=where))
                continue
            if reported == installed:
                continue
            running = running_description(session, observed, endpoint.type, reported)
            if running is None:
                detail = ('the node serves no description of it (~/get_type_description), so '
                          'the differing fields are unknown')
            else:
                lines = description_differences(type_description(index, endpoint.type), running)
                detail = '; '.join(lines) if lines else 'the fields agree; their order or defaults differ'
            out.append(Difference(
                'version_skew', section, endpoint.name,
                f"{endpoint.name}: the node uses another definition of '{endpoint.type}' than the "
                f'installed one ({detail}); rebuild it against the installed '
                f'{endpoint.type.split("/")[0]}, or install the version it was built with',
                declared=installed, observed=reported, location=where))
    return out
