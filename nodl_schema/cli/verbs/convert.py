"""``nodl convert``."""

from __future__ import annotations

import argparse
import sys

from nodl_schema.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class ConvertVerb(Verb):
    """Convert legacy NoDL XML (.nodl.xml or an exporting package.xml) to NoDL v2 node definitions."""

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('files', nargs='+', metavar='FILE',
                            help='legacy .nodl.xml files, or package.xml files that export them '
                                 'with <export><interface path="..."/></export>')
        parser.add_argument('-o', '--output-dir', required=True, metavar='DIR',
                            help='where to write one <executable>.nodl.yaml per node '
                                 '(created if missing; existing files are replaced)')

    def main(self, args: argparse.Namespace) -> int:
        from nodl_schema.legacy.convert import convert_files
        from nodl_schema.reporting import Tally, format_text, plural

        out = sys.stdout
        tally = Tally()
        unreadable = failed = False
        written = 0
        for result in convert_files(args.files, args.output_dir):
            if not result.readable:
                unreadable = True
                for path in result.written:  # before an output could not be written
                    out.write(f'wrote {path}\n')
                written += len(result.written)
                print(f'{result.path}: error: {result.problem}', file=sys.stderr)
                continue
            tally.files += 1
            tally.add(result.diagnostics)
            out.write(format_text(result.diagnostics))
            if result.errors:
                failed = True
                out.write(f'{result.path}: not converted (nothing written)\n')
            for path in result.written:
                out.write(f'wrote {path}\n')
            written += len(result.written)
        out.write(f'{plural(tally.files, "file")} read, {plural(written, "node definition")} '
                  f'written, {plural(tally.errors, "error")}, {plural(tally.warnings, "warning")}\n')
        if unreadable:
            return EXIT_USAGE
        return EXIT_FAILURE if failed else EXIT_OK
