"""``nodl system``: compose a launch file from node definitions, checked as you go."""

from __future__ import annotations

import argparse
import os
import sys
from typing import TYPE_CHECKING

from nodl.cli.arguments import (
    add_definitions_argument,
    add_launch_code_arguments,
    launch_limits,
    load_definitions,
)
from nodl.cli.report_options import (
    add_format_argument,
    reporter_for,
    show_diagnostics,
    write_report,
)
from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb
from nodl.reporting.reporters import Report

if TYPE_CHECKING:
    from typing import Any

    from nodl.composer import Change, Composition
    from nodl.reporting.reporters import ReporterExtension

#: Codes that mean what the command names is not there (exit status 2, as a missing file).
_NOT_FOUND = ('NODL970', 'NODL971')

#: operation -> its help line.
OPERATIONS = {
    'new': 'start an empty launch file (its format by its ending: .launch.xml, .launch.yaml, '
           '.launch.py)',
    'add': 'add a node (or, with --container, a composable node) to the launch file',
    'remove': 'remove a node (a container with its composable nodes)',
    'connect': 'join a publisher to a subscription, a service or action server to a client: the '
               'remapping rule is computed and written',
    'disconnect': "remove the node's own remapping rule that joins two endpoints",
    'set': "set a parameter of a node's entry, checked against its declared type and validators",
    'rename': "give a node's entry another name or namespace (checked as rcl checks names)",
    'remap': "set a node's own remapping rules to RULE... (none: remove them); rules kept as "
             'written stay',
    'show': 'print the composition (nodes, ports, connections, read-only parts) and its findings',
}


class SystemVerb(Verb):
    """Compose a launch file from node definitions: new, add, remove, connect, disconnect, set,
    rename, remap, show (every change checked at once, the file edited in place)."""

    failure = 'the operation was refused (what is wrong is printed), or show found errors'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        operations = parser.add_subparsers(dest='operation', metavar='OPERATION', required=True)
        for name, help_text in OPERATIONS.items():
            sub = operations.add_parser(name, help=help_text, description=help_text)
            sub.add_argument('file', metavar='FILE', help='the launch file (.launch.xml, '
                             '.launch.yaml or .launch.py)')
            getattr(self, f'_arguments_{name}')(sub)
            self._common(sub, name)
        parser.epilog = (
            'The launch file is edited in place, atomically; what the composer does not edit '
            '(includes, conditions, substitutions, Python code) is kept exactly as written. A '
            'change is not saved when the file changed on disk since it was read (NODL980) '
            'unless --force.')

    @staticmethod
    def _common(sub: argparse.ArgumentParser, name: str) -> None:
        add_definitions_argument(sub)
        if name in ('connect', 'disconnect', 'show', 'remove'):
            add_launch_code_arguments(sub)
        add_format_argument(sub, 'how to print what was done and found: a registered reporter')
        if name != 'show':
            sub.add_argument('--force', action='store_true',
                             help='write even over a file that exists (new) or that changed on '
                                  'disk since it was read')
            sub.add_argument('--dry-run', action='store_true',
                             help='print the launch file as it would be written; write nothing')

    @staticmethod
    def _arguments_new(sub: argparse.ArgumentParser) -> None:
        pass

    @staticmethod
    def _arguments_add(sub: argparse.ArgumentParser) -> None:
        sub.add_argument('package', metavar='PACKAGE')
        sub.add_argument('executable', metavar='EXECUTABLE',
                         help='the executable (or, with --container, the registration key or '
                              'the plugin class pkg::Class)')
        sub.add_argument('--name', required=True, help="the node's name")
        sub.add_argument('--namespace', metavar='NS',
                         help='its namespace: the node goes into the group pushing NS (made '
                              'when there is none)')
        sub.add_argument('--container', metavar='NAME',
                         help='load it as a composable node into the container NAME (made when '
                              'the file has none of that name)')
        sub.add_argument('--group', metavar='ID',
                         help="add it into the group of that id (show lists them: g1, g2...), "
                              "e.g. one that pushes a namespace given by a launch argument")
        sub.add_argument('--plugin', metavar='CLASS',
                         help='the composable node class (default: the one its registration '
                              'records)')

    @staticmethod
    def _arguments_remove(sub: argparse.ArgumentParser) -> None:
        sub.add_argument('node', metavar='NODE', help='its final name, its name, or its id')

    @staticmethod
    def _arguments_connect(sub: argparse.ArgumentParser) -> None:
        sub.add_argument('first', metavar='NODE:ENDPOINT')
        sub.add_argument('second', metavar='NODE:ENDPOINT')

    _arguments_disconnect = _arguments_connect

    @staticmethod
    def _arguments_set(sub: argparse.ArgumentParser) -> None:
        sub.add_argument('node', metavar='NODE', help='its final name, its name, or its id')
        sub.add_argument('parameter', metavar='PARAMETER')
        sub.add_argument('value', metavar='VALUE',
                         help='typed as ros2 launch types a value: 0.5 a double, 3 an integer, '
                              'true a bool, [1, 2] a list, anything else a string')

    @staticmethod
    def _arguments_rename(sub: argparse.ArgumentParser) -> None:
        sub.add_argument('node', metavar='NODE', help='its final name, its name, or its id')
        sub.add_argument('--name', help="the entry's new name ('': none, the program names "
                         'its node); not given: unchanged')
        sub.add_argument('--namespace', metavar='NS',
                         help="the entry's own namespace (relative to its groups' unless it "
                              "starts with /; '': none); not given: unchanged")

    @staticmethod
    def _arguments_remap(sub: argparse.ArgumentParser) -> None:
        sub.add_argument('node', metavar='NODE', help='its final name, its name, or its id')
        sub.add_argument('rules', metavar='RULE', nargs='*',
                         help="FROM:=TO, in rcl's order (the first that matches wins); the "
                              "entry's own editable rules become exactly these")

    @staticmethod
    def _arguments_show(sub: argparse.ArgumentParser) -> None:
        sub.add_argument('-v', '--verbose', action='store_true',
                         help='also print informational findings and every port')

    def main(self, args: argparse.Namespace) -> int:
        # The composer loads the whole analysis (about 0.4 s): imported when the verb runs,
        # not when ``nodl --help`` builds every verb's parser.
        from nodl.composer import Change, ComposerError, Composition

        prog = f'nodl system {args.operation}'
        if args.operation == 'rename' and args.name is None and args.namespace is None:
            print(f'{prog}: error: give --name, --namespace or both', file=sys.stderr)
            return EXIT_USAGE
        reporter = reporter_for(args, prog)
        if reporter is None:
            return EXIT_USAGE
        start = os.path.dirname(os.path.abspath(args.file))
        definitions = load_definitions(args, prog, start, report=False)
        if isinstance(definitions, int):
            return definitions
        options: dict[str, Any] = {'definitions': definitions}
        if getattr(args, 'no_exec', None) is not None:
            options['limits'] = launch_limits(args)
        try:
            if args.operation == 'new':
                composition = Composition.new(args.file, force=args.force, **options)
            else:
                if os.path.isdir(args.file) or not os.path.exists(args.file):
                    why = 'is a directory' if os.path.isdir(args.file) else 'no such file'
                    print(f'{args.file}: error: cannot read the launch file: {why} '
                          '(start one with nodl system new) [NODL020]', file=sys.stderr)
                    return EXIT_USAGE
                composition = Composition.open(args.file, **options)
        except ComposerError as exc:
            show_diagnostics([exc.diagnostic])
            return EXIT_USAGE
        if args.operation == 'show':
            from nodl.composer.showing import show_report

            write_report(reporter, show_report(composition, args.verbose, prog))
            return self._show_status(composition)
        if args.operation == 'new':
            change, done = Change(), f'started {args.file} (empty)'
        else:
            change, done = self._operate(args, composition)
        return self._change(args, prog, composition, reporter, change, done)

    @staticmethod
    def _operate(args: argparse.Namespace, composition: Composition) -> tuple[Change, str]:
        """Do the operation (all but new and show): ``(Change, what it did in words)``."""
        operation = args.operation
        if operation == 'add':
            change = composition.add(args.package, args.executable, args.name,
                                     namespace=args.namespace, container=args.container,
                                     plugin=args.plugin, group=args.group)
            node = composition.node(change.node) if change.node else None
            where = composition.fqn(node) if node is not None else args.name
            return change, f'added {where} ({args.package} {args.executable})'
        if operation == 'remove':
            return composition.remove(args.node), f'removed {args.node}'
        if operation == 'set':
            change = composition.set_parameter(args.node, args.parameter, args.value)
            return change, f'set {args.parameter} = {args.value} on {args.node}'
        if operation == 'rename':
            node = composition.node(args.node)
            before = composition.fqn(node) if node is not None else args.node
            change = composition.rename(
                args.node, args.name if args.name is not None else getattr(node, 'name', None),
                args.namespace if args.namespace is not None else getattr(node, 'namespace', None))
            after = composition.fqn(node) if node is not None else args.node
            return change, f'renamed {before} to {after}' if before != after else \
                f'{before}: the name and namespace are unchanged'
        if operation == 'remap':
            change = composition.set_remaps(args.node, args.rules)
            return change, f"remapping rules of {args.node}: {', '.join(args.rules) or 'none'}"
        if operation == 'connect':
            change = composition.connect(args.first, args.second)
            rules = ', '.join(f"{r['from']}:={r['to']} on {_final_name(composition, r['node'])}"
                              for r in change.remaps)
            return change, f'joined {args.first} and {args.second}' + \
                (f' (remapping rule {rules})' if rules else '')
        change = composition.disconnect(args.first, args.second)
        rules = ', '.join(f"{r['from']}:={r['to']}" for r in change.removed)
        return change, f'parted {args.first} and {args.second}' + \
            (f' (removed {rules})' if rules else '')

    @staticmethod
    def _change(args: argparse.Namespace, prog: str, composition: Composition,
                reporter: ReporterExtension, change: Change, done: str) -> int:
        """Save what the operation changed (unless refused or --dry-run) and report it."""
        diagnostics = list(change.diagnostics)
        status, written = EXIT_OK, False
        if not change.ok:
            summary = f'{prog}: nothing changed'
            # a node or endpoint that is not there is a usage error, as a missing file
            status = EXIT_USAGE if any(d.code in _NOT_FOUND for d in change.diagnostics) \
                else EXIT_FAILURE
        elif args.dry_run:
            sys.stdout.write(composition.render())
            summary = f'{done}; not written (--dry-run)'
        elif not composition.dirty and args.operation != 'new':
            summary = f'{done}; {args.file} unchanged'  # (already so: nothing to write)
        else:
            problems = composition.save(force=args.force)
            diagnostics += problems
            if problems:
                summary = f'{prog}: not saved'
                status = EXIT_USAGE
            else:
                summary, written = f'{done}; {args.file} saved', True
        payload = {'operation': args.operation, 'file': args.file, **change.to_dict(),
                   'saved': written}
        payload['diagnostics'] = [d.to_dict() for d in diagnostics]
        report = Report(prog, diagnostics, summary=summary, payload=payload)
        if args.dry_run and change.ok and reporter.FOR_PEOPLE:
            print(summary, file=sys.stderr)
            show_diagnostics(diagnostics)
            return status
        write_report(reporter, report)
        return status

    @staticmethod
    def _show_status(composition: Composition) -> int:
        """``show``'s exit status: 2 when the file cannot be read, 1 when it has errors."""
        if composition.analyse().analysis.unreadable:
            return EXIT_USAGE
        return EXIT_FAILURE if any(f.severity.value == 'error' for f in composition.findings) \
            else EXIT_OK


def _final_name(composition: Composition, node_id: str) -> str:
    """The final name of the node ``node_id`` (the id itself when it is gone)."""
    node = composition.node(node_id)
    return composition.fqn(node) if node is not None else node_id
