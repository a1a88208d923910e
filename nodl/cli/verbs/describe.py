"""``nodl describe``."""

from __future__ import annotations

import argparse
import sys

from nodl.cli.arguments import (
    add_client_library_argument,
    add_definitions_argument,
    add_launch_code_arguments,
    node_name,
    seconds,
)
from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class DescribeVerb(Verb):
    """Observe a running node and write the node definition it exposes."""

    failure = None

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('node', nargs='?', metavar='NODE', type=node_name,
                            help='the node, e.g. /robot/driver (omit with --all)')
        parser.add_argument('-o', '--output', metavar='PATH',
                            help='file to write (with --all: a directory); default: standard output')
        parser.add_argument('--all', action='store_true',
                            help='describe every node in the graph, one file each in -o DIR')
        parser.add_argument('--launch', nargs='+', metavar=('LAUNCH', 'NAME:=VALUE'),
                            help='with --all: describe the running system LAUNCH (with its launch '
                                 'arguments) started into the definitions folder -o DIR: '
                                 'DIR/<package>/<executable>.nodl.yaml, instances merged, remaps '
                                 'undone, composable nodes recorded in DIR/<package>/nodes.yaml')
        parser.add_argument('--missing', action='store_true',
                            help='with --launch: describe only the launched nodes no definition '
                                 'covers (registered, or in a definitions folder); the others are '
                                 'left out, not waited for')
        add_definitions_argument(parser)
        parser.add_argument('--timeout', type=seconds, default=5.0, metavar='S',
                            help='seconds to wait for the node to appear and settle (default: 5)')
        parser.add_argument('--watch', type=seconds, default=None, metavar='S',
                            help='keep watching for other nodes of the same name until discovery '
                                 'has run S seconds (default: while the node is read, at least '
                                 '0.3; 3.5 waits for the 3 s periodic announcements)')
        parser.add_argument('--no-parameters', action='store_true',
                            help="do not read the node's parameters")
        parser.add_argument('--format', choices=('yaml', 'json'), default='yaml',
                            help='output format (default: yaml)')
        parser.add_argument('--force', action='store_true',
                            help='-o: replace files nodl did not write or that were edited since '
                                 '(a JSON file, which has no room for a marker, always needs it)')
        add_client_library_argument(parser, 'deduced from the node: rclcpp if it subscribes to '
                                            '/parameter_events, else rclpy')
        add_launch_code_arguments(parser)

    def main(self, args: argparse.Namespace) -> int:
        import os

        from nodl.cli.output import OutputError
        from nodl.live.session import LiveError

        if args.launch and not args.all:
            print('nodl describe: error: --launch describes a whole system: give --all -o DIR '
                  'with it', file=sys.stderr)
            return EXIT_USAGE
        if args.all == bool(args.node):
            print('nodl describe: error: give a NODE, or --all with -o DIR', file=sys.stderr)
            return EXIT_USAGE
        if args.all and not args.output:
            print('nodl describe: error: --all needs -o DIR', file=sys.stderr)
            return EXIT_USAGE
        if args.all and os.path.exists(args.output) and not os.path.isdir(args.output):
            print(f'nodl describe: error: cannot write into {args.output}: not a directory '
                  '(--all writes one file per node into -o DIR)', file=sys.stderr)
            return EXIT_USAGE
        if args.no_exec and not args.launch:
            print('nodl describe: error: --no-exec is about the launch file: it needs --launch',
                  file=sys.stderr)
            return EXIT_USAGE
        if (args.missing or args.definitions) and not args.launch:
            option = '--missing' if args.missing else '--definitions'
            print(f'nodl describe: error: {option} is about the nodes a launch file starts: it '
                  'needs --all --launch', file=sys.stderr)
            return EXIT_USAGE
        if args.launch:
            return self._describe_launch(args)
        try:
            if args.all:
                from nodl.live.describe_all import describe_all

                try:
                    from nodl.live.observe import DISCOVERY_WINDOW

                    written = describe_all(args.output, timeout=args.timeout,
                                           parameters=not args.no_parameters, format=args.format,
                                           client_library=args.client_library, force=args.force,
                                           settle=DISCOVERY_WINDOW if args.watch is None
                                           else args.watch)
                except OSError as exc:
                    from nodl.files import describe_os_error

                    raise OutputError(f'cannot write {exc.filename or args.output}: '
                                      f'{describe_os_error(exc)}') from None
                if not written:
                    print(f'nodl describe: error: no node found in the graph within '
                          f'{args.timeout:g} s (ROS_DOMAIN_ID={os.environ.get("ROS_DOMAIN_ID", "0")}; '
                          'is discovery reaching the nodes?)', file=sys.stderr)
                    return EXIT_USAGE
                for fqn, path, notes in written:
                    print(f'{fqn} -> {path}')
                    for note in notes:
                        print(f'  note: {note}', file=sys.stderr)
                return EXIT_OK
            from nodl.live.observe import NAMESAKE_WATCH
            from nodl.live.session import ros_session

            with ros_session() as session:  # discovery runs while the rest is imported
                from nodl.live.describe import describe_node

                description = describe_node(args.node, timeout=args.timeout,
                                            parameters=not args.no_parameters,
                                            client_library=args.client_library, session=session,
                                            watch=NAMESAKE_WATCH if args.watch is None
                                            else args.watch)
        except LiveError as exc:
            print(f'nodl describe: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        from nodl.live.describe import render_description

        text = render_description(description, args.format)
        if args.format == 'json':  # YAML says it in its header; JSON has no comments
            from nodl.live.observe import watched_line

            print(f'nodl describe: note: client library {description.client_library}',
                  file=sys.stderr)
            print(f'nodl describe: note: {watched_line(description.watched)}', file=sys.stderr)
        for note in description.warnings + description.notes:
            print(f'nodl describe: warning: {note}', file=sys.stderr)
        for skew in description.skew_warnings:  # also a comment next to the entity
            print(f'nodl describe: warning: version skew: {skew} [NODL423]', file=sys.stderr)
        for note in description.skew_notes:
            print(f'nodl describe: note: {note}', file=sys.stderr)
        if not args.output:
            sys.stdout.write(text)
            return EXIT_OK
        from nodl.writing import write_marked

        # marked, atomic; a user's or an edited file needs --force (the runner prints why not)
        write_marked(args.output, text, force=args.force, make_parents=True)
        print(f'{description.fqn} -> {args.output}')
        return EXIT_OK

    def _describe_launch(self, args: argparse.Namespace) -> int:
        """``--all --launch LAUNCH [NAME:=VALUE...] -o DIR``."""
        import os

        from nodl.cli.arguments import launch_arguments, launch_limits
        from nodl.cli.output import OutputError
        from nodl.live.session import LiveError

        prog = 'nodl describe'
        launch_file, *items = args.launch
        arguments = launch_arguments(launch_file, items, prog)
        if isinstance(arguments, int):
            return arguments
        from nodl.cli.arguments import definitions_failed, load_definitions

        # as nodl analyse reads the launch file: --definitions, NODL_PATH, the nodl.toml that
        # applies to it (their layout's problems are printed)
        definitions = load_definitions(args, prog, os.path.dirname(os.path.abspath(launch_file)))
        if isinstance(definitions, int):
            return definitions
        from nodl.live.describe_launch import describe_launch

        try:
            result = describe_launch(launch_file, arguments, args.output, timeout=args.timeout,
                                     parameters=not args.no_parameters, format=args.format,
                                     client_library=args.client_library, force=args.force,
                                     limits=launch_limits(args), definitions=definitions,
                                     missing=args.missing)
        except LiveError as exc:
            print(f'{prog}: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        except OSError as exc:
            from nodl.files import describe_os_error

            raise OutputError(f'cannot write {exc.filename or args.output}: '
                              f'{describe_os_error(exc)}') from None
        for overlay in result.files:
            print(f'{overlay.path} <- ' + ', '.join(i.fqn for i in overlay.instances))
        for path in result.nodes_files:
            print(f'{path} (what registrations would record)')
        for fqn, why in result.left_out:
            print(f'  left out: {fqn}: {why}', file=sys.stderr)
        for diagnostic in result.diagnostics:
            print(diagnostic, file=sys.stderr)
        if result.unreadable:
            return EXIT_USAGE
        if args.missing and not result.files and not result.errors:
            print(f'{prog}: every node {launch_file} starts has a definition: nothing to describe',
                  file=sys.stderr)
        return EXIT_FAILURE if result.errors or definitions_failed(definitions) else EXIT_OK
