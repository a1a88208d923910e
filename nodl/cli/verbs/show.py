"""``nodl show``."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb, failure_status


def _complete_definition(**kwargs: Any) -> list[str]:
    from nodl.cli.completion import complete_definition

    return complete_definition(**kwargs)


class ShowVerb(Verb):
    """Print a node's whole interface (base + mixins + main resolved) as an interface definition."""

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('target', nargs='+', metavar='FILE | PACKAGE EXECUTABLE | nodl://PACKAGE/NAME',
                            help='a NoDL file, a package and one of its executables, or a '
                                 'registered interface definition (looked up in the ament index)'
                            ).completer = _complete_definition  # type: ignore[attr-defined]
        parser.add_argument('--format', choices=('yaml', 'json'), default='yaml',
                            help='output format (default: yaml)')
        parser.add_argument('--layers', action='store_true',
                            help="show the layer each entity comes from (base, mixin or main)")
        from nodl.cli.arguments import add_client_library_argument, add_definitions_argument

        add_client_library_argument(parser)
        add_definitions_argument(parser)

    failure = 'the definition is invalid, or cannot be composed'

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.arguments import definition_problem

        problem = definition_problem(args.target)
        if problem is not None:
            print(f'nodl show: error: {problem}', file=sys.stderr)
            return EXIT_USAGE
        from nodl.cli.arguments import definitions_failed, load_definitions
        from nodl.registry.overlay import using

        definitions = load_definitions(args, 'nodl show')
        if isinstance(definitions, int):
            return definitions
        with using(definitions):
            status = self._show(args)
        return max(status, EXIT_FAILURE) if definitions_failed(definitions) else status

    def _show(self, args: argparse.Namespace) -> int:
        import os

        from nodl.cli.report_options import show_diagnostics
        from nodl.reporting import without_info
        from nodl.show import render, show_file, show_registered

        if len(args.target) == 1 and args.target[0].startswith('nodl://'):
            from nodl.show import show_reference

            shown = show_reference(args.target[0])
        elif len(args.target) == 1:
            if not os.path.isfile(args.target[0]):
                what = 'is a directory' if os.path.isdir(args.target[0]) else 'no such file'
                print(f'nodl show: error: {args.target[0]}: {what} (to look up an installed '
                      'node, give PACKAGE EXECUTABLE)', file=sys.stderr)
                return EXIT_USAGE
            shown = show_file(args.target[0], args.client_library)
        elif len(args.target) == 2:
            shown = show_registered(args.target[0], args.target[1],
                                    client_library=args.client_library)
        else:
            print('nodl show: error: expected FILE or PACKAGE EXECUTABLE', file=sys.stderr)
            return EXIT_USAGE
        problems = without_info(shown.diagnostics)
        show_diagnostics(problems)
        if shown.interface is None:  # not registered: 2, as for a missing file; invalid: 1
            return failure_status(problems)
        provenance = shown.provenance
        if provenance is not None and provenance.source == 'overlay':  # which file served it
            from nodl.text_safety import visible

            print(visible(f'nodl show: note: {shown.source} ({provenance})', one_line=True),
                  file=sys.stderr)
        library = shown.client_library
        if library is not None and args.format == 'json' and not args.layers:
            # plain JSON is the interface alone; say which base it has where it cannot break it
            print(f'nodl show: note: client library {library}', file=sys.stderr)
        sys.stdout.write(render(shown.interface, args.format, args.layers, library))
        return EXIT_OK
