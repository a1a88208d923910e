"""``nodl deps``."""

from __future__ import annotations

import argparse
import sys

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class DepsVerb(Verb):
    """Print the files of its own package a node definition needs (its relative mixins)."""

    failure = 'FILE is not a valid node definition, or a mixin lies outside its package'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('file', metavar='FILE', help='a node definition')
        from nodl.cli.arguments import add_definitions_argument

        add_definitions_argument(parser)
        parser.epilog = ('One path per line, relative to the folder of FILE, as written in '
                         '`mixins` (normalised). Build systems install them next to the node '
                         'file, as ament_nodl_register_node does; references to other packages '
                         '(nodl://) are not files of this package and are not listed. A FILE that '
                         'is not a valid node definition, or a mixin outside the package (NODL532), '
                         'is an error (exit 1).')

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.arguments import run_with_definitions

        # registered definitions (and nodl:// mixins) are looked up in the definitions folders first
        return run_with_definitions(args, 'nodl deps', lambda: self._main(args))

    def _main(self, args: argparse.Namespace) -> int:
        import os

        from nodl.packaging import package_dependencies

        if not os.path.isfile(args.file):
            print(f'nodl deps: {args.file}: no such file', file=sys.stderr)
            return EXIT_USAGE
        try:
            paths, problems = package_dependencies(args.file)
        except OSError as exc:
            from nodl.files import describe_os_error

            print(f'nodl deps: {args.file}: {describe_os_error(exc)}', file=sys.stderr)
            return EXIT_USAGE
        for path in paths:
            sys.stdout.write(path + '\n')
        if problems:
            from nodl.reporting import format_text

            sys.stderr.write(format_text(problems))
            return EXIT_FAILURE
        return EXIT_OK
