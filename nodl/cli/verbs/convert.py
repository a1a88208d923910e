"""``nodl convert``."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb

if TYPE_CHECKING:
    from nodl.diagnostics import Diagnostic
    from nodl.reporting.junit import JUnitCase

#: ``--from`` values: the legacy XML formats and the dialects of :mod:`nodl.dialects`.
LEGACY = 'legacy-xml'


def _looks_like_xml(path: str) -> bool:
    try:
        with open(path, 'rb') as stream:
            head = stream.read(64)
    except OSError:
        return True  # the legacy reader reports why it cannot be read
    return head.lstrip(b'\xef\xbb\xbf \t\r\n').startswith(b'<')


class ConvertVerb(Verb):
    """Convert legacy NoDL XML, include-dialect node documents and generate_parameter_library files to NoDL v2."""

    failure = 'an input has errors (nothing is written for it)'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        from nodl.dialects import DIALECTS

        parser.add_argument('files', nargs='+', metavar='FILE',
                            help='legacy .nodl.xml files (or package.xml files that export them '
                                 'with <export><interface path="..."/></export>), node documents in '
                                 "the reference implementation's include dialect, or "
                                 'generate_parameter_library files')
        parser.add_argument('-o', '--output-dir', required=True, metavar='DIR',
                            help='where to write the NoDL v2 files: one <executable>.nodl.yaml per '
                                 'legacy node, the same file name for an include-dialect document, '
                                 '<namespace>.nodl.yaml for a generate_parameter_library file '
                                 '(created if missing; files nodl wrote there are replaced)')
        parser.add_argument('--force', action='store_true',
                            help='replace files nodl did not write, or converted files edited since')
        parser.add_argument('--from', dest='source_format', choices=(LEGACY, *DIALECTS),
                            help='the format of the inputs (default: recognised by content)')
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, 'how to print the diagnostics: a registered reporter (json: '
                                    'each input with what was written; junit: one test case per '
                                    'input)')

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.report_options import reporter_for, write_report
        from nodl.reporting import Tally, plural
        from nodl.reporting.reporters import Report

        reporter = reporter_for(args, 'nodl convert')
        if reporter is None:
            return EXIT_USAGE
        #: Files written from generate_parameter_library inputs (interface definitions).
        self._interfaces: set[str] = set()
        out = sys.stdout
        tally = Tally()
        unreadable = failed = False
        written = 0
        inputs: list[dict[str, object]] = []  # the JSON payload: each input, what it gave
        cases: list[tuple[str, list[Diagnostic], bool, bool]] = []  # a JUnit test case per input
        reported: list[Diagnostic] = []  # every diagnostic, for the machine formats
        for result in self._convert(args):
            inputs.append({'file': result.path, 'readable': result.readable,
                           'converted': result.readable and not result.errors,
                           'written': list(result.written),
                           'diagnostics': [d.to_dict() for d in result.diagnostics]})
            if not result.readable:
                unreadable = True
                cases.append((result.path, list(result.diagnostics), True, True))
                reported += result.diagnostics
                written += len(result.written)
                if reporter.FOR_PEOPLE:  # before an output could not be written
                    for path in result.written:
                        out.write(f'wrote {path}\n')
                out.write(reporter.unit(result.diagnostics[:-1] if not result.problem else
                                        result.diagnostics))
                if result.problem:  # the input could not be read
                    print(f'{result.path}: error: {result.problem}', file=sys.stderr)
                else:  # an output not written or not replaced: its own coded line
                    print(result.diagnostics[-1], file=sys.stderr)
                continue
            tally.files += 1
            tally.add(result.diagnostics)
            reported += result.diagnostics
            cases.append((result.path, list(result.diagnostics), bool(result.errors), False))
            out.write(reporter.unit(result.diagnostics))
            if reporter.FOR_PEOPLE:
                if result.errors:
                    out.write(f'{result.path}: not converted (nothing written)\n')
                for path in result.written:
                    out.write(f'wrote {path}\n')
            if result.errors:
                failed = True
            written += len(result.written)
        interfaces = len(self._interfaces)
        kinds = plural(written - interfaces, 'node definition')
        if interfaces:
            kinds += f', {plural(interfaces, "interface definition")}'
        summary = (f'{plural(tally.files, "file")} read, {kinds} written, '
                   f'{plural(tally.errors, "error")}, {plural(tally.warnings, "warning")}')
        # the text was shown input by input: only the summary is left
        write_report(reporter, Report('nodl convert', reported, summary=summary,
                                      text=f'{summary}\n', payload=inputs,
                                      cases=lambda: _junit_cases(cases)), out)
        if unreadable:
            return EXIT_USAGE
        return EXIT_FAILURE if failed else EXIT_OK

    def _convert(self, args: argparse.Namespace) -> list:  # type: ignore[type-arg]
        legacy = [f for f in args.files if args.source_format == LEGACY or
                  (args.source_format is None and _looks_like_xml(f))]
        results = []
        if legacy:
            from nodl.legacy.convert import convert_files

            results += convert_files(legacy, args.output_dir, force=args.force, inputs=args.files)
        from nodl.dialects import GENPARAMLIB
        from nodl.dialects.convert import convert_dialect_file

        for path in args.files:
            if path not in legacy:
                result, dialect = convert_dialect_file(path, args.output_dir, args.source_format,
                                                       force=args.force, inputs=args.files)
                results.append(result)
                if dialect == GENPARAMLIB:
                    self._interfaces.update(result.written)
        order = {path: index for index, path in enumerate(args.files)}
        return sorted(results, key=lambda r: order.get(r.path, 0))


def _junit_cases(cases: list[tuple[str, list[Diagnostic], bool, bool]]) -> list[JUnitCase]:
    from nodl.reporting.junit import JUnitCase

    return [JUnitCase(*case) for case in cases]
