"""``nodl list``."""

from __future__ import annotations

import argparse
import sys

from nodl_schema.cli.verb import EXIT_OK, Verb


class ListVerb(Verb):
    """List the node and interface definitions registered in the ament index."""

    failure = None

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('package', nargs='?', help='only this package')
        parser.add_argument('--format', choices=('text', 'json'), default='text',
                            help='output format (default: text)')
        parser.add_argument('--kind', choices=('node', 'interface'),
                            help='only node definitions (legacy ones included) or only interface '
                                 'definitions (default: both)')

    def main(self, args: argparse.Namespace) -> int:
        import json
        import os

        from nodl_schema.index.registry import list_registrations

        found = list_registrations(args.package, kind=args.kind)
        if args.format == 'json':
            sys.stdout.write(json.dumps([r._asdict() for r in found], indent=2) + '\n')
            return EXIT_OK
        for r in found:
            sys.stdout.write(f'{r.package:<24} {r.kind:<12} {r.name:<28} {r.file}\n')
        if not found:
            where = f" for package '{args.package}'" if args.package else ''
            what = f'{args.kind} definitions' if args.kind else 'NoDL definitions'
            prefixes = os.environ.get('AMENT_PREFIX_PATH', '') or 'empty'
            print(f'no {what} registered{where} (AMENT_PREFIX_PATH: {prefixes})',
                  file=sys.stderr)
        return EXIT_OK
