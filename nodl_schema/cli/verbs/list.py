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

    def main(self, args: argparse.Namespace) -> int:
        import json
        import os

        from nodl_schema.index.registry import list_registrations

        found = list_registrations(args.package)
        if args.format == 'json':
            sys.stdout.write(json.dumps([r._asdict() for r in found], indent=2) + '\n')
            return EXIT_OK
        for r in found:
            sys.stdout.write(f'{r.package:<24} {r.kind:<12} {r.name:<28} {r.file}\n')
        if not found:
            where = f" for package '{args.package}'" if args.package else ''
            prefixes = os.environ.get('AMENT_PREFIX_PATH', '') or 'empty'
            print(f'no NoDL definitions registered{where} (AMENT_PREFIX_PATH: {prefixes})',
                  file=sys.stderr)
        return EXIT_OK
