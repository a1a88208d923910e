"""``describe``: a node definition written from what a running node exposes.

The base is deduced (``lifecycle_node`` when the node serves the lifecycle
services, else ``node``) and the base's own entities are left out of
``main``.  Names under the node become ``~/x``, names under its namespace
relative, others stay absolute.  What the middleware cannot report is not
invented: it is listed in the header comment and returned as notes (topic
history and depth on some middlewares, service QoS).
"""

from __future__ import annotations

from typing import Any

from nodl_schema.composition.bases import base_layer
from nodl_schema.live.observe import ObservedNode, ObservedParameter, observe_node
from nodl_schema.model import ENDPOINT_SECTIONS
from nodl_schema.naming import expand, relativize
from nodl_schema.vocabulary import QOS_KEYS, TOPIC_SECTIONS

__all__ = ['Description', 'deduce_base', 'describe_observed', 'describe_node', 'render_description']

_LIFECYCLE_SERVICES = ('change_state', 'get_state', 'get_available_states',
                       'get_available_transitions', 'get_transition_graph')


class Description:
    """A described node: the definition (a plain dict) and what could not be observed."""

    def __init__(self, fqn: str, definition: dict[str, Any], notes: list[str]) -> None:
        self.fqn = fqn
        self.definition = definition
        self.notes = notes


def deduce_base(observed: ObservedNode) -> str:
    """``lifecycle_node`` if the node serves the lifecycle services, else ``node``."""
    served = {e.name for e in observed.service_servers}
    if all(expand('~/' + s, observed.name, observed.namespace) in served
           for s in _LIFECYCLE_SERVICES):
        return 'lifecycle_node'
    return 'node'


def _parameter(param: ObservedParameter) -> dict[str, Any]:
    out: dict[str, Any] = {'type': param.type}
    if param.value is not None and param.type != 'none':
        out['default_value'] = param.value
    if param.description:
        out['description'] = param.description
    if param.read_only:
        out['read_only'] = True
    if param.range is not None:
        low, high = param.range
        out['validation'] = {'bounds<>': [low, high]}
    return out


def describe_observed(observed: ObservedNode) -> Description:
    """Turn an observation into a node definition (as a plain, valid dict)."""
    base = deduce_base(observed)
    base_iface = base_layer(base).interface
    name, namespace = observed.name, observed.namespace
    notes = list(observed.notes)
    main: dict[str, Any] = {'nodl_version': 2}

    if observed.parameters:
        inherited = base_iface.parameters or {}
        params = {k: _parameter(p) for k, p in sorted(observed.parameters.items())
                  if k not in inherited and not k.startswith('qos_overrides.')}
        if params:
            main['parameters'] = params

    unobserved: set[str] = set()
    for section in ENDPOINT_SECTIONS:
        from_base = {(expand(e.name, name, namespace), e.type) for e in base_iface.endpoints(section)}
        entries = []
        for endpoint in getattr(observed, section):
            if (endpoint.name, endpoint.type) in from_base:
                continue
            entry: dict[str, Any] = {'name': relativize(endpoint.name, name, namespace),
                                     'type': endpoint.type}
            if section in TOPIC_SECTIONS:
                qos = dict(endpoint.qos or {})
                unobserved.update(endpoint.unobserved)
                if 'history' not in qos:
                    # The schema needs a history; SYSTEM_DEFAULT claims nothing about it.
                    qos['history'] = 'SYSTEM_DEFAULT'
                if 'reliability' not in qos:
                    qos['reliability'] = 'SYSTEM_DEFAULT'
                entry['qos'] = {k: qos[k] for k in QOS_KEYS if k in qos}
            entries.append(entry)
        if entries:
            main[section] = entries

    if unobserved & {'history', 'depth'}:
        notes.append('topic history and depth are not reported by the middleware: written as '
                     'history SYSTEM_DEFAULT without a depth; fill in the real values')
    for field in sorted(unobserved - {'history', 'depth', 'qos'}):
        notes.append(f'topic {field} was not reported by the middleware for some endpoints')
    if 'qos' in unobserved:
        notes.append('the QoS of some topic endpoints could not be read')
    if main.get('service_servers') or main.get('service_clients'):
        notes.append('service QoS cannot be observed (no graph API reports it): left out')
    definition = {'nodl_version': 2, 'base': base, 'main': main}
    return Description(observed.fully_qualified_name, definition, notes)


def describe_node(fqn: str, *, timeout: float = 5.0, parameters: bool = True,
                  session: Any = None) -> Description:
    """Observe the running node ``fqn`` and describe it (raises LiveError for the user).

    ``session``: an observer node of :func:`~nodl_schema.live.session.ros_session` to reuse.
    """
    return describe_observed(observe_node(fqn, timeout=timeout, parameters=parameters,
                                          session=session))


def render_description(description: Description, format: str = 'yaml') -> str:
    """The definition as a file: YAML with a header comment, or JSON."""
    from nodl_schema.loading import dump_nodl

    if format == 'json':
        return dump_nodl(description.definition, 'json')
    header = [f'# Described from the running node {description.fqn} by `nodl describe`.']
    if description.notes:
        header.append('# Not observable, so not stated here:')
        header += [f'#   - {note}' for note in description.notes]
    # Marks what describe cannot know (see nodl_schema.overrides): no 'has no description'
    # warning, even with --strict, until someone writes the descriptions.
    header.append('# nodl: ignore=NODL216 (a running node has no descriptions: write them, '
                  'then remove this line)')
    return '\n'.join(header) + '\n' + dump_nodl(description.definition, 'yaml')
