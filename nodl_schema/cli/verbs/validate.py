"""``nodl validate``."""

from __future__ import annotations

import argparse
import sys

from nodl_schema.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class ValidateVerb(Verb):
    """Validate NoDL files (parameter, interface or node definitions) and report every problem."""

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('paths', nargs='+', metavar='PATH',
                            help='files (any extension), directories (searched for *.nodl.yaml, '
                                 '*.nodl.yml, *.nodl.json) or - for standard input')
        parser.add_argument('--kind', choices=('parameter', 'interface', 'node'),
                            help='require this kind of document (default: detect it)')
        parser.add_argument('--format', choices=('text', 'json'), default='text',
                            help='how to print diagnostics (default: text)')
        parser.add_argument('--strict', action='store_true',
                            help='treat warnings as errors')
        parser.add_argument('--resolve', action='store_true',
                            help="also compose node definitions: every mixin reference must "
                                 "resolve (nodl:// through the ament index, paths relative to "
                                 "the file) to a valid interface definition")
        parser.add_argument('-q', '--quiet', action='store_true',
                            help='print only diagnostics (no list of valid files, and no '
                                 'summary when every file is clean)')
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='also print informational diagnostics (e.g. which layer '
                                 'overrides which, with --resolve)')
        parser.add_argument('--stderr', action='store_true',
                            help='print everything to standard error (for build systems, which '
                                 'show a failed step\'s stderr)')

    def main(self, args: argparse.Namespace) -> int:
        from nodl_schema.checking import check_paths, failed
        from nodl_schema.reporting import Tally, format_json, format_text, summary_line, without_info
        from nodl_schema.validation.kinds import Kind

        results = check_paths(args.paths, Kind(args.kind) if args.kind else None, args.resolve)
        tally = Tally()
        unreadable = False
        invalid = False
        out = sys.stderr if args.stderr else sys.stdout
        for result in results:
            if not result.readable:
                unreadable = True
                print(f'{result.path}: error: {result.problem}', file=sys.stderr)
                continue
            tally.files += 1
            tally.add(result.diagnostics)
            if failed(result, args.strict):
                invalid = True
            elif args.format == 'text' and not args.quiet and result.report is not None:
                kind = result.report.kind
                out.write(f'{result.path}: valid {kind} definition\n')
            if args.format == 'text':
                shown = result.diagnostics if args.verbose else without_info(result.diagnostics)
                out.write(format_text(shown))
        if args.format == 'json':
            out.write(format_json(tally.diagnostics))
            print(summary_line(tally), file=sys.stderr)
        elif not (args.quiet and tally.errors + tally.warnings == 0 and not unreadable):
            out.write(summary_line(tally) + '\n')
        if unreadable:
            return EXIT_USAGE
        return EXIT_FAILURE if invalid else EXIT_OK
