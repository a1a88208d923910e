"""``nodl doc``."""

from __future__ import annotations

import argparse
import sys

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class DocVerb(Verb):
    """Write reference pages (MyST Markdown, HTML or reStructuredText) for nodes, packages and
    launched systems."""

    failure = ('a target cannot be documented, a page cannot be written, or (--check) a page '
               'on disk is stale, missing or left over')

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('target', nargs='+',
                            metavar='FILE | PACKAGE | PACKAGE/EXECUTABLE | DIR | LAUNCH_FILE',
                            help='a node definition file, a package (all its registered nodes), '
                                 'one registered node, a definitions folder, or a launch file '
                                 '(the system it starts, through the analysis)')
        parser.add_argument('-o', '--output', required=True, metavar='DIR',
                            help='the folder the pages are written to (created if missing); '
                                 "<package>/doc/ for rosdoc2")
        parser.add_argument('--format', choices=('md', 'html', 'rst'), default='md',
                            help='md: MyST Markdown for Sphinx (default); html: self-contained '
                                 'pages; rst: reStructuredText')
        parser.add_argument('--check', action='store_true',
                            help='write nothing; exit 1 if a page on disk differs from what the '
                                 'definitions give, is missing, or is no longer made')
        parser.add_argument('--force', action='store_true',
                            help='replace files nodl did not write, or pages edited since')
        parser.add_argument('--arg', action='append', default=[], metavar='NAME:=VALUE',
                            help="a launch argument for a launch file target (repeatable)")
        from nodl.cli.arguments import add_client_library_argument, add_definitions_argument, add_launch_code_arguments

        add_client_library_argument(parser)
        add_definitions_argument(parser)
        add_launch_code_arguments(parser)

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.arguments import run_with_definitions

        return run_with_definitions(args, 'nodl doc', lambda: self._main(args))

    def _main(self, args: argparse.Namespace) -> int:
        import os

        from nodl.cli.arguments import launch_limits
        from nodl.cli.report_options import show_diagnostics
        from nodl.registry.overlay import active

        prog = 'nodl doc'
        arguments: dict[str, str] = {}
        for item in args.arg:
            name, sep, value = item.partition(':=')
            if not sep or not name:
                print(f"{prog}: error: --arg '{item}' is not NAME:=VALUE", file=sys.stderr)
                return EXIT_USAGE
            arguments[name] = value
        if os.path.exists(args.output) and not os.path.isdir(args.output):
            print(f'{prog}: error: -o {args.output}: not a folder', file=sys.stderr)
            return EXIT_USAGE
        from nodl.doc.collect import collect

        docs = collect(args.target, client_library=args.client_library,
                       launch_arguments=arguments, limits=launch_limits(args),
                       definitions=active())
        show_diagnostics(docs.diagnostics)
        if not docs.pages:
            return EXIT_FAILURE
        from nodl.doc.writer import render_files

        files = render_files(docs, args.format)
        if args.check:
            from nodl.doc.check import check_files

            problems = check_files(files, args.output, args.format)
            show_diagnostics(problems)
            return EXIT_FAILURE if problems or docs.failed else EXIT_OK
        from nodl.writing import outputs_are_inputs

        clash = outputs_are_inputs([('-o', os.path.join(args.output, name)) for name in files],
                                   docs.inputs)
        if clash is not None:  # a definition is never overwritten by its page
            print(clash, file=sys.stderr)
            return EXIT_USAGE
        from nodl.doc.writer import write_files

        written, problems = write_files(files, args.output, force=args.force)
        show_diagnostics(problems)
        for path in written:
            print(path)
        return EXIT_FAILURE if problems or docs.failed else EXIT_OK
