"""``nodl describe``."""

from __future__ import annotations

import argparse
import sys

from nodl_schema.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class DescribeVerb(Verb):
    """Observe a running node and write the node definition it exposes."""

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('node', nargs='?', metavar='NODE',
                            help='the node, e.g. /robot/driver (omit with --all)')
        parser.add_argument('-o', '--output', metavar='PATH',
                            help='file to write (with --all: a directory); default: standard output')
        parser.add_argument('--all', action='store_true',
                            help='describe every node in the graph, one file each in -o DIR')
        parser.add_argument('--timeout', type=float, default=5.0, metavar='S',
                            help='seconds to wait for the node to appear and settle (default: 5)')
        parser.add_argument('--no-parameters', action='store_true',
                            help="do not read the node's parameters")
        parser.add_argument('--format', choices=('yaml', 'json'), default='yaml',
                            help='output format (default: yaml)')

    def main(self, args: argparse.Namespace) -> int:
        import os

        from nodl_schema.live.describe import describe_node, render_description
        from nodl_schema.live.session import LiveError

        if args.all == bool(args.node):
            print('nodl describe: error: give a NODE, or --all with -o DIR', file=sys.stderr)
            return EXIT_USAGE
        if args.all and not args.output:
            print('nodl describe: error: --all needs -o DIR', file=sys.stderr)
            return EXIT_USAGE
        try:
            if args.all:
                from nodl_schema.live.describe_all import describe_all

                written = describe_all(args.output, timeout=args.timeout,
                                       parameters=not args.no_parameters, format=args.format)
                for fqn, path, notes in written:
                    print(f'{fqn} -> {path}')
                    for note in notes:
                        print(f'  note: {note}', file=sys.stderr)
                return EXIT_OK
            description = describe_node(args.node, timeout=args.timeout,
                                        parameters=not args.no_parameters)
        except LiveError as exc:
            print(f'nodl describe: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        text = render_description(description, args.format)
        for note in description.notes:
            print(f'nodl describe: warning: {note}', file=sys.stderr)
        if not args.output:
            sys.stdout.write(text)
            return EXIT_OK
        try:
            os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
            with open(args.output, 'w', encoding='utf-8') as f:
                f.write(text)
        except OSError as exc:
            print(f'nodl describe: error: cannot write {args.output}: {exc.strerror}', file=sys.stderr)
            return EXIT_FAILURE
        print(f'{description.fqn} -> {args.output}')
        return EXIT_OK
