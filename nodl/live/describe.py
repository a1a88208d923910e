"""``describe``: a node definition written from what a running node exposes.

The base is deduced (``lifecycle_node`` when the node serves the lifecycle
services, else ``node``) and the base's own entities are left out of
``main``.  Names under the node become ``~/x``, names under its namespace
relative, others stay absolute.  What the middleware cannot report is not
invented: it is listed in the header comment and returned as notes (topic
history and depth on some middlewares, service QoS).  What makes the
observation itself doubtful (a name several nodes share) is a warning, on a
header line of its own.

Each observed endpoint's type is also compared with the installed definition
(version skew, :mod:`nodl.live.type_skew`): a difference is a warning
(NODL423), written as a comment next to the entity it concerns.
"""

from __future__ import annotations

import time
from typing import Any

from nodl.composition.bases import base_layer
from nodl.composition.client_library import ClientLibraryChoice
from nodl.live.observe import DISCOVERY_WINDOW, ObservedNode, ObservedParameter, observe_node, recount, watched_line
from nodl.model import ENDPOINT_SECTIONS, Base, Interface, Node, ParameterDefinition, QoSProfile
from nodl.naming import NodeNames, declared_names, expand, relativize
from nodl.vocabulary import QOS_KEYS, SERVICE_SECTIONS, TOPIC_SECTIONS

__all__ = ['Description', 'deduce_base', 'deduce_client_library', 'describe_observed',
           'describe_node', 'render_description', 'add_type_skew', 'annotate_yaml']


def _lifecycle_services() -> list[str]:
    """The services only a lifecycle node serves (from the bases, not a second list)."""
    plain = {s.name for s in base_layer('node').interface.endpoints('service_servers')}
    return [s.name for s in base_layer('lifecycle_node').interface.endpoints('service_servers')
            if s.name not in plain]


class Description:
    """A described node: the definition (a typed :class:`~nodl.model.Node`), what
    could not be observed, what makes the observation doubtful, and the client library
    whose base entities were left out."""

    def __init__(self, fqn: str, node: Node, notes: list[str],
                 client_library: ClientLibraryChoice | None = None,
                 warnings: list[str] | None = None) -> None:
        self.fqn = fqn
        #: The node definition, typed.
        self.node = node
        #: What could not be observed, so is not stated (one line each).
        self.notes = notes
        #: What makes the observation itself doubtful (several nodes share the name).
        self.warnings = list(warnings or [])
        self.client_library = client_library or ClientLibraryChoice('rclpy', 'the default')
        #: Every name the node could declare for each endpoint written, by ``(section,
        #: written name)``, the written one first (see :func:`describe_observed`'s ``names``).
        self.forms: dict[tuple[str, str], list[str]] = {}
        #: The final names no name the node could declare resolves to (kept as observed).
        self.unmapped: list[tuple[str, str]] = []
        #: Seconds of discovery namesakes were watched for (None: not counted); the
        #: header says it (:func:`~nodl.live.observe.watched_line`).
        self.watched: float | None = None
        #: The name written for each observed endpoint, by ``(section, final name)``.
        self.written: dict[tuple[str, str], str] = {}
        #: The version-skew findings (:func:`add_type_skew`): endpoints whose type differs
        #: from the installed definition (NODL420 kind ``version_skew``), or that cannot be
        #: compared (``skew_unverifiable``, ``services_unverifiable``: notes).
        self.skew: list[Any] = []

    @property
    def skew_warnings(self) -> list[str]:
        """The version skews in words, one line each (warnings: NODL423)."""
        return [d.message for d in self.skew if d.kind == 'version_skew']

    @property
    def skew_notes(self) -> list[str]:
        """What of the types could not be compared with the installed definitions."""
        return [d.message for d in self.skew if d.kind != 'version_skew']

    def skew_comments(self) -> dict[tuple[str, str], list[str]]:
        """Comment lines for the written definition, by ``(section, written name)``."""
        out: dict[tuple[str, str], list[str]] = {}
        for d in self.skew:
            if d.kind != 'version_skew':
                continue
            written = self.written.get((d.section, d.name), d.name)
            out.setdefault((d.section, written), []).append(f'Version skew: {d.message}')
        return out

    @property
    def definition(self) -> dict[str, Any]:
        """The node definition as the mapping a file holds (made from :attr:`node`)."""
        return self.node.to_dict()


def deduce_base(observed: ObservedNode) -> str:
    """``lifecycle_node`` if the node serves the lifecycle services, else ``node``."""
    served = {e.name for e in observed.service_servers}
    if all(expand(s, observed.name, observed.namespace) in served for s in _lifecycle_services()):
        return 'lifecycle_node'
    return 'node'


#: What only an rclcpp node has: its time source's subscription (see the rclcpp base additions).
_RCLCPP_MARK = ('subscriptions', '/parameter_events', 'rcl_interfaces/msg/ParameterEvent')


def deduce_client_library(observed: ObservedNode,
                          requested: str | None = None) -> ClientLibraryChoice:
    """The client library the node is written with: ``requested``, else rclcpp if the node
    subscribes to /parameter_events (as rclcpp's time source does), else rclpy."""
    from nodl.composition.client_library import choose_client_library

    if requested is not None:
        return choose_client_library(requested)
    section, topic, type_ = _RCLCPP_MARK
    if any(e.name == topic and e.type == type_ for e in getattr(observed, section)):
        return ClientLibraryChoice('rclcpp', f'the node subscribes to {topic}, as rclcpp\'s time '
                                   'source does')
    return ClientLibraryChoice('rclpy', f'the node does not subscribe to {topic}, as rclcpp '
                               'nodes do')


def _parameter(param: ObservedParameter) -> ParameterDefinition:
    return ParameterDefinition(
        param.type,
        param.value if param.value is not None and param.type != 'none' else None,
        param.description or '',
        bool(param.read_only),
        validation={'bounds<>': list(param.range)} if param.range is not None else None)


def describe_observed(observed: ObservedNode, client_library: str | None = None, *,
                      names: NodeNames | None = None) -> Description:
    """Turn an observation into a node definition (a typed, valid :class:`Node`).

    The entities of the base of ``client_library`` are left out of ``main``;
    by default the library is deduced from the node (:func:`deduce_client_library`).
    ValueError for an unknown client library.

    ``names``: the node's final name, namespace and remapping rules, when known (from a
    launch file): each final name is then turned back into the name the node declares
    (:func:`~nodl.naming.declared_names`: the remaps undone, ``~/x`` under the
    node, relative under its namespace, the root's included); a final name no declared
    name resolves to is kept as observed, with a note.  Without it, names are only made
    relative (:func:`~nodl.naming.relativize`).
    """
    library = deduce_client_library(observed, client_library)
    base = deduce_base(observed)
    base_iface = base_layer(base, library.name).interface
    name, namespace = observed.name, observed.namespace
    notes = list(observed.notes)
    main = Interface(nodl_version=2)

    if observed.parameters:
        inherited = base_iface.parameters or {}
        params = {k: _parameter(p) for k, p in sorted(observed.parameters.items())
                  if k not in inherited and not k.startswith('qos_overrides.')}
        if params:
            main.parameters = params

    unobserved: set[str] = set()
    forms: dict[tuple[str, str], list[str]] = {}
    unmapped: list[tuple[str, str]] = []
    written: dict[tuple[str, str], str] = {}
    for section in ENDPOINT_SECTIONS:
        service = section in SERVICE_SECTIONS
        from_base = {(_final(e.name, name, namespace, names, service), e.type)
                     for e in base_iface.endpoints(section)}
        make = ENDPOINT_SECTIONS[section]
        entries = []
        for endpoint in getattr(observed, section):
            if (endpoint.name, endpoint.type) in from_base:
                continue
            if names is None:
                short = relativize(endpoint.name, name, namespace)
            else:
                candidates = declared_names(endpoint.name, names, service=service)
                if not candidates:
                    unmapped.append((section, endpoint.name))
                    candidates = [endpoint.name]
                short = candidates[0]
                forms[(section, short)] = candidates
            written[(section, endpoint.name)] = short
            if section not in TOPIC_SECTIONS:
                entries.append(make(short, endpoint.type))
                continue
            qos = dict(endpoint.qos or {})
            unobserved.update(endpoint.unobserved)
            if 'history' not in qos:
                # The schema needs a history; SYSTEM_DEFAULT claims nothing about it.
                qos['history'] = 'SYSTEM_DEFAULT'
            if 'reliability' not in qos:
                qos['reliability'] = 'SYSTEM_DEFAULT'
            entries.append(make(short, endpoint.type,
                                QoSProfile.from_dict({k: qos[k] for k in QOS_KEYS if k in qos})))
        if entries:
            setattr(main, section, entries)

    if unobserved & {'history', 'depth'}:
        notes.append('topic history and depth are not reported by the middleware: written as '
                     'history SYSTEM_DEFAULT without a depth; fill in the real values')
    for field in sorted(unobserved - {'history', 'depth', 'qos'}):
        notes.append(f'topic {field} was not reported by the middleware for some endpoints')
    if 'qos' in unobserved:
        notes.append('the QoS of some topic endpoints could not be read')
    if main.service_servers or main.service_clients:
        notes.append('service QoS cannot be observed (no graph API reports it): left out')
    for section, final in unmapped:
        notes.append(f'{final} ({section}): no name the node could declare becomes it under '
                     'its remapping rules (a name from a parameter, or a rule only the running '
                     'launch knows?): written as observed')
    definition = Node(main, 2, Base(base))
    description = Description(observed.fully_qualified_name, definition, notes, library,
                              list(observed.warnings))
    description.forms = forms
    description.unmapped = unmapped
    description.written = written
    description.watched = observed.watched
    return description


def _final(declared: str, name: str, namespace: str, names: NodeNames | None,
           service: bool) -> str:
    """The final name of a base entity ``declared`` by the node (its rules applied when
    ``names`` is known)."""
    if names is not None:
        try:
            return names.resolve(declared, service=service)
        except ValueError:
            pass
    return expand(declared, name, namespace)


def describe_node(fqn: str, *, timeout: float = 5.0, parameters: bool = True,
                  session: Any = None, client_library: str | None = None,
                  types: bool = True, watch: float = DISCOVERY_WINDOW) -> Description:
    """Observe the running node ``fqn`` and describe it (raises LiveError for the user).

    ``session``: an observer node of :func:`~nodl.live.session.ros_session` to reuse;
    ``client_library``: see :func:`describe_observed`; ``types``: compare each endpoint's
    type with the installed definition (:func:`add_type_skew`); ``watch``: seconds of
    discovery to watch for namesakes at least (see :func:`~nodl.live.observe.observe_node`;
    the version skew is read while they are watched for).
    """
    if session is None and types:
        from nodl.live.session import ros_session

        with ros_session() as own:
            return describe_node(fqn, timeout=timeout, parameters=parameters, session=own,
                                 client_library=client_library, types=types, watch=watch)
    if not types:
        return describe_observed(observe_node(fqn, timeout=timeout, parameters=parameters,
                                              session=session, watch=watch), client_library)
    # the types are compared before namesakes are counted: the watch goes on meanwhile
    deadline = time.monotonic() + timeout
    observed = observe_node(fqn, timeout=timeout, parameters=parameters, session=session,
                            watch=0.0)
    description = describe_observed(observed, client_library)
    add_type_skew(description, session, observed)
    recount(session, observed, watch, deadline)
    description.warnings = list(observed.warnings)
    description.watched = observed.watched
    return description


def add_type_skew(description: Description, session: Any, observed: ObservedNode,
                  index: Any = None) -> Description:
    """Compare the observed endpoints' types with the installed definitions (``index``:
    an :class:`~nodl.interface_types.InterfaceIndex`, by default the environment's)
    and keep what differs in :attr:`Description.skew`.  The endpoints the base gives are
    compared too (the node's build may predate the installed ``rcl_interfaces``)."""
    from nodl.live.type_skew import type_skew

    if index is None:
        from nodl.interface_types import interface_index

        index = interface_index()
    description.skew = type_skew(session, observed, index)
    return description


def annotate_yaml(text: str, comments: dict[tuple[str, str], list[str]]) -> tuple[str, list[str]]:
    """``text`` (a definition as :func:`~nodl.loading.dump_nodl` writes YAML) with
    each comment written above the entity it concerns, by ``(section, written name)``;
    also the comments whose entity is not in the text (for a header)."""
    import re

    import yaml

    from nodl.text_safety import one_line

    if not comments:
        return text, []
    left = dict(comments)
    out: list[str] = []
    section = None
    for line in text.splitlines(keepends=True):
        heading = re.match(r'^\s*([a-z_]+):\s*$', line)
        if heading:
            section = heading.group(1)
        entry = re.match(r'^(\s*)- name: (.*)$', line.rstrip('\n'))
        if entry and section is not None:
            try:
                name = yaml.safe_load(entry.group(2))
            except yaml.YAMLError:
                name = None
            for comment in left.pop((section, str(name)), []):
                out.append(f'{entry.group(1)}# {one_line(comment)}\n')
        out.append(line)
    return ''.join(out), [c for found in left.values() for c in found]


def render_description(description: Description, format: str = 'yaml') -> str:
    """The definition as a file: YAML with a header comment, or JSON."""
    from nodl.loading import dump_nodl
    from nodl.text_safety import one_line

    if format == 'json':
        return dump_nodl(description.node, 'json')
    # one line whatever a name or reason holds (a running node's text included): a comment
    # cannot break out, nor hold a control or bidi character
    header = [f'# Described from the running node {one_line(description.fqn)} by `nodl describe`.',
              f'# Left out: what the base gives an {one_line(description.client_library.name)} node '
              f'({one_line(description.client_library.reason)}).']
    header += [f'# Warning: {one_line(warning)}.' for warning in description.warnings]
    if description.watched is not None:
        header.append(f'# {watched_line(description.watched)[:1].upper()}'
                      f'{watched_line(description.watched)[1:]}.')
    body, unplaced = annotate_yaml(dump_nodl(description.node, 'yaml'), description.skew_comments())
    header += [f'# {one_line(comment)}' for comment in unplaced]
    notes = description.notes + description.skew_notes
    if notes:
        header.append('# Not observable, so not stated here:')
        header += [f'#   - {one_line(note)}' for note in notes]
    # Marks what describe cannot know (see nodl.overrides): no 'has no description'
    # warning, even with --strict, until someone writes the descriptions.
    header.append('# nodl: ignore=NODL216 (a running node has no descriptions: write them, '
                  'then remove this line)')
    return '\n'.join(header) + '\n' + body
