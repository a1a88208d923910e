"""``nodl list``."""

from __future__ import annotations

import argparse
import sys

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class ListVerb(Verb):
    """List the node and interface definitions: the definitions folders', then the ament index's."""

    failure = None

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('package', nargs='?', help='only this package')
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, 'output format: a registered reporter that can show a listing',
                            kind='listing')
        parser.add_argument('--kind', choices=('node', 'interface'),
                            help='only node definitions (legacy ones included) or only interface '
                                 'definitions (default: both)')
        from nodl.cli.arguments import add_definitions_argument

        add_definitions_argument(parser)
        parser.epilog = ('Each entry says where it comes from: index (the ament index) or overlay '
                         '(a definitions folder), with (extracted) or (described) when nodl extract '
                         'or nodl describe wrote the file. A definition of a folder shadows the '
                         "index's of the same package and name.")

    def main(self, args: argparse.Namespace) -> int:
        import os

        from nodl.cli.arguments import definitions_failed, load_definitions
        from nodl.cli.report_options import reporter_for, write_report
        from nodl.registry.overlay import using
        from nodl.registry.registrations import list_registrations
        from nodl.reporting.reporters import Report
        from nodl.targets.resolve import Provenance

        reporter = reporter_for(args, 'nodl list', 'listing')
        if reporter is None:
            return EXIT_USAGE
        definitions = load_definitions(args, 'nodl list')
        if isinstance(definitions, int):
            return definitions
        with using(definitions):
            found = list_registrations(args.package, kind=args.kind)
        origins = [Provenance.of(r.origin, r.file) for r in found]
        status = EXIT_FAILURE if definitions_failed(definitions) else EXIT_OK
        from nodl.text_safety import visible

        lines = []
        for r, o in zip(found, origins, strict=True):
            origin = o.source + (f'({o.made_by})' if o.made_by else '')
            lines.append(visible(f'{r.package:<24} {r.kind:<12} {r.name:<28} {origin:<10} '
                                 f'{r.file}', one_line=True) + '\n')
        entries = [{'package': r.package, 'name': r.name, 'kind': r.kind, 'file': r.file,
                    'origin': o.source, 'folder': o.folder, 'provenance': o.made_by}
                   for r, o in zip(found, origins, strict=True)]
        write_report(reporter, Report('nodl list', kind='listing', text=''.join(lines),
                                      payload=entries))
        if not reporter.FOR_PEOPLE:
            return status
        if not found:
            where = f" for package '{args.package}'" if args.package else ''
            what = f'{args.kind} definitions' if args.kind else 'NoDL definitions'
            prefixes = os.environ.get('AMENT_PREFIX_PATH', '') or 'empty'
            folders = ''.join(f'; definitions folder: {f.root}' for f in definitions.folders)
            print(f'no {what} registered{where} (AMENT_PREFIX_PATH: {prefixes}{folders})',
                  file=sys.stderr)
        return status
