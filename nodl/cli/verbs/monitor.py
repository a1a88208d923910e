"""``nodl monitor``: runtime health monitoring of a running system on ``/diagnostics``."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.cli.verb import EXIT_FAILURE, EXIT_INTERRUPTED, EXIT_OK, EXIT_USAGE, Verb


class MonitorVerb(Verb):
    """Monitor a running system against the one a launch file (or placed definitions) starts,
    publishing diagnostic_msgs/DiagnosticArray on /diagnostics."""

    failure = 'with --once: a status is ERROR'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        from nodl.cli.arguments import (
            add_client_library_argument,
            add_definitions_argument,
            add_launch_code_arguments,
            node_name,
        )

        parser.add_argument('launch_file', metavar='LAUNCH_FILE | DEFINITION',
                            help='the launch file that starts the system, or node definitions '
                                 '(FILE or PACKAGE EXECUTABLE, as many as wanted) placed by name')
        parser.add_argument('launch_arguments', nargs='*', metavar='NAME:=VALUE | DEFINITION',
                            help='launch arguments, as for ros2 launch (or more definitions)')
        add_definitions_argument(parser)
        parser.add_argument('--name', action='append', default=[], type=node_name,
                            metavar='/NS/NODE',
                            help='the name of the next definition, in order (repeatable)')
        parser.add_argument('--remap', action='append', default=[], metavar='FROM:=TO',
                            help='a remapping rule given to every placed definition')
        add_client_library_argument(parser)
        add_launch_code_arguments(parser)
        parser.add_argument('--once', action='store_true',
                            help='observe until every expected node was seen and read (or --wait '
                                 'seconds passed), print the report and exit: 0 no ERROR, 1 an '
                                 'ERROR')
        parser.add_argument('--wait', type=float, default=10.0, metavar='S',
                            help='with --once: seconds to wait at most (default: 10)')
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, '--once: how to print the report (a registered reporter); '
                                    'jsonl: stream every change of level as one JSON object per '
                                    'line (text: one line per change)', extra=('jsonl',))
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='also list informational findings in the text report')
        parser.add_argument('--ignore-node', action='append', default=[], metavar='PATTERN',
                            help='a node never reported as unexpected (fnmatch pattern on the '
                                 'fully qualified name or the name; repeatable)')
        parser.add_argument('--aggregator-config', metavar='FILE',
                            help='write a diagnostic_aggregator analyzer configuration grouping '
                                 'the statuses by namespace to FILE, and exit')
        parser.add_argument('--ros-args', nargs=argparse.REMAINDER, default=[],
                            dest='ros_args', metavar='ARG',
                            help="the monitor node's ROS arguments (-p publish_rate:=2.0, -r ...): "
                                 'everything after it')

    def main(self, args: argparse.Namespace) -> int:
        prog = 'nodl monitor'
        if args.wait <= 0:
            print(f'{prog}: error: --wait must be more than 0 seconds', file=sys.stderr)
            return EXIT_USAGE
        expected = self._expected(args, prog)
        if isinstance(expected, int):
            return expected
        if args.aggregator_config:
            from nodl.cli.output import write_file
            from nodl.monitor.aggregator import analyzer_config, format_config

            write_file(args.aggregator_config, format_config(analyzer_config(expected.nodes)))
            print(f'wrote {args.aggregator_config}: {len(expected.nodes)} nodes', file=sys.stderr)
            return EXIT_OK
        reporter = None
        if args.once and args.format != 'jsonl':  # the report's format, loaded before watching
            from nodl.cli.report_options import reporter_for

            reporter = reporter_for(args, prog)
            if reporter is None:
                return EXIT_USAGE
        return self._run(args, prog, expected, reporter)

    @staticmethod
    def _expected(args: argparse.Namespace, prog: str) -> Any:
        """The expected system, or an exit status after printing why."""
        import os

        from nodl.cli.arguments import launch_arguments, launch_limits, load_definitions, usage_error
        from nodl.cli.report_options import show_diagnostics
        from nodl.monitor.expected import expected_from_definitions, expected_from_launch
        from nodl.targets.placement import names_definitions, split_targets

        if names_definitions(args.launch_file):
            try:
                targets, launches = split_targets([args.launch_file, *args.launch_arguments])
            except ValueError as exc:
                print(f'{prog}: error: {exc}', file=sys.stderr)
                return EXIT_USAGE
            if launches:
                print(f'{prog}: error: give a launch file, or node definitions, not both',
                      file=sys.stderr)
                return EXIT_USAGE
            for target in targets:
                if target.file is not None and not os.path.isfile(target.file):
                    why = 'is a directory' if os.path.isdir(target.file) else 'no such file'
                    print(f'{target.file}: error: cannot read the definition: {why} [NODL020]',
                          file=sys.stderr)
                    return EXIT_USAGE
            files = [t.file for t in targets if t.file is not None]
            start = os.path.dirname(os.path.abspath(files[0])) if files else os.getcwd()
            definitions = load_definitions(args, prog, start)
            if isinstance(definitions, int):
                return definitions
            try:
                expected = expected_from_definitions(targets, args.name, remaps=args.remap,
                                                     client_library=args.client_library,
                                                     definitions=definitions)
            except (ValueError, OSError) as exc:
                return usage_error(prog, exc)
        else:
            if args.name or args.remap:
                print(f'{prog}: error: --name and --remap place definitions; a launch file names '
                      'its nodes', file=sys.stderr)
                return EXIT_USAGE
            arguments = launch_arguments(args.launch_file, args.launch_arguments, prog)
            if isinstance(arguments, int):
                return arguments
            definitions = load_definitions(
                args, prog, os.path.dirname(os.path.abspath(args.launch_file)))
            if isinstance(definitions, int):
                return definitions
            expected = expected_from_launch(args.launch_file, arguments,
                                            client_library=args.client_library,
                                            limits=launch_limits(args), definitions=definitions)
        if expected.unreadable:
            show_diagnostics(expected.diagnostics)
            return EXIT_USAGE
        if not expected.nodes:
            show_diagnostics(expected.diagnostics)
            print(f'{prog}: error: the expected system has no node to monitor', file=sys.stderr)
            return EXIT_USAGE
        return expected

    @staticmethod
    def _run(args: argparse.Namespace, prog: str, expected: Any, reporter: Any) -> int:
        import signal

        from nodl.live.session import LiveError
        from nodl.monitor import status as report
        from nodl.monitor.node import Monitor, MonitorSettings

        stopped: list[int] = []

        def on_signal(number: int, _frame: Any) -> None:
            stopped.append(number)

        def on_change(status: Any, when: float) -> None:
            if args.format == 'jsonl':
                print(report.jsonl_line(status, when), flush=True)
            elif not args.once:
                import datetime

                stamp = datetime.datetime.fromtimestamp(when).strftime('%H:%M:%S.%f')[:-3]
                codes = f" [{','.join(status.codes)}]" if status.codes else ''
                print(f'{stamp} {status.level_name:<5} {status.name}: {status.message}{codes}',
                      flush=True)

        monitor = Monitor(expected, MonitorSettings(ignore=list(args.ignore_node)),
                          ros_args=args.ros_args, on_change=on_change)
        previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
        try:
            monitor.start()
            statuses = monitor.run(lambda: bool(stopped), once=args.once, wait=args.wait)
        except LiveError as exc:
            print(f'{prog}: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        finally:
            monitor.close()
            for number, handler in previous.items():
                signal.signal(number, handler)
        if not args.once:
            return EXIT_OK
        note = 'interrupted: the report covers what was observed until then' if stopped else ''
        if reporter is not None:
            from nodl.cli.report_options import write_report

            write_report(reporter, report.monitor_report(statuses, args.verbose, note))
        sys.stdout.flush()
        if stopped and stopped[0] == signal.SIGINT:
            return EXIT_INTERRUPTED
        return EXIT_FAILURE if any(s.level == 2 for s in statuses) else EXIT_OK
