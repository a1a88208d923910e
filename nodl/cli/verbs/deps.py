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
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, 'output format: a registered reporter that can show a listing '
                                    '(json: {"files": [...], "diagnostics": [...]})', kind='listing')
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

        from nodl.cli.report_options import reporter_for, show_diagnostics, write_report
        from nodl.packaging import package_dependencies
        from nodl.reporting.reporters import Report

        reporter = reporter_for(args, 'nodl deps', 'listing')
        if reporter is None:
            return EXIT_USAGE
        if not os.path.isfile(args.file):
            print(f'nodl deps: {args.file}: no such file', file=sys.stderr)
            return EXIT_USAGE
        try:
            paths, problems = package_dependencies(args.file)
        except OSError as exc:
            from nodl.files import describe_os_error

            print(f'nodl deps: {args.file}: {describe_os_error(exc)}', file=sys.stderr)
            return EXIT_USAGE
        # for people: the paths on standard output (what CMake reads), the problems on standard error
        write_report(reporter, Report('nodl deps', problems, kind='listing',
                                      text=''.join(f'{path}\n' for path in paths),
                                      payload=lambda: {'files': paths,
                                                       'diagnostics': [d.to_dict() for d in problems]}))
        if reporter.FOR_PEOPLE:
            show_diagnostics(problems)
        return EXIT_FAILURE if problems else EXIT_OK
