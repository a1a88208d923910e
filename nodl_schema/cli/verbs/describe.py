"""``nodl describe``."""

from __future__ import annotations

import argparse
import sys

from nodl_schema.cli.arguments import node_name, seconds
from nodl_schema.cli.verb import EXIT_OK, EXIT_USAGE, Verb


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
        parser.add_argument('--timeout', type=seconds, default=5.0, metavar='S',
                            help='seconds to wait for the node to appear and settle (default: 5)')
        parser.add_argument('--no-parameters', action='store_true',
                            help="do not read the node's parameters")
        parser.add_argument('--format', choices=('yaml', 'json'), default='yaml',
                            help='output format (default: yaml)')
        parser.add_argument('--force', action='store_true',
                            help='-o: replace files nodl did not write or that were edited since '
                                 '(a JSON file, which has no room for a marker, always needs it)')
        from nodl_schema.cli.arguments import add_client_library_argument

        add_client_library_argument(parser, 'deduced from the node: rclcpp if it subscribes to '
                                            '/parameter_events, else rclpy')

    def main(self, args: argparse.Namespace) -> int:
        import os

        from nodl_schema.cli.output import OutputError
        from nodl_schema.live.describe import describe_node, render_description
        from nodl_schema.live.session import LiveError

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
        try:
            if args.all:
                from nodl_schema.live.describe_all import describe_all

                try:
                    written = describe_all(args.output, timeout=args.timeout,
                                           parameters=not args.no_parameters, format=args.format,
                                           client_library=args.client_library, force=args.force)
                except OSError as exc:
                    raise OutputError(f'cannot write {exc.filename or args.output}: '
                                      f'{exc.strerror or exc}') from None
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
            description = describe_node(args.node, timeout=args.timeout,
                                        parameters=not args.no_parameters,
                                        client_library=args.client_library)
        except LiveError as exc:
            print(f'nodl describe: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        text = render_description(description, args.format)
        if args.format == 'json':  # YAML says it in its header; JSON has no comments
            print(f'nodl describe: note: client library {description.client_library}',
                  file=sys.stderr)
        for note in description.warnings + description.notes:
            print(f'nodl describe: warning: {note}', file=sys.stderr)
        if not args.output:
            sys.stdout.write(text)
            return EXIT_OK
        from nodl_schema.writing import write_marked

        # marked, atomic; a user's or an edited file needs --force (the runner prints why not)
        write_marked(args.output, text, force=args.force, make_parents=True)
        print(f'{description.fqn} -> {args.output}')
        return EXIT_OK
