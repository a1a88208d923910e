"""One studio session: a :class:`nodl.composer.Composition` and what the page asks of it.

The session owns no model of its own: every edit is a composer operation, every answer
the composer's state shaped for the page (:meth:`Session.state`): nodes with their ports
and parameters (with editors' facts: type, value, default, constraints in words), edges
(pairs of ports whose final names meet), the analysis's findings (``nodl analyse``'s,
same codes), the read-only pieces, the positions of the side file
(:mod:`nodl.studio.layout`) and whether the launch files' Python code has run.

Safety:

* files are read and written only under the session's folders (:class:`FolderGuard`):
  the launch file, its side file and the exports;
* the launch files' Python code (a Python launch file, ``$(eval)``) does not run until
  :meth:`Session.run_code` (the page's button, the user's explicit action); never when the
  session was started with ``execute=False`` (``--no-exec``).
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable, Sequence
from typing import Any

from nodl.composer import ComposerError, Composition
from nodl.composer.ports import ports_of, verdict
from nodl.composer.values import xml_value
from nodl.composition.entities import Provider
from nodl.diagnostics import Diagnostic, Severity
from nodl.launch.sandbox import LaunchLimits
from nodl.naming import join_name
from nodl.registry.overlay import using
from nodl.studio.guard import FolderGuard
from nodl.studio.layout import layout_file, read_layout, write_layout
from nodl.studio.palette import build_palette
from nodl.validation.validators import lookup
from nodl.writing import WriteError

__all__ = ['NOT_RUN_CODES', 'SUFFIXES', 'Session', 'StudioError', 'port_id']

#: The endings of the launch files the studio opens.
SUFFIXES = ('.launch.xml', '.launch.yaml', '.launch.yml', '.launch.py')
#: The analysis's codes that say launch code was not run (--no-exec, or not yet asked).
NOT_RUN_CODES = frozenset({'NODL525', 'NODL526'})
#: How long an export (a separate nodl process) may take.
EXPORT_TIMEOUT = 120.0


class StudioError(Exception):
    """A request the session refuses: a message, the diagnostics (JSON), the HTTP status."""

    def __init__(self, message: str, diagnostics: Sequence[Diagnostic] = (), status: int = 400,
                 **extra: Any) -> None:
        super().__init__(message)
        self.message = message
        self.diagnostics = [d.to_dict() for d in diagnostics]
        self.status = status
        self.extra = extra


def port_id(node: str, kind: str, name: str) -> str:
    """The page's identifier of a port: ``NODE_ID|KIND|NAME``."""
    return f'{node}|{kind}|{name}'


def _split_port(text: Any) -> tuple[str, str, str]:
    if not isinstance(text, str) or text.count('|') < 2:
        raise StudioError(f'{text!r} is not a port')
    node, kind, name = text.split('|', 2)
    return node, kind, name


def _text(data: dict[str, Any], key: str, *, required: bool = True) -> str:
    value = data.get(key)
    if value is None and not required:
        return ''
    if not isinstance(value, str):
        raise StudioError(f"'{key}' must be a string")
    return value


def _value_text(value: Any) -> str | None:
    """A parameter value as the editor shows it (launch's typing reads it back the same)."""
    if value is None:
        return None
    key = (type(value).__name__, repr(value))
    text = _VALUE_TEXTS.get(key)
    if text is None:
        text = _VALUE_TEXTS[key] = xml_value(value)[0]
    return text


#: Texts of values shown already (a 100-node system shows the same defaults again and again).
_VALUE_TEXTS: dict[tuple[str, str], str] = {}


def _constraints(definition: Any) -> str:
    """A parameter's validators (and additional constraints) in words."""
    words = []
    for key, raw in (getattr(definition, 'validation', None) or {}).items():
        rule = lookup(key)
        if rule is not None and rule.accepts(raw):
            words.append(rule.describe(raw))
    extra = getattr(definition, 'additional_constraints', '') or ''
    if extra:
        words.append(extra)
    return '; '.join(words)


class Session:
    """The studio's state (see the module docstring)."""

    def __init__(self, launch_file: str, *, definitions: Any = None,
                 roots: Sequence[str] = (), execute: bool = True,
                 definition_folders: Sequence[str] = (),
                 exporters: dict[str, Callable[..., list[str]]] | None = None) -> None:

        self.launch_file = os.path.abspath(launch_file)
        self.guard = FolderGuard([os.path.dirname(self.launch_file), *roots])
        problem = self.guard.check(self.launch_file, 'the launch file')
        if problem is not None:
            raise StudioError(problem.message, [problem])
        #: ``--no-exec`` not given: the user may ask for the launch's Python code to run.
        self.execute_allowed = execute
        #: The user asked for it (the page's button).
        self.code_ran = False
        self.definitions = definitions
        self.definition_folders = list(definition_folders)
        self._palette: list[dict[str, Any]] | None = None
        self._positions_cache: dict[str, dict[str, float]] | None = None
        options = {'definitions': definitions, 'limits': LaunchLimits(execute=False)}
        try:
            if os.path.exists(self.launch_file):
                self.composition = Composition.open(self.launch_file, **options)
            else:
                self.composition = Composition.new(self.launch_file, **options)
        except ComposerError as exc:
            raise StudioError(str(exc.diagnostic), [exc.diagnostic]) from None

    # -- reading ------------------------------------------------------------------------------

    def palette(self) -> dict[str, Any]:
        """``{'palette': [...]}``: every definition the toolkit finds (computed once)."""
        if self._palette is None:

            with using(self.definitions):
                self._palette = build_palette()
        return {'ok': True, 'palette': self._palette}

    def _positions(self) -> dict[str, dict[str, float]]:
        if self._positions_cache is None:

            self._positions_cache = read_layout(self.launch_file) \
                if self.guard.inside(self.launch_file) else {}
        return self._positions_cache

    def state(self) -> dict[str, Any]:
        """``{'ok': True, 'state': ...}``: the whole state the page draws."""
        return {'ok': True, 'state': self.snapshot()}

    def snapshot(self) -> dict[str, Any]:
        """The state the page draws (see the module docstring)."""
        composition = self.composition
        with using(self.definitions):
            analysis = composition.analyse()
            data = composition.to_dict(analyse=False)
            findings = [f.to_dict() for f in analysis.findings]
            if self.execute_allowed:  # not run yet because nobody asked: say how to ask
                findings = [_not_asked(f) if f['code'] in NOT_RUN_CODES else f
                            for f in findings]
            nodes = []
            by_entity: dict[tuple[int, int], str] = {}
            launched_of: list[tuple[dict[str, Any], Any]] = [
                (item, analysis.node(item['id'])) for item in data['nodes']]
            seen: dict[str, int] = {}
            for launched in analysis.others:  # from included files and kept code: read-only
                fqn = str(launched.fqn)
                seen[fqn] = seen.get(fqn, 0) + 1
                node_id = f'x:{fqn}' + (f'#{seen[fqn]}' if seen[fqn] > 1 else '')
                entry = launched.entry
                where = launched.location
                launched_of.append(({
                    'id': node_id, 'kind': getattr(entry, 'kind', 'node') or 'node',
                    'package': entry.package, 'executable': entry.executable,
                    'plugin': getattr(entry, 'plugin', None), 'name': None, 'namespace': None,
                    'fqn': fqn, 'editable': False,
                    'read_only_reason': f'launched by {os.path.basename(str(where.file))}:'
                                        f'{where.line}, kept as written',
                    'parameters': {}, 'remaps': [], 'kept': [],
                    'definition': launched.match.file if launched.match.resolved is not None
                    else None, 'included': True}, launched))
            by_id = {n.id: n for n in composition.nodes}
            for item, launched in launched_of:
                ports = []
                for port in ports_of(item['id'], launched):
                    bound = port.entity
                    if bound.entity.provider is Provider.CLIENT_LIBRARY:
                        continue
                    key = port_id(item['id'], port.kind, port.name)
                    by_entity[id(bound.instance), id(bound.entity)] = key
                    ports.append({'kind': port.kind, 'name': port.name,
                                  'final': port.final_name, 'type': port.type})
                nodes.append(self._node(composition, item, ports, by_id.get(item['id'])))
            edges = self._edges(analysis, by_entity)
        counts = {'error': 0, 'warning': 0, 'info': 0}
        for finding in findings:
            counts[finding['severity']] = counts.get(finding['severity'], 0) + 1
        not_run = [f for f in findings if f['code'] in NOT_RUN_CODES]
        positions = self._positions()
        placed = {n['id']: positions[n['fqn']] for n in nodes if n['fqn'] in positions}
        if not self.execute_allowed:
            message = "the launch files' Python code is not run (--no-exec)"
        elif not_run:
            message = ("the launch files' Python code has not run: what it launches is not "
                       'analysed until you run it (in a sandboxed child process)')
        else:
            message = ''
        return {
            'file': self.launch_file, 'format': data['format'], 'dirty': data['dirty'],
            'editable': data.get('editable', True),
            'nodes': nodes, 'edges': edges, 'findings': findings, 'counts': counts,
            'readonly': data.get('kept', []), 'groups': data.get('groups', []),
            'positions': placed,
            'code': {'allowed': self.execute_allowed and not self.code_ran,
                     'ran': self.code_ran, 'needed': bool(not_run), 'message': message},
        }

    @staticmethod
    def _edges(analysis: Any, by_entity: dict[tuple[int, int], str]) -> list[dict[str, Any]]:
        """The analysis's connections between the ports drawn (publisher -> subscription,
        server -> client), client-library endpoints left out."""
        context = getattr(analysis.analysis, 'context', None)
        if context is None:
            return []
        out = []
        for connection in context.system.connections(include_client_library=False,
                                                      lone_servers=False):
            for offering in connection.offering:
                source = by_entity.get((id(offering.instance), id(offering.entity)))
                for user in connection.using:
                    target = by_entity.get((id(user.instance), id(user.entity)))
                    if source is None or target is None:
                        continue
                    out.append({'id': f'e:{source}>{target}', 'source': source,
                                'target': target, 'name': connection.name,
                                'communication': connection.communication,
                                'type': offering.entity.type_name})
        return out

    def _node(self, composition: Any, item: dict[str, Any], ports: list[dict[str, Any]],
              node: Any) -> dict[str, Any]:
        fqn = item['fqn']
        namespace, _, name = fqn.rpartition('/')
        resolved = composition.definition_of(node) if node is not None else None
        given = item.get('parameters') or {}
        parameters = []
        if resolved is not None:

            for entity in resolved.entities:
                if not entity.is_parameter:
                    continue
                if entity.provider is Provider.CLIENT_LIBRARY and entity.name not in given:
                    continue
                definition = entity.definition
                value = given.get(entity.name)
                parameters.append({
                    'name': entity.name, 'type': entity.type_name,
                    'value': value, 'text': _value_text(value) if entity.name in given else '',
                    'given': entity.name in given,
                    'default_text': _value_text(entity.default_value),
                    'read_only': entity.read_only,
                    'description': getattr(definition, 'description', '') or '',
                    'constraints': _constraints(definition), 'error': ''})
        known = {p['name'] for p in parameters}
        for pname, value in given.items():  # given but not declared (the analysis says so)
            if pname not in known:
                parameters.append({'name': pname, 'type': 'undeclared', 'value': value,
                                   'text': _value_text(value), 'given': True,
                                   'default_text': None, 'read_only': False, 'description': '',
                                   'constraints': 'not declared by the definition',
                                   'error': ''})
        remaps = [{'from': a, 'to': b, 'kept': False} for a, b in item.get('remaps', [])]
        kept = item.get('kept', [])
        remaps += [{'kept': True, 'text': k['text'], 'from': '', 'to': ''} for k in kept
                   if 'remap' in k.get('what', '').lower()]
        return {
            'id': item['id'], 'kind': item['kind'], 'package': item['package'],
            'executable': item.get('executable'), 'plugin': item.get('plugin'),
            'name': name or fqn, 'namespace': namespace or '/', 'fqn': fqn,
            'name_given': item.get('name') or '', 'namespace_given': item.get('namespace') or '',
            'editable': item.get('editable', True),
            'read_only_reason': item.get('read_only_reason', ''),
            'definition': bool(item.get('definition')),
            'ports': ports, 'included': bool(item.get('included')),
            'parameters': parameters, 'remaps': remaps,
            'kept': [{'what': k.get('what', ''), 'text': k.get('text', '')} for k in kept],
        }

    # -- editing ------------------------------------------------------------------------------

    def _answer(self, change: Any, **extra: Any) -> dict[str, Any]:
        out: dict[str, Any] = dict(change.to_dict())
        out.update(extra)
        out['state'] = self.snapshot()
        if not change.ok:
            errors = [d for d in change.diagnostics if d.severity is Severity.ERROR]
            out['error'] = '; '.join(d.message for d in errors)
        return out

    def _node_ref(self, data: dict[str, Any]) -> str:
        ref = _text(data, 'node')
        if self.composition.node(ref) is None:
            raise StudioError(f"no node '{ref}' in the composition")
        return ref

    def add(self, data: dict[str, Any]) -> dict[str, Any]:
        """Add ``{package, executable, name, namespace}`` (a free name is chosen when the
        name is taken in that namespace)."""
        package, executable = _text(data, 'package'), _text(data, 'executable')
        name = _text(data, 'name', required=False) or executable
        namespace = _text(data, 'namespace', required=False) or '/'
        container = _text(data, 'container', required=False) or None
        taken = {n['fqn'] for n in self.composition.instances}
        base, number = name, 1
        while join_name(namespace, name) in taken:
            number += 1
            name = f'{base}_{number}'
        with using(self.definitions):
            change = self.composition.add(package, executable, name,
                                          namespace if namespace != '/' else None, container)
        return self._answer(change)

    def remove(self, data: dict[str, Any]) -> dict[str, Any]:
        """Remove ``{node}``."""
        ref = self._node_ref(data)
        fqn = self.composition.fqn(self.composition.node(ref))  # type: ignore[arg-type]
        change = self.composition.remove(ref)
        if change.ok:
            self._forget(fqn)
        return self._answer(change)

    def _port_ref(self, text: Any) -> str:
        node, kind, name = _split_port(text)
        return f'{node}:{kind}/{name}'

    def connect(self, data: dict[str, Any]) -> dict[str, Any]:
        """Join ports ``{a, b}`` (page port identifiers)."""
        with using(self.definitions):
            change = self.composition.connect(self._port_ref(data.get('a')),
                                              self._port_ref(data.get('b')))
        rules = ', '.join(f"{r['from']}:={r['to']}" for r in change.remaps)
        return self._answer(change, message=f'connected ({rules})' if rules else 'connected')

    def disconnect(self, data: dict[str, Any]) -> dict[str, Any]:
        """Part ports ``{a, b}``."""
        with using(self.definitions):
            change = self.composition.disconnect(self._port_ref(data.get('a')),
                                                 self._port_ref(data.get('b')))
        return self._answer(change)

    def compatible(self, data: dict[str, Any]) -> dict[str, Any]:
        """``{port}`` -> ``{'ports': {port id: {ok, verdict, reason}}}`` for every other port:
        the composer's verdict (kinds pair, same type, QoS can connect), from the last
        analysis's ports (nothing is analysed again)."""
        node_id, kind, name = _split_port(data.get('port'))
        composition = self.composition
        all_ports = {n.id: composition.ports(n) for n in composition.nodes}
        source = next((p for p in all_ports.get(node_id, [])
                       if p.kind == kind and p.name == name), None)
        if source is None:
            raise StudioError(f"no port {kind} '{name}' on node '{node_id}'")
        out: dict[str, Any] = {}
        for other_id, ports in all_ports.items():
            for port in ports:
                if port is source:
                    continue
                key = port_id(other_id, port.kind, port.name)
                if other_id == node_id:
                    out[key] = {'ok': False, 'verdict': 'error',
                                'reason': 'a port of the same node'}
                    continue
                judged = verdict(source, port)
                out[key] = {'ok': judged.ok, 'verdict': judged.verdict,
                            'reason': judged.reason or 'compatible'}
        return {'ok': True, 'ports': out}

    def set_parameter(self, data: dict[str, Any]) -> dict[str, Any]:
        """Set ``{node, name, value}`` (the value's text, typed as launch types it); refused,
        with the errors, when it breaks the declared type or a validator."""
        ref = self._node_ref(data)
        with using(self.definitions):
            change = self.composition.set_parameter(ref, _text(data, 'name'),
                                                    _text(data, 'value'))
        return self._answer(change)

    def rename(self, data: dict[str, Any]) -> dict[str, Any]:
        """Give ``{node}`` the ``name`` and ``namespace`` of its entry (empty: none); refused,
        with the composer's errors, for a name or namespace rcl would refuse, a final name
        another node has (NODL982) or a read-only node (NODL983)."""
        ref = self._node_ref(data)
        node = self.composition.node(ref)
        assert node is not None
        before = self.composition.fqn(node)
        change = self.composition.rename(node, _text(data, 'name', required=False) or None,
                                         _text(data, 'namespace', required=False) or None)
        answer = self._answer(change)
        after = self.composition.fqn(node)
        if change.ok and before != after:
            self._move(before, after)
        return answer

    def set_remaps(self, data: dict[str, Any]) -> dict[str, Any]:
        """Replace ``{node}``'s own rules with ``remaps`` (``[[from, to], ...]``); refused, with
        the composer's errors, for a rule rcl would refuse (NODL988) or a read-only node."""
        ref = self._node_ref(data)
        rules = data.get('remaps')
        if not isinstance(rules, list) or not all(
                isinstance(r, list) and len(r) == 2 and all(isinstance(x, str) for x in r)
                for r in rules):
            raise StudioError("'remaps' must be a list of [from, to] pairs")
        change = self.composition.set_remaps(ref, [(a, b) for a, b in rules])
        return self._answer(change)

    # -- files --------------------------------------------------------------------------------

    def save(self, data: dict[str, Any]) -> dict[str, Any]:
        """Write the launch file through the composer (``force``: over changes made on disk
        since it was read), and the positions' side file."""
        problem = self.guard.check(self.launch_file, 'the launch file')
        if problem is not None:
            raise StudioError(problem.message, [problem], status=403)
        problems = self.composition.save(force=bool(data.get('force')))
        if problems:
            changed = any(d.code in ('NODL980', 'NODL981') for d in problems)
            return {'ok': False, 'error': '; '.join(d.message for d in problems),
                    'diagnostics': [d.to_dict() for d in problems], 'changed': changed,
                    'state': self.snapshot()}
        self._write_positions()
        return {'ok': True, 'file': self.launch_file, 'state': self.snapshot()}

    def save_positions(self, data: dict[str, Any]) -> dict[str, Any]:
        """Keep ``{positions: {node id: {x, y}}}`` in the side file (by final name)."""
        given = data.get('positions')
        if not isinstance(given, dict):
            raise StudioError("'positions' must be an object")
        fqns = {n['id']: n['fqn'] for n in self.composition.instances}
        positions = self._positions()
        for node_id, where in given.items():
            if node_id in fqns and isinstance(where, dict) and all(
                    isinstance(where.get(k), (int, float)) and not isinstance(where.get(k), bool)
                    for k in ('x', 'y')):
                positions[fqns[node_id]] = {'x': float(where['x']), 'y': float(where['y'])}
        written = self._write_positions()
        return {'ok': True, 'file': written}

    def _write_positions(self) -> str | None:

        side = layout_file(self.launch_file)
        problem = self.guard.check(side, 'the positions file')
        if problem is not None:
            raise StudioError(problem.message, [problem], status=403)
        if not self._positions() and not os.path.exists(side):
            return None
        try:
            return write_layout(self.launch_file, self._positions())
        except WriteError as exc:
            raise StudioError(exc.diagnostic.message, [exc.diagnostic]) from None

    def _forget(self, fqn: str) -> None:
        self._positions().pop(fqn, None)

    def _move(self, before: str, after: str) -> None:
        positions = self._positions()
        if before in positions:
            positions[after] = positions.pop(before)

    def export(self, data: dict[str, Any]) -> dict[str, Any]:
        """Write ``{what}``: ``policy`` (``<stem>.policy.xml``), ``doc`` (``<stem>-docs/``) or
        ``graph`` (``<stem>.graph.svg``) next to the launch file, or at ``output`` (under the
        session's folders), with ``nodl policy``, ``nodl doc`` or ``nodl analyse --graph`` on the
        saved launch file (unsaved changes: save first)."""
        what = _text(data, 'what')
        folder, base = os.path.split(self.launch_file)
        stem = base
        for suffix in SUFFIXES:
            if stem.lower().endswith(suffix):
                stem = stem[:-len(suffix)]
        defaults = {'policy': f'{stem}.policy.xml', 'doc': f'{stem}-docs',
                    'graph': f'{stem}.graph.svg'}
        if what not in defaults:
            raise StudioError(f"cannot export '{what}': policy, doc or graph")
        if self.composition.dirty or not os.path.exists(self.launch_file):
            raise StudioError('save the launch file first: the export reads it from the disk')
        output = os.path.join(folder, _text(data, 'output', required=False) or defaults[what])
        problem = self.guard.check(output, 'the export')
        if problem is not None:
            raise StudioError(problem.message, [problem], status=403)
        command = {'policy': ['policy', self.launch_file, '-o', output],
                   'doc': ['doc', self.launch_file, '-o', output],
                   'graph': ['analyse', self.launch_file, '--graph', output]}[what]
        for folder_given in self.definition_folders:
            command += ['--definitions', folder_given]
        if not (self.execute_allowed and self.code_ran):
            command.append('--no-exec')
        before = os.stat(output).st_mtime_ns if os.path.exists(output) else None
        done = _run_nodl(command)
        if not os.path.exists(output) or (done.returncode not in (0, 1) and before is not None
                                          and os.stat(output).st_mtime_ns == before):
            # (a file of the user's at that path is not replaced: nodl says so)
            raise StudioError(f'nodl {command[0]} wrote nothing: '
                              + (done.stderr.strip().splitlines() or ['no reason given'])[-1])
        return {'ok': True, 'written': [output], 'status': done.returncode,
                'log': done.stderr[-4000:]}

    def run_code(self, data: dict[str, Any]) -> dict[str, Any]:
        """The user's explicit action: analyse with the launch files' Python code run (in the
        analysis's sandboxed child process).  Refused with ``--no-exec`` (NODL994)."""
        if not self.execute_allowed:
            problem = Diagnostic(Severity.ERROR, "nodl studio was started with --no-exec: the "
                                 "launch files' Python code never runs", file=self.launch_file,
                                 code='NODL994')
            raise StudioError(problem.message, [problem], status=403)

        self.code_ran = True
        self.composition.set_limits(LaunchLimits(execute=True))
        return {'ok': True, 'state': self.snapshot()}


def _run_nodl(arguments: list[str]) -> subprocess.CompletedProcess[str]:
    """``nodl ARGUMENTS`` in a process of its own (the same interpreter and package)."""
    import nodl

    package_root = os.path.dirname(os.path.dirname(os.path.abspath(nodl.__file__)))
    env = dict(os.environ)
    env['PYTHONPATH'] = os.pathsep.join(p for p in (package_root, env.get('PYTHONPATH')) if p)
    try:
        return subprocess.run([sys.executable, '-m', 'nodl', *arguments], capture_output=True,
                              text=True, timeout=EXPORT_TIMEOUT, env=env, check=False)
    except subprocess.TimeoutExpired:
        raise StudioError(f'nodl {arguments[0]} took longer than {EXPORT_TIMEOUT:g} s') from None


#: What the analysis says of launch code it did not run, and what the studio says instead when
#: it was started without --no-exec (the code runs when the user asks).
_NOT_ASKED = (('--no-exec is set and reading a Python launch file runs its code',
               'reading a Python launch file runs its code, which the studio does only when you '
               'click Run launch Python'),
              ('--no-exec is set and it is Python code',
               'it is Python code, which the studio runs only when you click Run launch Python'),
              ('(analyse it without --no-exec, where its code may run)',
               '(Run launch Python runs it, in a sandboxed child process)'))


def _not_asked(finding: dict[str, Any]) -> dict[str, Any]:
    """``finding`` (NODL525/526) as the studio says it: not run until the user asks, rather
    than because of ``--no-exec``, which the studio was not given."""
    message = finding['message']
    for said, meant in _NOT_ASKED:
        message = message.replace(said, meant)
    return {**finding, 'message': message}
