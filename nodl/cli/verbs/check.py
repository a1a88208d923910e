"""``nodl check``."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.cli.arguments import node_name, seconds
from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


def _complete_definition(**kwargs: Any) -> list[str]:
    from nodl.cli.completion import complete_definition

    return complete_definition(**kwargs)


class CheckVerb(Verb):
    """Check a running node against its node definition and report every difference."""

    failure = 'the node drifts from its definition'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('node', metavar='NODE', type=node_name,
                            help='the running node, e.g. /robot/driver')
        parser.add_argument('definition', nargs='+', metavar='FILE | PACKAGE EXECUTABLE',
                            help='the node definition: a file, or a package and executable '
                                 'registered in the ament index'
                            ).completer = _complete_definition  # type: ignore[attr-defined]
        parser.add_argument('--remap', action='append', default=[], metavar='FROM:=TO',
                            help='a remapping the node was launched with (repeatable)')
        parser.add_argument('--timeout', type=seconds, default=5.0, metavar='S',
                            help='seconds to wait for the node (default: 5)')
        parser.add_argument('--watch', type=seconds, default=3.5, metavar='S',
                            help='watch for other nodes of the same name (which the check refuses) '
                                 'until discovery has run S seconds, the node being read and '
                                 'compared meanwhile (default: 3.5, past the 3 s periodic '
                                 'announcements; within --timeout)')
        parser.add_argument('--no-parameters', action='store_true',
                            help='do not check parameters')
        from nodl.cli.arguments import add_client_library_argument

        add_client_library_argument(parser)
        from nodl.cli.arguments import add_definitions_argument

        add_definitions_argument(parser)
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, 'output format: a registered reporter (junit: JUnit XML; '
                                    'sarif: SARIF 2.1.0 for code scanning, each difference at '
                                    'its declaration)')
        parser.add_argument('--junit', metavar='FILE', help='also write a JUnit XML report')
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='also list what could not be verified')
        from nodl.cli.diagnostic_options import add_diagnostic_options

        add_diagnostic_options(parser)

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.arguments import run_with_definitions

        # registered definitions (and nodl:// mixins) are looked up in the definitions folders first
        return run_with_definitions(args, 'nodl check', lambda: self._main(args))

    def _main(self, args: argparse.Namespace) -> int:
        from nodl.cli.arguments import definition_problem
        from nodl.cli.diagnostic_options import PolicyError
        from nodl.cli.report_options import policy_and_reporter, show_diagnostics, write_report
        from nodl.diagnostics import ValidationError
        from nodl.live.check import check_node
        from nodl.live.report import check_report
        from nodl.live.session import LiveError

        problem = definition_problem(args.definition)
        if problem is not None:
            print(f'nodl check: error: {problem}', file=sys.stderr)
            return EXIT_USAGE
        asked = policy_and_reporter(args, 'nodl check')  # --ignore / --error, --format
        if asked is None:
            return EXIT_USAGE
        policy, reporter = asked
        definition = args.definition[0] if len(args.definition) == 1 else tuple(args.definition)
        if args.junit and isinstance(definition, str):
            from nodl.writing import output_is_input

            clash = output_is_input(args.junit, [definition], '--junit')
            if clash is not None:
                print(clash, file=sys.stderr)
                return EXIT_USAGE
        try:  # the nodl.toml or [tool.nodl] found upward from the file
            if isinstance(definition, str):  # known before observing: a bad one fails at once
                policy.overrides_for(definition)
        except PolicyError as exc:
            print(exc, file=sys.stderr)
            return EXIT_USAGE
        try:
            result = check_node(args.node, definition, timeout=args.timeout, remaps=args.remap,
                                parameters=not args.no_parameters,
                                client_library=args.client_library, watch=args.watch)
        except ValidationError as exc:
            show_diagnostics(exc.diagnostics)
            return EXIT_USAGE
        except OSError as exc:
            from nodl.files import describe_os_error

            print(f'nodl check: error: cannot read the definition {exc.filename or ""}: '
                  f'{describe_os_error(exc)}', file=sys.stderr)
            return EXIT_USAGE
        except (LiveError, ValueError) as exc:
            print(f'nodl check: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        if args.junit:  # now that the definition is found: none of the files it was read from
            import os

            from nodl.config import find_config_file
            from nodl.writing import output_is_input

            config = find_config_file(os.path.dirname(os.path.abspath(result.definition)))
            clash = output_is_input(args.junit, [result.definition, *result.composed.files,
                                                 config or ''], '--junit')
            if clash is not None:
                print(clash, file=sys.stderr)
                return EXIT_USAGE
        # A definition in the reference's include dialect says so once, as in every verb (NODL851).
        dialect = [d for d in result.composed.diagnostics if d.code == 'NODL851']
        show_diagnostics(dialect)
        try:  # conformance is decided after the overrides (of the file a package registers, too)
            result = result.with_overrides(policy.overrides_for(result.definition))
        except PolicyError as exc:
            print(exc, file=sys.stderr)
            return EXIT_USAGE
        write_report(reporter, check_report(result, args.verbose))  # a machine format: the verdict
        if args.junit:  # a report: replaced atomically; a failure is one line, exit status 2
            from nodl.cli.report_options import write_report_file

            write_report_file('junit', check_report(result), args.junit)
        return EXIT_OK if result.conforms else EXIT_FAILURE
