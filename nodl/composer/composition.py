"""A composition: a launch file being composed (see :mod:`nodl.composer`)."""

from __future__ import annotations

import hashlib
import os
from collections.abc import Sequence
from typing import Any

from nodl.composer.adding import add_node, remove_node
from nodl.composer.analysed import ComposedAnalysis, analyse_text
from nodl.composer.change import Change, ComposerError
from nodl.composer.connecting import connect, disconnect, resolve_ports
from nodl.composer.convert import convert_document
from nodl.composer.formats import (
    ReadError,
    format_of,
    new_document,
    read_document,
    render,
)
from nodl.composer.model import (
    ComposedNode,
    Document,
    Group,
    Item,
    Kept,
    Param,
    Remap,
    pushes_group_namespace,
)
from nodl.composer.ports import Port, Verdict, ports_of, verdict
from nodl.composer.renaming import rename, set_remaps
from nodl.composer.rendering import Rendered
from nodl.composer.setting import set_parameter
from nodl.diagnostics import Diagnostic, Severity
from nodl.files import describe_os_error
from nodl.launch.model import LaunchedNode, SourceLocation
from nodl.naming import join_name
from nodl.registry import overlay
from nodl.system.matching import DefinitionMatcher
from nodl.writing import WriteError, write_file

__all__ = ['Change', 'ComposerError', 'Composition']


def _digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


class Composition:
    """A launch file as a composition of nodes (see :mod:`nodl.composer`)."""

    def __init__(self, path: str, doc: Document, digest: str | None, *,
                 definitions: Any = None, limits: Any = None,
                 arguments: dict[str, str] | None = None,
                 prefixes: list[str] | None = None) -> None:
        #: The launch file.
        self.path = path
        #: The items (:class:`~nodl.composer.model.Document`).
        self.document = doc
        self._digest = digest
        self._dirty = digest is None
        self.definitions = definitions
        self.limits = limits
        self.arguments = dict(arguments or {})
        self.prefixes = prefixes
        self._rendered: Rendered | None = None
        self._analysis: ComposedAnalysis | None = None
        self._matches: dict[tuple[str, str, str], Any] = {}

    # -- opening -----------------------------------------------------------------------------

    @classmethod
    def open(cls, path: str, **options: Any) -> Composition:
        """Read the launch file ``path`` (XML, YAML or Python, by its ending; never run).
        ``options``: ``definitions`` (:class:`~nodl.registry.overlay.Definitions`),
        ``limits`` (:class:`~nodl.launch.sandbox.LaunchLimits`, for the analysis of Python),
        ``arguments`` (launch arguments), ``prefixes`` (ament prefixes).  ComposerError (NODL984,
        or NODL020 for a file that cannot be read)."""
        kind = _kind(path)
        try:
            with open(path, 'rb') as stream:
                raw = stream.read()
        except OSError as exc:
            raise ComposerError(Diagnostic(Severity.ERROR, f'cannot read the launch file: '
                                           f'{describe_os_error(exc)}', file=path,
                                           code='NODL020')) from None
        try:
            text = raw.decode('utf-8')
            doc = read_document(text, kind)
        except UnicodeDecodeError:
            raise ComposerError(Diagnostic(Severity.ERROR, 'the launch file is not UTF-8 text',
                                           file=path, code='NODL984')) from None
        except ReadError as exc:
            raise ComposerError(Diagnostic(Severity.ERROR, f'{exc.message}; the composer reads '
                                           'launch files ros2 launch reads (fix it, then open it '
                                           'again)', file=path, line=exc.line, column=exc.column,
                                           code='NODL984')) from None
        return cls(path, doc, _digest(raw), **options)

    @classmethod
    def new(cls, path: str, *, force: bool = False, **options: Any) -> Composition:
        """An empty composition to be saved as ``path`` (its format by its ending).
        ComposerError NODL981 when ``path`` exists (unless ``force``), NODL984 for an ending
        that is not a launch file's."""
        kind = _kind(path)
        if os.path.lexists(path) and not force:
            raise ComposerError(Diagnostic(Severity.ERROR, 'the file exists already: not '
                                           'replaced (open it with nodl system add/show, or give '
                                           '--force to start it anew)', file=path,
                                           code='NODL981'))
        composition = cls(path, new_document(kind), None, **options)
        composition._replace = force
        return composition

    _replace = False

    # -- what it holds -------------------------------------------------------------------------

    @property
    def format(self) -> str:
        """``xml``, ``yaml`` or ``python``."""
        return self.document.format

    @property
    def dirty(self) -> bool:
        """True when there are changes not saved."""
        return self._dirty

    @property
    def nodes(self) -> list[ComposedNode]:
        """Every node (composable nodes after their container), in file order."""
        return self.document.nodes()

    def node(self, ref: str) -> ComposedNode | None:
        """The node ``ref`` names (see :meth:`find`), or None."""
        found, _ = self.find(ref)
        return found

    def find(self, ref: str) -> tuple[ComposedNode | None, Diagnostic | None]:
        """The node ``ref`` names: its id (``n3``), its final name (``/rover/lidar``), its name
        when only one node has it, or ``package/executable`` when only one node runs it.
        ``(None, NODL970 diagnostic)`` when none or several."""
        nodes = self.nodes
        exact = [n for n in nodes if n.id == ref]
        if exact:
            return exact[0], None
        found, problem = self._find(ref, nodes)
        if found is None and self._analysis is None:
            self.analyse()  # the final names only the analysis knows (pushed namespaces...)
            found, problem = self._find(ref, nodes)
        return found, problem

    def _find(self, ref: str, nodes: list[ComposedNode]
              ) -> tuple[ComposedNode | None, Diagnostic | None]:
        finals = [n for n in nodes if self.fqn(n) == ref or self.fqn(n) == join_name('/', ref.lstrip('/'))]
        if len(finals) == 1:
            return finals[0], None
        named = [n for n in nodes if self.fqn(n).rsplit('/', 1)[-1] == ref]
        if len(named) == 1:
            return named[0], None
        runs = [n for n in nodes if f'{n.package}/{n.executable or n.plugin}' == ref]
        if len(runs) == 1:
            return runs[0], None
        several = finals or named or runs
        names = ', '.join(sorted({self.fqn(n) for n in nodes}))
        why = f"several nodes are called '{ref}' ({', '.join(self.fqn(n) for n in several)}); " \
            'give the final name or the id' if several else \
            f"no node of the composition is called '{ref}' (it has: {names or 'no node'})"
        return None, Diagnostic(Severity.ERROR, why, file=self.path, code='NODL970')

    def fqn(self, node: ComposedNode) -> str:
        """The node's final name: the analysis's when it has run, else as the entry and the
        groups give it (``?`` for a namespace only the running launch knows)."""
        analysed = self._analysis.node(node.id) if self._analysis is not None else None
        if analysed is not None:
            return str(analysed.fqn)
        return self._written_fqn(node)

    def _written_fqn(self, node: ComposedNode) -> str:
        namespace = '/'
        for group in self._groups_of(node):
            if group.namespace_unknown:
                namespace = '/?'
            elif group.namespace:
                namespace = group.namespace if group.namespace.startswith('/') else \
                    join_name(namespace, group.namespace)
        if node.namespace:
            namespace = node.namespace if node.namespace.startswith('/') else \
                join_name(namespace, node.namespace)
        name = node.name or (node.executable if node.kind != 'composable' else None) or \
            (node.plugin or '').rsplit('::', 1)[-1].lower()
        return join_name(namespace, name)

    def _groups_of(self, node: ComposedNode) -> list[Group]:
        """The groups holding ``node`` (its container's), outermost first."""
        def visit(items: list[Item], chain: list[Group]) -> list[Group] | None:
            for item in items:
                if isinstance(item, ComposedNode) and node in list(item.walk()):
                    return chain
                if isinstance(item, Group):
                    found = visit(item.items, chain + [item])
                    if found is not None:
                        return found
            return None
        return visit(self.document.items, []) or []

    def container_of(self, node: ComposedNode) -> ComposedNode | None:
        """The container holding a composable node."""
        return next((n for n in self.nodes if node in n.children), None)

    # -- the analysis --------------------------------------------------------------------------

    def rendered(self) -> Rendered:
        """The text the composition saves, and where each node is in it."""
        if self._rendered is None:
            self._rendered = render(self.document)
        return self._rendered

    def render(self, kind: str | None = None) -> str:
        """The launch file's text; ``kind`` (``xml``, ``yaml``, ``python``): the same system in
        another format (its declarative part: kept pieces are the source format's and are left
        out, each with a comment saying so)."""
        if kind is None or kind == self.format:
            return self.rendered().text
        return render(convert_document(self.document, kind)).text

    def analyse(self) -> ComposedAnalysis:
        """The analysis of the composition as it would be saved (cached until the next change);
        its ``findings`` are ``nodl analyse``'s, with the same codes."""
        if self._analysis is None:
            rendered = self.rendered()
            self._analysis = _analyse(self, rendered)
        return self._analysis

    @property
    def findings(self) -> list[Any]:
        """The analysis's findings (:class:`nodl.system.findings.Finding`)."""
        return self.analyse().findings

    def ports(self, node: ComposedNode | str) -> list[Port]:
        """The ports of a node (runs the analysis if it has not run)."""
        found = self._node(node)
        return ports_of(found.id, self.analyse().node(found.id)) if found is not None else []

    @property
    def instances(self) -> list[dict[str, Any]]:
        """Every node as JSON: what :meth:`to_dict` lists under ``nodes``."""
        return [self._node_dict(n) for n in self.nodes]

    def connections(self) -> list[dict[str, Any]]:
        """Every pair of ports whose final names meet (and kinds pair): ``{'from': port,
        'to': port, 'verdict': ...}``, the offering side first."""
        analysis = self.analyse()
        by_name: dict[tuple[str, str], list[Port]] = {}
        for node in self.nodes:
            for port in ports_of(node.id, analysis.node(node.id)):
                by_name.setdefault((port.communication, port.final_name), []).append(port)
        out = []
        for ports in by_name.values():
            for offering in (p for p in ports if p.offers):
                for using in (p for p in ports if not p.offers and p.node != offering.node):
                    judged = verdict(offering, using)
                    out.append({'from': offering.to_dict(), 'to': using.to_dict(),
                                'verdict': judged.verdict, 'reason': judged.reason,
                                'code': judged.code})
        return out

    # -- operations ----------------------------------------------------------------------------

    def _node(self, node: ComposedNode | str) -> ComposedNode | None:
        return node if isinstance(node, ComposedNode) else self.node(node)

    def _changed(self, node: ComposedNode | None = None) -> None:
        self._dirty = True
        self._rendered = None
        self._analysis = None
        if node is not None:
            node.dirty = True
            container = self.container_of(node) if node.kind == 'composable' else None
            if container is not None:
                container.dirty = True

    def _next_id(self, prefix: str) -> str:
        count = int(self.document.style.get('next_id', 0)) + 1
        self.document.style['next_id'] = count
        return f'{prefix}{count}'

    def _node_to_edit(self, ref: ComposedNode | str) -> ComposedNode | Change:
        """The node ``ref`` names, when it can be edited; else the refusal (NODL970: no such
        node, or several; NODL983: read-only)."""
        node = self._node(ref)
        if node is None:
            return Change([self.find(str(ref))[1]])  # type: ignore[list-item]
        problem = self._editable(node)
        if problem is not None:
            return Change([problem], node.id)
        return node

    def _editable(self, node: ComposedNode) -> Diagnostic | None:
        if self.document.style.get('opaque'):
            return Diagnostic(Severity.ERROR, 'the Python launch file does not return '
                              'LaunchDescription([...]) literally: it is kept as written and '
                              'cannot be edited here', file=self.path, code='NODL983')
        if not node.editable:
            return Diagnostic(Severity.ERROR, f'{self.fqn(node)} ({node.label}) is read-only: '
                              f'{node.read_only_reason}; edit the launch file itself',
                              file=self.path, line=node.line, code='NODL983')
        return None

    def add(self, package: str, executable: str, name: str, namespace: str | None = None,
            container: str | None = None, plugin: str | None = None,
            group: str | None = None) -> Change:
        """Add a node (``container``: a composable node loaded into the container of that name,
        made when there is none; ``plugin``: its class, by default the one its registration
        records).  ``namespace`` puts it in the group pushing that namespace (made when there is
        none); ``group``: the id of a group to add it to instead of the top level."""
        change = add_node(self, package, executable, name, namespace, container, plugin, group)
        if change.ok:
            self._changed()
        return change

    def remove(self, node: ComposedNode | str) -> Change:
        """Remove a node (a container with its composable nodes)."""
        found = self._node_to_edit(node)
        if isinstance(found, Change):
            return found
        remove_node(self.document, found, self.container_of(found))
        self._changed()
        return Change([], found.id)

    def can_connect(self, first: str, second: str) -> Verdict:
        """Whether ``NODE:ENDPOINT`` ``first`` and ``second`` can be joined (cheap: the last
        analysis's ports, no new analysis unless none has run)."""
        ports, problem = resolve_ports(self, first, second)
        if problem is not None:
            return Verdict('error', problem.message, problem.code)
        return verdict(*ports)

    def connect(self, first: str, second: str) -> Change:
        """Join ``NODE:ENDPOINT`` ``first`` and ``second``: the rule that makes their final names
        meet is written into the using side's entry (the subscription's, the client's; the
        offering side's when the using side's rules are read-only).  Refused (an error, nothing
        changed) when the kinds do not pair, the types differ or the QoS cannot connect."""
        return connect(self, first, second)

    def disconnect(self, first: str, second: str) -> Change:
        """Undo a join: remove the node's own rules that make the two final names meet."""
        return disconnect(self, first, second)

    def set_parameter(self, node: ComposedNode | str, name: str, text: str) -> Change:
        """Set a parameter of a node's entry to ``text`` typed as launch types it, checked at
        once against the declared type and validators (refused when it breaks them)."""
        return set_parameter(self, node, name, text)

    def rename(self, node: ComposedNode | str, name: str | None,
               namespace: str | None) -> Change:
        """Give the node's entry ``name`` and ``namespace`` (its ``name=``/``namespace=``;
        None or empty: none, the program's name, the groups' namespace alone).  Refused (an
        error, nothing changed) for a name or namespace rcl would refuse, or a final name
        another node has (NODL982), and for a read-only node (NODL983).  Its remapping rules
        are not rewritten: what the new name joins is the next analysis's."""
        return rename(self, node, name, namespace)

    def set_remaps(self, node: ComposedNode | str,
                   rules: Sequence[tuple[str, str] | str]) -> Change:
        """Replace the node's own editable remapping rules with ``rules`` (``(FROM, TO)``
        pairs or ``FROM:=TO`` texts, in rcl's order: the first that matches wins); rules kept as
        written stay where they are.  Every rule is parsed as rcl parses it: one it would
        refuse refuses the whole change (NODL988); a rule an earlier one hides is a warning
        (NODL989).  Refused for a read-only node (NODL983) or rules computed by code
        (NODL976).  ``Change.remaps``/``removed``: the rules added and taken away."""
        return set_remaps(self, node, rules)

    def set_limits(self, limits: Any) -> None:
        """Analyse from now on under ``limits`` (:class:`~nodl.launch.sandbox.LaunchLimits`):
        e.g. ``LaunchLimits(execute=True)`` once the user explicitly asked for the launch's
        Python code to run.  The cached analysis is dropped (the next :meth:`analyse` runs
        anew); the composition itself is unchanged (nothing to save)."""
        self.limits = limits
        self._analysis = None

    def definition_of(self, node: ComposedNode) -> Any:
        """The resolved definition of the node (:class:`~nodl.composition.resolved.ResolvedNode`),
        looked up as the analysis looks it up, or None."""
        match = self.match_of(node)
        return match.resolved if match is not None else None

    def match_of(self, node: ComposedNode) -> Any:
        """The definition the node runs (:class:`nodl.system.matching.Match`), cached."""
        key = (node.package, node.executable or '', node.plugin or '')
        if key not in self._matches:
            self._matches[key] = _match(self, node)
        return self._matches[key]

    # -- saving ---------------------------------------------------------------------------------

    def save(self, force: bool = False) -> list[Diagnostic]:
        """Write the launch file, atomically.  Refused (NODL980) when the file changed on disk
        since it was read (or, for a new composition, when a file appeared there: NODL981),
        unless ``force``.  Returns the diagnostics (empty: saved)."""
        text = self.rendered().text
        try:
            with open(self.path, 'rb') as stream:
                current: str | None = _digest(stream.read())
        except FileNotFoundError:
            current = None
        except OSError:
            current = 'unreadable'
        if not force:
            if self._digest is None and current is not None and not self._replace:
                return [Diagnostic(Severity.ERROR, 'a file appeared at this path since the '
                                   'composition was started: not replaced (give --force to '
                                   'replace it)', file=self.path, code='NODL981')]
            if self._digest is not None and current != self._digest:
                return [Diagnostic(Severity.ERROR, 'the launch file changed on disk since it was '
                                   'read: not saved, so that those changes are not lost (open it '
                                   'again and redo the edit, or give --force to overwrite them)',
                                   file=self.path, code='NODL980')]
        try:
            write_file(self.path, text)
        except WriteError as exc:
            return [exc.diagnostic]
        self._digest = _digest(text.encode('utf-8'))
        self._dirty = False
        self._replace = False
        self._reread(text)
        return []

    def _reread(self, text: str) -> None:
        """Read the saved text again (every item as written), keeping the nodes' ids."""
        old = self.nodes
        old_groups = [g for g, _ in self.document.walk() if isinstance(g, Group)]
        doc = read_document(text, self.format)
        doc.style['next_id'] = self.document.style.get('next_id', 0)
        new = doc.nodes()
        if len(new) == len(old):
            for before, after in zip(old, new, strict=True):
                after.id = before.id
        groups = [g for g, _ in doc.walk() if isinstance(g, Group)]
        if len(groups) == len(old_groups):
            for before_group, after_group in zip(old_groups, groups, strict=True):
                after_group.id = before_group.id
        self.document = doc
        self._rendered = None
        if self._analysis is not None:  # the same text: the analysis stands, ids kept
            self._rendered = render(doc)

    # -- JSON --------------------------------------------------------------------------------

    def _node_dict(self, node: ComposedNode) -> dict[str, Any]:
        analysis = self._analysis
        launched = analysis.node(node.id) if analysis is not None else None
        spans = self.rendered().spans
        groups = self._groups_of(node)
        container = self.container_of(node) if node.kind == 'composable' else None
        match = launched.match if launched is not None else None
        return {
            'id': node.id, 'kind': node.kind, 'package': node.package,
            'executable': node.executable, 'plugin': node.plugin, 'name': node.name,
            'namespace': node.namespace, 'fqn': self.fqn(node),
            'container': container.id if container is not None else None,
            'group': groups[-1].id if groups else None,
            'editable': node.editable and not self.document.style.get('opaque'),
            'read_only_reason': node.read_only_reason,
            'launched': launched is not None if analysis is not None else None,
            'line': spans.get(node.id, (0, 0))[0],
            'parameters': {p.name: p.value for p in node.params if isinstance(p, Param)},
            'remaps': [[r.source, r.target] for r in node.remaps if isinstance(r, Remap)],
            'kept': [k.to_dict() for k in (*node.params, *node.remaps, *node.extra)
                     if isinstance(k, Kept)],
            'definition': match.file if match is not None and match.resolved is not None
            else None,
            'ports': [p.to_dict() for p in ports_of(node.id, launched)],
        }

    def to_dict(self, analyse: bool = True) -> dict[str, Any]:
        """A JSON-ready snapshot: the file, its format, whether it has unsaved changes, every
        node (with its ports, parameters, remapping rules and kept pieces), every group, every
        kept piece, and (``analyse``) the connections and findings."""
        if analyse:
            self.analyse()
        groups = []
        for item, parent in self.document.walk():
            if isinstance(item, Group):
                groups.append({'id': item.id, 'namespace': item.namespace,
                               'namespace_unknown': item.namespace_unknown,
                               'conditional': item.conditional,
                               'parent': parent.id if parent is not None else None})
        out: dict[str, Any] = {
            'file': self.path, 'format': self.format, 'dirty': self.dirty,
            'editable': not self.document.style.get('opaque'),
            'nodes': self.instances, 'groups': groups,
            'kept': [k.to_dict() for k in self.document.kept()],
        }
        if analyse:
            out['connections'] = self.connections()
            out['findings'] = [f.to_dict() for f in self.findings]
        return out

    def kept_diagnostics(self) -> list[Diagnostic]:
        """One NODL979 info per piece kept verbatim (items and parts of nodes): what it is and
        that it is read-only."""
        out = []
        for item, group in self.document.walk():
            if isinstance(item, Kept) and item.line and not pushes_group_namespace(item, group):
                out.append(Diagnostic(Severity.INFO, f'{item.what}: kept as written, read-only '
                                      'here', file=self.path, line=item.line, code='NODL979'))
            elif isinstance(item, ComposedNode):
                for node in item.walk():
                    if not node.editable:
                        out.append(Diagnostic(Severity.INFO, f'{node.label}: read-only here '
                                              f'({node.read_only_reason})', file=self.path,
                                              line=node.line, code='NODL979'))
        if self.document.style.get('opaque'):
            out.append(Diagnostic(Severity.INFO, 'the Python launch file does not return '
                                  'LaunchDescription([...]) literally: kept whole, read-only',
                                  file=self.path, line=1, code='NODL979'))
        return out


def _kind(path: str) -> str:
    kind = format_of(path)
    if kind is None:
        raise ComposerError(Diagnostic(
            Severity.ERROR, 'the name does not say which launch format: end it in .launch.xml, '
            '.launch.yaml or .launch.py', file=path, code='NODL984'))
    return kind


def _analyse(composition: Composition, rendered: Rendered) -> ComposedAnalysis:
    on_disk = not composition.dirty and composition._digest is not None
    return analyse_text(composition.path, rendered, on_disk=on_disk,
                        definitions=composition.definitions, limits=composition.limits,
                        arguments=composition.arguments, prefixes=composition.prefixes)


def _match(composition: Composition, node: ComposedNode) -> Any:
    """The node's definition, as the analysis matches a launched node."""
    record = LaunchedNode(node.kind, node.package, node.executable, node.name, '/',
                          SourceLocation(composition.path, node.line, 0), plugin=node.plugin)
    with overlay.using(composition.definitions):
        return DefinitionMatcher(None, composition.prefixes).match(record)
