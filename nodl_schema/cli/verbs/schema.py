"""``nodl schema``."""

from __future__ import annotations

import argparse
import sys

from nodl_schema.cli.verb import EXIT_OK, EXIT_USAGE, Verb


class SchemaVerb(Verb):
    """Print the JSON Schema of a kind of NoDL document (self-contained, for editors)."""

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('kind', nargs='?', choices=('parameter', 'interface', 'node'),
                            default='node', help='which schema (default: node)')
        parser.add_argument('-o', '--output', metavar='FILE',
                            help='write the schema to FILE instead of standard output')

    def main(self, args: argparse.Namespace) -> int:
        import json

        from nodl_schema.schemas import bundled_schema

        text = json.dumps(bundled_schema(args.kind), indent=2) + '\n'
        if not args.output:
            sys.stdout.write(text)
            return EXIT_OK
        try:
            with open(args.output, 'w', encoding='utf-8') as f:
                f.write(text)
        except OSError as exc:
            print(f'nodl schema: error: cannot write {args.output}: {exc.strerror}', file=sys.stderr)
            return EXIT_USAGE
        return EXIT_OK
