"""``nodl schema``."""

from __future__ import annotations

import argparse
import sys

from nodl.cli.verb import EXIT_OK, Verb


class SchemaVerb(Verb):
    """Print the JSON Schema of a kind of NoDL document (self-contained, for editors)."""

    failure = None

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        from nodl.vocabulary import Kind

        parser.add_argument('kind', nargs='?', choices=[kind.value for kind in Kind],
                            default='node', help='which schema (default: node)')
        parser.add_argument('-o', '--output', metavar='FILE',
                            help='write the schema to FILE instead of standard output')

    def main(self, args: argparse.Namespace) -> int:
        import json

        from nodl.schemas import bundled_schema

        text = json.dumps(bundled_schema(args.kind), indent=2) + '\n'
        if not args.output:
            sys.stdout.write(text)
            return EXIT_OK
        from nodl.cli.output import write_file

        write_file(args.output, text)  # a failure is one 'cannot write' line, exit status 2
        return EXIT_OK
