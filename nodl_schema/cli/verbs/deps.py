"""``nodl deps``."""

from __future__ import annotations

import argparse
import sys

from nodl_schema.cli.verb import EXIT_OK, EXIT_USAGE, Verb


class DepsVerb(Verb):
    """Print the files of its own package a node definition needs (its relative mixins)."""

    failure = None

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('file', metavar='FILE', help='a node definition')
        parser.epilog = ('One path per line, relative to the folder of FILE, as written in '
                         '`mixins` (normalised). Build systems install them next to the node '
                         'file, as ament_nodl_register_node does; references to other packages '
                         '(nodl://) are not files of this package and are not listed.')

    def main(self, args: argparse.Namespace) -> int:
        import os

        from nodl_schema.packaging import relative_mixins

        if not os.path.isfile(args.file):
            print(f'nodl deps: {args.file}: no such file', file=sys.stderr)
            return EXIT_USAGE
        for path in relative_mixins(args.file):
            sys.stdout.write(path + '\n')
        return EXIT_OK
