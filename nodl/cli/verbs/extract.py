"""``nodl extract``."""

from __future__ import annotations

import argparse
import os
import sys
from typing import TYPE_CHECKING

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb

if TYPE_CHECKING:
    from nodl.diagnostics import Diagnostic
    from nodl.extract.model import Extraction
    from nodl.reporting.reporters import ReporterExtension

#: Codes that mean the input cannot be read or used as asked (exit status 2).
_USAGE_CODES = frozenset({'NODL020', 'NODL912', 'NODL913', 'NODL030', 'NODL031', 'NODL032', 'NODL033',
                          'NODL034'})


def _is_file_output(path: str) -> bool:
    return not os.path.isdir(path) and not path.endswith(os.sep) and path.endswith(('.yaml', '.yml'))


class ExtractVerb(Verb):
    """Draft node definitions from rclpy and rclcpp source code (read, never run), or compare the source with a definition."""  # noqa: E501  (one line: the help of nodl -h)

    failure = ('the sources have errors (a file that cannot be parsed), or with --diff the source and the '
               'definition differ (with --strict: also a gap or another warning)')

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('paths', nargs='+', metavar='PATH',
                            help='a package (its setup.py/setup.cfg entry points or CMakeLists.txt name '
                                 'the executables), a folder of packages or sources, or source files')
        parser.add_argument('-o', '--output', metavar='DIR|FILE',
                            help='write the drafts: DIR/<package>/<executable>.nodl.yaml (the overlay '
                                 'layout; components and node names recorded in DIR/<package>/nodes.yaml), '
                                 'or FILE (.yaml) when exactly one node is found; without it, the drafts '
                                 'are printed')
        parser.add_argument('--diff', metavar='DEFINITION',
                            help='compare the one node found with this node definition: each difference '
                                 'is a diagnostic (NODL920-926)')
        parser.add_argument('--force', action='store_true',
                            help='replace files nodl did not write, or drafts edited since')
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, 'how to print diagnostics: a registered reporter')
        parser.add_argument('--strict', action='store_true', help='treat warnings (gaps) as errors')
        from nodl.cli.diagnostic_options import add_diagnostic_options

        add_diagnostic_options(parser)

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.diagnostic_options import PolicyError
        from nodl.cli.report_options import policy_and_reporter
        from nodl.diagnostics import Diagnostic, Severity, has_errors
        from nodl.extract.targets import extract_paths

        asked = policy_and_reporter(args, 'nodl extract')
        if asked is None:
            return EXIT_USAGE
        policy, reporter = asked
        extraction = extract_paths(args.paths)
        diagnostics = list(extraction.all_diagnostics)
        written: list[str] = []
        usage = any(d.code in _USAGE_CODES for d in diagnostics)
        if not usage and (args.diff or (args.output and _is_file_output(args.output))) \
                and len(extraction.nodes) != 1:
            option = '--diff' if args.diff else '-o FILE'
            names = ', '.join(n.output_name for n in extraction.nodes)
            diagnostics.append(Diagnostic(Severity.ERROR, f'{option} needs exactly one node; found '
                                          f'{len(extraction.nodes)} ({names}): give -o DIR, or the one '
                                          'file or package of the node', file=args.paths[0], code='NODL913'))
            usage = True
        if not usage and args.output:
            written, problems = self._write(args, extraction)
            diagnostics += problems
            usage = any(d.severity is Severity.ERROR for d in problems)
        if not usage and args.diff:
            from nodl.diagnostics import ValidationError
            from nodl.extract.diff import diff_node

            try:
                diagnostics += diff_node(extraction.nodes[0], args.diff)
            except ValidationError as exc:
                diagnostics += exc.diagnostics
                usage = True
            except OSError as exc:
                from nodl.files import describe_os_error

                diagnostics.append(Diagnostic(Severity.ERROR, f'cannot read the definition: '
                                              f'{describe_os_error(exc)}', file=args.diff, code='NODL020'))
                usage = True
        try:
            diagnostics = policy.apply(None, diagnostics)
        except PolicyError as exc:
            print(exc, file=sys.stderr)
            return EXIT_USAGE
        self._report(args, reporter, extraction, diagnostics, written, usage)
        if usage:
            return EXIT_USAGE
        return EXIT_FAILURE if has_errors(diagnostics, args.strict) else EXIT_OK

    def _write(self, args: argparse.Namespace, extraction: Extraction) -> tuple[list[str], list[Diagnostic]]:
        from nodl.extract.targets import nodes_file_text, output_paths, registrations
        from nodl.extract.writer import draft_text
        from nodl.registry.overlay import NODES_FILE
        from nodl.writing import WriteError, check_within, output_is_input, write_marked

        single = _is_file_output(args.output)
        within = None if single else args.output  # no folder under -o DIR may lead outside it
        paths = output_paths(extraction)
        written: list[str] = []
        read = extraction.files + ([args.diff] if args.diff else [])
        targets = [args.output if single else os.path.join(args.output, paths[id(node)])
                   for node in extraction.nodes]
        if not single:
            targets += [os.path.join(args.output, package, NODES_FILE)
                        for package in registrations(extraction)[0]]
        for target in targets:  # every output is checked before any is written
            problem = (check_within(target, args.output) if within else None) or \
                output_is_input(target, read)
            if problem is not None:
                return written, [problem]
        for node in extraction.nodes:
            target = args.output if single else os.path.join(args.output, paths[id(node)])
            problem = output_is_input(target, extraction.files + ([args.diff] if args.diff else []))
            if problem is not None:
                return written, [problem]
            text = draft_text(node, relative_to=os.path.dirname(os.path.abspath(target)))
            try:
                write_marked(target, text, force=args.force, make_parents=True, within=within)
            except WriteError as exc:
                return written, [exc.diagnostic]
            written.append(target)
        if single:
            return written, []
        tables, notes = registrations(extraction)
        for package, table in sorted(tables.items()):
            target = os.path.join(args.output, package, NODES_FILE)
            problem = output_is_input(target, extraction.files)
            if problem is not None:
                return written, notes + [problem]
            try:
                write_marked(target, nodes_file_text(package, table), force=args.force,
                             make_parents=True, within=args.output)
            except WriteError as exc:
                return written, notes + [exc.diagnostic]
            written.append(target)
        return written, notes

    def _report(self, args: argparse.Namespace, reporter: ReporterExtension, extraction: Extraction,
                diagnostics: list[Diagnostic],
                written: list[str], usage: bool) -> None:
        from nodl.cli.report_options import write_report
        from nodl.reporting import Tally, format_text, plural, summary_line, without_info
        from nodl.reporting.reporters import Report, cases_by_file

        tally = Tally()
        tally.files = len(extraction.files)
        tally.add(diagnostics)
        drafts = [path for path in written if os.path.basename(path) != 'nodes.yaml']
        summary = f'{plural(len(extraction.nodes), "node")} found, {plural(len(drafts), "draft")} written; ' + \
            summary_line(tally)
        if reporter.FOR_PEOPLE:
            if not args.output and not args.diff and not usage:
                from nodl.extract.targets import output_paths
                from nodl.extract.writer import draft_text

                paths = output_paths(extraction)
                for index, node in enumerate(extraction.nodes):
                    if len(extraction.nodes) > 1:
                        sys.stdout.write(f'{"" if index == 0 else chr(10)}# ==> {paths[id(node)]} <==\n')
                    sys.stdout.write(draft_text(node, relative_to=os.getcwd()))
                sys.stdout.flush()
            # the drafts own standard output when they are printed; the diagnostics then go to stderr
            stream = sys.stdout if args.output or args.diff else sys.stderr
        else:
            stream = sys.stdout
        shown = without_info(diagnostics)
        text = format_text(shown) + ''.join(f'wrote {path}\n' for path in written) + summary + '\n'
        write_report(reporter, Report('nodl extract', shown, summary=summary, text=text,
                                      payload=[d.to_dict() for d in diagnostics],
                                      cases=cases_by_file(shown, args.strict)), stream)
