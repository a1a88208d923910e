"""``describe --all --launch``: the running system a launch file started, as a definitions
folder (overlay).

The launch file is analysed first (:func:`~nodl.system.run.analyse_launch`, no
checks): it says which nodes to expect, under which final names, and which package and
executable (or composable plugin) each one runs.  The observer then waits for exactly
those nodes, together, until they and their endpoints are seen and stable (or the
timeout passes), instead of a fixed discovery window.  Each observed node is described
with its final names turned back into the names its executable declares (its remaps
undone, ``~/x`` under the node, relative under its namespace), and the instances of
one executable are merged into one definition, filed as the overlay layout says
(:mod:`nodl.registry.overlay`):

* ``DIR/<package>/<executable>.nodl.yaml`` for a node started as a process;
* ``DIR/<package>/<class_in_snake_case>.nodl.yaml`` for a composable node, and its
  plugin recorded in ``DIR/<package>/nodes.yaml`` (with the node name a node launched
  without ``name=`` gives itself).

What the instances disagree on is said in the merged file's header and as a warning
(NODL410); what differs with their parameters, which a definition cannot express, is
left out of the definition and said (NODL411).  A lifecycle node's state is recorded;
one observed before ``configure`` lacks what it creates there (NODL413).  Hidden nodes
and nodes the launch file does not start are left out.  With ``missing``, so are the
launched nodes a definition already covers (registered in the ament index, or in a
definitions folder): only what nothing defines is waited for and described, so the folder
written never shadows a package's own definition.  Nothing here prints.
"""

from __future__ import annotations

import dataclasses
import os
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from nodl.diagnostics import Diagnostic, Severity
from nodl.live.describe import Description, annotate_yaml, describe_observed
from nodl.live.observe import (
    ObservedNode,
    count_nodes,
    list_nodes,
    observe_settled,
    read_lifecycle_states,
    read_parameters,
    settle_nodes,
)
from nodl.live.session import is_hidden_node, ros_session
from nodl.model import ENDPOINT_SECTIONS, Base, Interface, Node, ParameterDefinition
from nodl.vocabulary import TOPIC_SECTIONS

if TYPE_CHECKING:
    from nodl.launch.sandbox import LaunchLimits
    from nodl.registry.overlay import Definitions
    from nodl.system.launched import SystemNode

__all__ = ['OverlayFile', 'LaunchDescription', 'Instance', 'describe_launch', 'merge_instances',
           'render_merged']

#: How long the endpoints of the expected nodes must stay unchanged before they are taken.
QUIET = 0.15


@dataclass
class Instance:
    """One launched node as observed: the analysis's record, and what was seen."""

    #: The analysed launched node (final name, namespace, remaps, parameters, entry).
    launched: SystemNode
    observed: ObservedNode
    description: Description

    @property
    def fqn(self) -> str:
        """Its final fully qualified name."""
        return str(self.launched.fqn)

    @property
    def where(self) -> str:
        """``file:line:col`` of its launch entry."""
        loc = self.launched.location
        return f'{loc.file}:{loc.line}:{loc.column}' if loc.line else str(loc.file)

    def launch_values(self) -> dict[str, Any]:
        """The parameter values the launch gives it, by name."""
        return dict(self.launched.parameter_values())


@dataclass
class OverlayFile:
    """One definition written into the overlay, and what was said about it."""

    package: str
    #: The executable, or the registration key of a composable node (its class in snake case).
    key: str
    #: The file written (None when nothing could be written).
    path: str | None
    #: The merged definition.
    node: Node
    #: The instances it was described from.
    instances: list[Instance]
    #: The plugin of a composable node (``pkg::Class``).
    plugin: str | None = None
    #: The name the executable gives its node, when the launch gives none and it was observed.
    node_name: str | None = None
    #: Header lines: where the instances disagree, what was left out and why.
    comments: list[str] = field(default_factory=list)
    #: What could not be observed (one line each).
    notes: list[str] = field(default_factory=list)
    #: The client library whose base entities were left out, and why.
    client_library: str = 'rclpy'
    client_library_reason: str = ''


@dataclass
class LaunchDescription:
    """What ``describe --all --launch`` did."""

    launch_file: str
    #: The definitions written (one per package and executable or plugin).
    files: list[OverlayFile] = field(default_factory=list)
    #: The ``nodes.yaml`` files written.
    nodes_files: list[str] = field(default_factory=list)
    #: Coded diagnostics: the launch file's problems, nodes not observed, disagreements...
    diagnostics: list[Diagnostic] = field(default_factory=list)
    #: Nodes left out, with why (hidden, not started by the launch file).
    left_out: list[tuple[str, str]] = field(default_factory=list)
    #: Seconds the graph was watched for namesakes (nodes sharing a final name).
    watched: float = 0.0
    #: True when the launch file could not be read at all (nothing was observed).
    unreadable: bool = False

    @property
    def errors(self) -> list[Diagnostic]:
        """The diagnostics of severity error."""
        return [d for d in self.diagnostics if d.severity is Severity.ERROR]


def _diagnostic(code: str, severity: Severity, message: str, launched: SystemNode | None,
                launch_file: str, related: list[tuple[str, int, int, str]] | None = None
                ) -> Diagnostic:
    if launched is not None:
        loc = launched.location
        return Diagnostic(severity, message, (), str(loc.file), int(loc.line), int(loc.column),
                          code=code, related=related or ())
    return Diagnostic(severity, message, (), launch_file, 0, 0, code=code, related=related or ())


def _related(instance: Instance, message: str) -> tuple[str, int, int, str]:
    loc = instance.launched.location
    return (str(loc.file), int(loc.line), int(loc.column), message)


def _group_key(launched: SystemNode) -> tuple[str, str, str | None] | None:
    """``(package, key, plugin)`` a launched node is filed under, or None if unknown."""
    from nodl.registry.node_info import plugin_key

    entry = launched.entry
    if not entry.package:
        return None
    if entry.plugin:
        return entry.package, plugin_key(entry.plugin), entry.plugin
    if not entry.executable:
        return None
    return entry.package, entry.executable, None


def describe_launch(launch_file: str, arguments: Mapping[str, str] | None, directory: str, *,
                    timeout: float = 5.0, parameters: bool = True, format: str = 'yaml',
                    client_library: str | None = None, force: bool = False,
                    limits: LaunchLimits | None = None, prefixes: list[str] | None = None,
                    quiet: float = QUIET, types: bool = True,
                    definitions: Definitions | None = None,
                    missing: bool = False) -> LaunchDescription:
    """Describe the running system ``launch_file`` (with launch ``arguments``) started into
    the definitions folder ``directory`` (see the module docstring).

    ``timeout``: seconds to wait for every launched node and its endpoints (and for their
    parameter and lifecycle services).  ``limits``: whether and how the launch file's
    Python code runs (:class:`~nodl.launch.sandbox.LaunchLimits`; ``--no-exec``).
    ``types``: each node's endpoint types are compared with the installed definitions; a
    version skew is a warning (NODL423) and a comment next to the entity in its file.
    Files are written as :func:`~nodl.writing.write_marked` writes them (a file nodl
    did not write, or that was edited, stops the run with a
    :class:`~nodl.writing.WriteError` unless ``force``).  Problems in the launch
    file and with what was observed are :attr:`LaunchDescription.diagnostics`.

    ``definitions``: the definitions folders the launch file is analysed with, as ``nodl
    analyse`` does (the node names their ``nodes.yaml`` record), except ``directory`` itself:
    what it holds is what this run replaces.  ``missing``: describe only the launched nodes
    no definition covers (neither the ament index ``prefixes`` nor ``definitions``); the
    others are :attr:`LaunchDescription.left_out`, not waited for.
    """
    from nodl.system.run import LAUNCH_KIND, analyse_launch

    result = LaunchDescription(launch_file)
    if definitions:  # the folder written is refreshed by this run, not read by it
        from nodl.registry.overlay import Definitions

        written = os.path.realpath(directory)
        definitions = Definitions([f for f in definitions.folders
                                   if os.path.realpath(f.root) != written])
    analysis = analyse_launch(launch_file, arguments, prefixes=prefixes, checks={}, limits=limits,
                              definitions=definitions)
    result.diagnostics.extend(f.diagnostic for f in analysis.findings if f.kind == LAUNCH_KIND)
    if analysis.unreadable:
        result.unreadable = True
        return result

    expected: dict[str, int] = {}
    launched: list[SystemNode] = []
    covered: set[str] = set()  # launched, and left out because a definition covers them
    for node in analysis.nodes:
        if node.names is None:
            result.diagnostics.append(_diagnostic(
                'NODL416', Severity.WARNING, f'{node.executable_label}: its final name cannot be '
                'computed (see nodl analyse), so it cannot be found in the graph: left out',
                node, launch_file))
            continue
        if is_hidden_node(node.fqn):
            result.left_out.append((node.fqn, 'a hidden node (its name starts with _)'))
            continue
        if missing and node.match.file is not None:
            from nodl.system.launched import node_provenance

            covered.add(node.fqn)
            result.left_out.append((node.fqn, f'has a definition: {node.match.file} '
                                              f'({node_provenance(node)})'))
            continue
        if _group_key(node) is None:
            result.diagnostics.append(_diagnostic(
                'NODL416', Severity.WARNING, f'{node.fqn}: the launch file does not say which '
                'package and executable (or plugin) it runs, so it cannot be filed: left out',
                node, launch_file))
            continue
        expected[node.fqn] = expected.get(node.fqn, 0) + 1
        launched.append(node)

    instances: list[Instance] = []
    with ros_session() as session:
        raw, counts = settle_nodes(session, expected, timeout, quiet) if expected else ({}, {})
        seen = [fqn for fqn in expected if fqn in raw]
        observed = {fqn: observe_settled(session, fqn, raw[fqn]) for fqn in seen}
        if parameters and seen:
            read = read_parameters(session, seen, timeout)
            for fqn, table in read.items():
                observed[fqn].parameters = table
                if table is None:
                    observed[fqn].notes.append('parameters could not be read (the node serves no '
                                               'parameter services, or they did not answer in '
                                               'time)')
        from nodl.live.describe import deduce_base

        lifecycle = [fqn for fqn in seen if deduce_base(observed[fqn]) == 'lifecycle_node']
        if lifecycle:
            for fqn, state in read_lifecycle_states(session, lifecycle, timeout).items():
                observed[fqn].lifecycle_state = state
        skews: dict[str, list[Any]] = {}
        if types and seen:  # version skew: each endpoint's type against the installed one
            from nodl.interface_types import interface_index
            from nodl.live.type_skew import type_skew

            index = interface_index(prefixes=prefixes)
            skews = {fqn: type_skew(session, observed[fqn], index) for fqn in seen}
        # namesakes: every name the graph holds more often than the launch starts it
        counts = count_nodes(session)
        result.watched = time.monotonic() - float(getattr(session, 'nodl_started', time.monotonic()))
        for fqn in list_nodes(session):
            if fqn in expected or fqn in covered:
                continue
            why = ('a hidden node (its name starts with _)' if is_hidden_node(fqn)
                   else f'not started by {launch_file}')
            result.left_out.append((fqn, why))

    by_fqn: dict[str, list[SystemNode]] = {}
    for node in launched:
        by_fqn.setdefault(node.fqn, []).append(node)
    for fqn, nodes in by_fqn.items():
        if fqn not in observed:
            for node in nodes:
                hint = (' (the launch gives it no name: its program may name itself otherwise; '
                        'set name= in the launch file)' if node.name_assumed else '')
                result.diagnostics.append(_diagnostic(
                    'NODL409', Severity.ERROR, f'{fqn} ({node.executable_label}) was not seen in '
                    f'the graph within {timeout:g} s{hint}: not described (is the system running, '
                    'in this ROS_DOMAIN_ID?)', node, launch_file))
            continue
        seen_count = counts.get(fqn, 0)
        if seen_count > 1 or len(nodes) > 1:
            result.diagnostics.append(_diagnostic(
                'NODL414', Severity.WARNING, f'{seen_count} nodes in the graph are named {fqn} '
                f'(the launch file starts {len(nodes)}): the graph cannot tell their endpoints '
                'apart, so what was observed is all of them together (give each node a unique '
                'name)', nodes[0], launch_file))
        for node in nodes:
            description = describe_observed(observed[fqn], client_library, names=node.names)
            description.skew = skews.get(fqn, [])
            instances.append(Instance(node, observed[fqn], description))
            for message in description.skew_warnings:  # also a comment next to the entity
                result.diagnostics.append(_diagnostic(
                    'NODL423', Severity.WARNING, f'{fqn}: version skew: {message}', node,
                    launch_file))
            for section, final in description.unmapped:
                result.diagnostics.append(_diagnostic(
                    'NODL412', Severity.WARNING, f'{fqn}: {final} ({section}) is no name the node '
                    'could declare under its remapping rules (a name it reads from a parameter, '
                    'or a rule only the running launch knows?): written as observed', node,
                    launch_file))
            if observed[fqn].lifecycle_state == 'unconfigured':
                result.diagnostics.append(_diagnostic(
                    'NODL413', Severity.WARNING, f'{fqn} is a lifecycle node observed before '
                    "'configure' (state unconfigured): the endpoints it creates when configured "
                    'are missing from its definition; configure it and describe again',
                    node, launch_file))
        if not nodes[0].entry.remaps_complete:
            result.diagnostics.append(_diagnostic(
                'NODL415', Severity.WARNING, f'{fqn}: some of its remapping rules are known only '
                'to the running launch: names they remap are written as observed, not as the '
                'node declares them', nodes[0], launch_file))

    groups: dict[tuple[str, str], list[Instance]] = {}
    plugins: dict[tuple[str, str], str | None] = {}
    for instance in instances:
        filed = _group_key(instance.launched)
        assert filed is not None
        groups.setdefault(filed[:2], []).append(instance)
        plugins.setdefault(filed[:2], filed[2])
    for (package, key), members in groups.items():
        overlay, diagnostics = merge_instances(package, key, members, plugins[(package, key)],
                                               launch_file)
        result.diagnostics.extend(diagnostics)
        result.files.append(overlay)
    result.files.sort(key=lambda f: (f.package, f.key))
    _write(result, directory, format, force, arguments or {}, [launch_file, *analysis.files()])
    result.diagnostics.sort(key=lambda d: (d.file, d.line, d.column, d.code))
    return result


# -- merging the instances of one executable ------------------------------------------------


@dataclass
class _Group:
    """One endpoint across instances: its section, type, the names every member could
    declare for it, and each member's entity."""

    section: str
    type: str
    forms: list[str]
    members: dict[int, Any] = field(default_factory=dict)


def _endpoint_groups(instances: list[Instance]) -> list[_Group]:
    groups: list[_Group] = []
    for index, instance in enumerate(instances):
        main = instance.description.node.main
        for section in ENDPOINT_SECTIONS:
            for entity in main.endpoints(section):
                forms = instance.description.forms.get((section, entity.name), [entity.name])
                for group in groups:
                    if (group.section == section and group.type == entity.type
                            and index not in group.members
                            and any(f in forms for f in group.forms)):
                        group.forms = [f for f in group.forms if f in forms]
                        group.members[index] = entity
                        break
                else:
                    groups.append(_Group(section, entity.type, list(forms), {index: entity}))
    return groups


def _qos_text(entity: Any) -> str:
    qos = getattr(entity, 'qos', None)
    return str(qos.to_dict()) if qos is not None else ''


def _names(instances: list[Instance], indices: Any) -> str:
    return ', '.join(instances[i].fqn for i in sorted(indices))


def _differing_parameters(instances: list[Instance]) -> list[str]:
    """The launch parameters whose values differ between the instances that have an entity
    and those that do not."""
    values = [instance.launch_values() for instance in instances]
    names = sorted({n for v in values for n in v})
    return [name for name in names if len({repr(v.get(name, _UNSET)) for v in values}) > 1]


_UNSET = object()


def merge_instances(package: str, key: str, instances: list[Instance], plugin: str | None,
                    launch_file: str) -> tuple[OverlayFile, list[Diagnostic]]:
    """One definition of ``package``'s ``key`` from its observed ``instances``.

    What every instance shows is the definition.  An endpoint or parameter only some show
    is left out and said: as a difference their parameters explain (the launch gives them
    different values; a definition cannot express that: NODL411), or as a disagreement
    (NODL410).  Where a lifecycle instance shows what an unconfigured one cannot (it is
    created at ``configure``), the configured ones are believed.  A parameter every
    instance is given by the launch has no observable default: none is written.
    """
    first = instances[0]
    diagnostics: list[Diagnostic] = []
    comments: list[str] = []
    notes: list[str] = []
    everyone = set(range(len(instances)))
    states = [i.observed.lifecycle_state for i in instances]

    def disagree(what: str, having: set[int]) -> None:
        others = everyone - having
        # an unconfigured lifecycle instance lacks what configure creates: believe the others
        if all(states[i] == 'unconfigured' for i in others) and all(
                states[i] not in (None, 'unconfigured') for i in having):
            comments.append(f'{what}: seen on {_names(instances, having)} only; '
                            f'{_names(instances, others)} were not configured yet')
            return
        differing = _differing_parameters(instances)
        if differing:
            comments.append(f'Not in the definition: {what}: seen on {_names(instances, having)}, '
                            f'not on {_names(instances, others)}; their parameters differ '
                            f'({", ".join(differing)}), which a definition cannot express')
            diagnostics.append(_diagnostic(
                'NODL411', Severity.WARNING, f'{package} {key}: {what} is seen on '
                f'{_names(instances, having)} but not on {_names(instances, others)}, whose '
                f'parameters differ ({", ".join(differing)}): a definition cannot express an '
                'interface that depends on parameters, so it is left out',
                instances[min(having)].launched, launch_file,
                [_related(instances[i], f'{instances[i].fqn} is launched here')
                 for i in sorted(others)]))
            return
        comments.append(f'Instances disagree: {what}: seen on {_names(instances, having)}, not on '
                        f'{_names(instances, others)} (left out)')
        diagnostics.append(_diagnostic(
            'NODL410', Severity.WARNING, f'{package} {key}: its instances disagree: {what} is '
            f'seen on {_names(instances, having)} but not on {_names(instances, others)}: left '
            'out of the merged definition', instances[min(having)].launched, launch_file,
            [_related(instances[i], f'{instances[i].fqn} is launched here')
             for i in sorted(others)]))

    def believed(having: set[int]) -> bool:
        others = everyone - having
        return bool(others) and all(states[i] == 'unconfigured' for i in others) and all(
            states[i] not in (None, 'unconfigured') for i in having)

    base = first.description.node.base.value if first.description.node.base else 'node'
    library = first.description.client_library
    for index, instance in enumerate(instances[1:], 1):
        other = instance.description.node.base.value if instance.description.node.base else 'node'
        if other != base:
            disagree(f'base {other} (not {base})', {index})
    main = Interface(nodl_version=2)
    for group in _endpoint_groups(instances):
        having = set(group.members)
        name = group.forms[0] if group.forms else next(iter(group.members.values())).name
        what = f'{group.section[:-1].replace("_", " ")} {name} ({group.type})'
        if having != everyone and not believed(having):
            disagree(what, having)
            continue
        entity = group.members[min(having)]
        if not group.forms:
            disagree(f'{what}: no one name every instance could declare for it', having)
            continue
        if group.section in TOPIC_SECTIONS:
            qos = {i: _qos_text(e) for i, e in group.members.items()}
            if len(set(qos.values())) > 1:
                comments.append(f'Instances disagree: {what}: QoS differs between '
                                f'{_names(instances, having)}; written as on '
                                f'{instances[min(having)].fqn}')
                diagnostics.append(_diagnostic(
                    'NODL410', Severity.WARNING, f'{package} {key}: its instances disagree on the '
                    f'QoS of {what} ({_names(instances, having)}): written as on '
                    f'{instances[min(having)].fqn}', instances[min(having)].launched, launch_file))
        if entity.name != name:
            entity = dataclasses.replace(entity, name=name)
        current = list(main.endpoints(group.section))
        setattr(main, group.section, current + [entity])

    params = _merge_parameters(instances, disagree, comments, notes)
    if params:
        main.parameters = params
    node = Node(main, 2, Base(base))
    for instance in instances:
        for note in instance.description.notes:
            if note not in notes:
                notes.append(note)
    node_name = None
    launched = first.launched
    if not launched.entry.name and not any(i.launched.entry.name for i in instances):
        # launched without name=: the name observed is the one the program gives itself
        import re

        names = first.launched.names
        if names is not None and not any(rule.kind == 'node' for rule in names.rules) and \
                re.fullmatch(r'[A-Za-z_][A-Za-z0-9_]*', names.name):
            node_name = names.name
    overlay = OverlayFile(package, key, None, node, instances, plugin, node_name, comments, notes,
                          library.name, library.reason)
    return overlay, diagnostics


def _merge_parameters(instances: list[Instance], disagree: Any, comments: list[str],
                      notes: list[str]) -> dict[str, ParameterDefinition]:
    everyone = set(range(len(instances)))
    tables = [i.description.node.main.parameters or {} for i in instances]
    out: dict[str, ParameterDefinition] = {}
    for name in sorted({n for t in tables for n in t}):
        having = {i for i, t in enumerate(tables) if name in t}
        if having != everyone:
            disagree(f'parameter {name}', having)
            continue
        definitions = [tables[i][name] for i in sorted(having)]
        shapes = {(d.type, d.read_only, repr(d.validation), d.description) for d in definitions}
        if len(shapes) > 1:
            comments.append(f'Instances disagree: parameter {name}: its type or descriptor '
                            f'differs between {_names(instances, having)}; written as on '
                            f'{instances[0].fqn}')
        # the value observed is the launch's where the launch sets it: not a default
        unset = [i for i in sorted(having) if name not in instances[i].launch_values()]
        defaults = {repr(tables[i][name].default_value) for i in unset}
        chosen = definitions[0]
        if not unset:
            chosen = ParameterDefinition(chosen.type, None, chosen.description, chosen.read_only,
                                         validation=chosen.validation)
            notes.append(f'parameter {name}: its default is not observable (the launch file sets '
                         'it on every instance): written without one')
        else:
            chosen = tables[unset[0]][name]
            if len(defaults) > 1:
                comments.append(f'Instances disagree: parameter {name}: its value differs between '
                                f'{_names(instances, set(unset))}, which the launch does not set; '
                                f'written as on {instances[unset[0]].fqn}')
        out[name] = chosen
    return out


# -- writing --------------------------------------------------------------------------------


def render_merged(overlay: OverlayFile, launch_file: str, arguments: Mapping[str, str],
                  watched: float, format: str = 'yaml') -> str:
    """The merged definition as a file: YAML with its provenance and every remark in the
    header, or JSON (which has no room for them)."""
    from nodl.loading import dump_nodl
    from nodl.text_safety import one_line

    if format == 'json':
        return dump_nodl(overlay.node, 'json')
    given = ' '.join(f'{k}:={v}' for k, v in arguments.items())
    what = f'plugin {overlay.plugin}' if overlay.plugin else f'executable {overlay.key}'
    header = [f'# Described by `nodl describe --all --launch` from the running system '
              f'{one_line(launch_file)}{" " + one_line(given) if given else ""} started.',
              f'# Provenance: described; {one_line(overlay.package)} {one_line(what)}, '
              f'{len(overlay.instances)} instance{"s" * (len(overlay.instances) != 1)}:']
    for instance in overlay.instances:
        state = instance.observed.lifecycle_state
        header.append(f'#   - {one_line(instance.fqn)} (launched at {one_line(instance.where)})'
                      + (f', lifecycle state {one_line(state)}' if state else ''))
    header.append(f'# Names are the declared ones: remaps undone, ~/x under the node, relative '
                  f'under its namespace.  Namesakes watched for {watched:.1f} s (one discovered '
                  'later is not counted).')
    header.append(f'# Left out: what the base gives an {one_line(overlay.client_library)} node '
                  f'({one_line(overlay.client_library_reason)}).')
    header += [f'# {one_line(comment)}.' for comment in overlay.comments]
    skews: dict[tuple[str, str], list[str]] = {}
    for instance in overlay.instances:  # version skew, next to the entity it concerns
        for key, comments in instance.description.skew_comments().items():
            skews.setdefault(key, []).extend(
                f'{instance.fqn}: {c}' if len(overlay.instances) > 1 else c for c in comments)
    body, unplaced = annotate_yaml(dump_nodl(overlay.node, 'yaml'), skews)
    header += [f'# {one_line(comment)}' for comment in unplaced]
    if overlay.notes:
        header.append('# Not observable, so not stated here:')
        header += [f'#   - {one_line(note)}' for note in overlay.notes]
    header.append('# nodl: ignore=NODL216 (a running node has no descriptions: write them, '
                  'then remove this line)')
    return '\n'.join(header) + '\n' + body


def _nodes_yaml(package: str, files: list[OverlayFile], launch_file: str) -> str | None:
    import yaml

    from nodl.text_safety import one_line

    table: dict[str, dict[str, str]] = {}
    for overlay in files:
        record: dict[str, str] = {}
        if overlay.plugin and overlay.plugin.split('::', 1)[0] == package:
            record['plugin'] = overlay.plugin
        if overlay.node_name:
            record['node_name'] = overlay.node_name
        if record:
            table[overlay.key] = record
    if not table:
        return None
    header = (f'# What registrations would record for {one_line(package)} (plugin, node name), '
              f'as observed by `nodl describe --all --launch {one_line(launch_file)}`.\n'
              '# Provenance: described.\n')
    return header + yaml.safe_dump(table, sort_keys=True, default_flow_style=False)


def _write(result: LaunchDescription, directory: str, format: str, force: bool,
           arguments: Mapping[str, str], inputs: list[str]) -> None:
    """Write the definitions and ``nodes.yaml`` files into ``directory``: every path is checked
    first (none of ``inputs``, the files the analysis read: NODL033; none through a folder
    that is a symbolic link leading outside ``directory``: NODL708), so a refusal writes nothing."""
    from nodl.registry.overlay import NODES_FILE
    from nodl.writing import WriteError, check_within, output_is_input, write_marked

    suffix = '.nodl.json' if format == 'json' else '.nodl.yaml'
    ordered = sorted(result.files, key=lambda f: (f.package, f.key))
    planned = [os.path.join(directory, o.package, o.key + suffix) for o in ordered] + [
        os.path.join(directory, package, NODES_FILE) for package in {o.package for o in ordered}]
    for path in planned:
        problem = check_within(path, directory) or output_is_input(path, inputs)
        if problem is not None:
            raise WriteError(problem)
    by_package: dict[str, list[OverlayFile]] = {}
    for overlay in ordered:
        path = os.path.join(directory, overlay.package, overlay.key + suffix)
        write_marked(path, render_merged(overlay, result.launch_file, arguments, result.watched,
                                         format), force=force, make_parents=True, within=directory)
        overlay.path = path
        by_package.setdefault(overlay.package, []).append(overlay)
    for package, files in sorted(by_package.items()):
        text = _nodes_yaml(package, files, result.launch_file)
        if text is not None:
            path = os.path.join(directory, package, NODES_FILE)
            write_marked(path, text, force=force, within=directory)
            result.nodes_files.append(path)
