"""``nodl validate``."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb
from nodl.diagnostics import Diagnostic, Severity

if TYPE_CHECKING:  # (the JUnit reporter is loaded only when it is asked for)
    from nodl.reporting.junit import JUnitCase

#: The code of a path that cannot be read (see nodl.codes).
UNREADABLE_CODE = 'NODL020'


class ValidateVerb(Verb):
    """Validate NoDL files (parameter, interface or node definitions) and report every problem."""

    failure = 'a file is invalid (with --strict: or has warnings)'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('paths', nargs='+', metavar='PATH',
                            help='files (any extension), directories (searched for *.nodl.yaml, '
                                 '*.nodl.yml, *.nodl.json) or - for standard input')
        from nodl.vocabulary import Kind

        parser.add_argument('--kind', choices=[kind.value for kind in Kind],
                            help='require this kind of document (default: detect it)')
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, 'how to print diagnostics: a registered reporter (sarif: '
                                    'SARIF 2.1.0 for code scanning; junit: JUnit XML for CI, one '
                                    'test case per file)')
        parser.add_argument('--strict', action='store_true',
                            help='treat warnings as errors')
        parser.add_argument('--resolve', action='store_true',
                            help="also compose node definitions: every mixin reference must "
                                 "resolve (nodl:// through the ament index, paths relative to "
                                 "the file) to a valid interface definition")
        parser.add_argument('--types', action='store_true',
                            help='also check every endpoint type against the installed '
                                 'interfaces (AMENT_PREFIX_PATH): the package, the type and '
                                 'its kind must exist; a registered definition\'s interface '
                                 'packages must be run-time dependencies in its package.xml')
        parser.add_argument('--package', metavar='DIR', dest='package_dir',
                            help='the files belong to the package in DIR (implies --types): '
                                 'its own msg/, srv/ and action/ types resolve from its source, '
                                 'and its package.xml must declare each interface package')
        parser.add_argument('--types-at-build', action='store_true',
                            help='with --types: checked while the package builds (ament_nodl), '
                                 'where an interface package declared in package.xml but not '
                                 'installed is a warning, not an error')
        from nodl.cli.arguments import add_client_library_argument

        add_client_library_argument(parser, 'rclpy; with --resolve, the base of this client '
                                            'library is composed')
        parser.add_argument('-q', '--quiet', action='store_true',
                            help='print only diagnostics (no list of valid files, and no '
                                 'summary when every file is clean)')
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='also print informational diagnostics (e.g. which layer '
                                 'overrides which, with --resolve)')
        from nodl.cli.diagnostic_options import add_diagnostic_options

        add_diagnostic_options(parser)
        parser.add_argument('--stderr', action='store_true',
                            help='print everything to standard error (for build systems, which '
                                 'show a failed step\'s stderr)')

    def main(self, args: argparse.Namespace) -> int:
        from nodl.checking import failed, iter_check_paths
        from nodl.cli.diagnostic_options import PolicyError
        from nodl.cli.output import Progress
        from nodl.cli.report_options import policy_and_reporter, write_report
        from nodl.reporting import Tally, plural, summary_line, without_info
        from nodl.reporting.reporters import Report
        from nodl.validation.kinds import Kind

        asked = policy_and_reporter(args, 'nodl validate')
        if asked is None:
            return EXIT_USAGE
        policy, reporter = asked
        tally = Tally()
        unreadable: list[Diagnostic] = []
        cases: list[tuple[str, list[Diagnostic], bool, bool]] = []  # a JUnit test case per path
        invalid = False
        out = sys.stderr if args.stderr else sys.stdout
        text = reporter.FOR_PEOPLE
        progress = Progress('nodl validate')
        for stream in (sys.stdout, sys.stderr):  # the progress line is erased before any output
            if hasattr(stream, 'before_write'):
                stream.before_write = progress.clear
        if '-' in args.paths and sys.stdin.isatty():
            print('nodl validate: note: reading standard input (end it with Ctrl-D)', file=sys.stderr)
        if args.package_dir is not None:
            import os

            if not os.path.isfile(os.path.join(args.package_dir, 'package.xml')):
                print(f'nodl validate: --package {args.package_dir}: no package.xml there '
                      '(give the folder of a ROS package)', file=sys.stderr)
                return EXIT_USAGE
        results = iter_check_paths(args.paths, Kind(args.kind) if args.kind else None, args.resolve,
                                   client_library=args.client_library, types=args.types,
                                   package_dir=args.package_dir, build=args.types_at_build)
        for result in results:
            if result.note is not None:
                print(f'{result.path}: note: {result.note}', file=sys.stderr)
                continue
            if not result.readable:
                # An I/O problem: counted, in the JSON output too, and exit status 2.
                problem = Diagnostic(Severity.ERROR, result.problem or 'cannot be read',
                                     file=result.path, code=UNREADABLE_CODE)
                unreadable.append(problem)
                cases.append((result.path, [problem], True, True))
                print(problem, file=sys.stderr)
                sys.stderr.flush()
                continue
            try:  # --ignore / --error and the nodl.toml or [tool.nodl] found upward from the file
                result.diagnostics = policy.apply(result.path, result.diagnostics)
            except PolicyError as exc:
                progress.clear()
                print(exc, file=sys.stderr)
                return EXIT_USAGE
            tally.files += 1
            tally.add(result.diagnostics)
            cases.append((result.path, without_info(result.diagnostics), failed(result, args.strict),
                          False))
            header = None
            if failed(result, args.strict):
                invalid = True
            elif text and not args.quiet and result.report is not None:
                header = f'{result.path}: valid {result.report.kind} definition'
            shown = result.diagnostics if args.verbose else without_info(result.diagnostics)
            out.write(reporter.unit(shown, header))
            out.flush()  # each file's diagnostics as soon as it is checked (Ctrl-C keeps them)
            progress.update(tally.files + len(unreadable))
        progress.clear()
        summary = summary_line(tally)
        if unreadable:
            summary += ', ' + plural(len(unreadable), 'unreadable path')
        # the text was shown file by file: only the summary is left (none when quiet and clean)
        quiet = args.quiet and tally.errors + tally.warnings == 0 and not unreadable
        write_report(reporter, Report('nodl validate', tally.diagnostics + unreadable,
                                      summary=summary, cases=lambda: _junit_cases(cases),
                                      text='' if quiet else f'{summary}\n'), out)
        if unreadable:
            return EXIT_USAGE
        return EXIT_FAILURE if invalid else EXIT_OK


def _junit_cases(cases: list[tuple[str, list[Diagnostic], bool, bool]]) -> list[JUnitCase]:
    from nodl.reporting.junit import JUnitCase

    return [JUnitCase(*case) for case in cases]
