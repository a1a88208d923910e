"""``nodl export``."""

from __future__ import annotations

import argparse
import sys

from nodl.cli.verb import EXIT_OK, EXIT_USAGE, Verb, failure_status

#: The formats ``nodl export`` writes.
FORMATS = ('genparamlib',)


class ExportVerb(Verb):
    """Write the parameters of a definition in another tool's format (generate_parameter_library)."""

    failure = 'the definition is invalid or cannot be composed (nothing is written)'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('format', choices=FORMATS,
                            help='genparamlib: a generate_parameter_library YAML file, for builds '
                                 'that generate their parameter code with it')
        parser.add_argument('definition', nargs='+', metavar='FILE | PACKAGE EXECUTABLE',
                            help='a node or interface definition file, or a package and one of its '
                                 'executables (looked up in the ament index)')
        parser.add_argument('-o', '--output', required=True, metavar='FILE',
                            help="the file to write ('-' for standard output)")
        parser.add_argument('--force', action='store_true',
                            help='replace the file even if nodl did not write it or it was edited '
                                 'since')
        parser.add_argument('--namespace', metavar='NAME',
                            help='the top-level key (the namespace of the generated code; default: '
                                 'the definition file name without .nodl.yaml, or the executable)')
        parser.add_argument('--with-mixins', action='store_true',
                            help="also export the mixins' parameters (default: main's only; the "
                                 "base's are always left out, the client library declares them)")

    def main(self, args: argparse.Namespace) -> int:
        import os

        from nodl.cli.report_options import show_diagnostics
        from nodl.dialects.export import parameters_of_file, parameters_of_registered
        from nodl.dialects.genparamlib import IDENTIFIER, export_genparamlib
        from nodl.reporting import without_info

        if len(args.definition) == 1:
            path = args.definition[0]
            if not os.path.isfile(path):
                what = 'is a directory' if os.path.isdir(path) else 'no such file'
                print(f'nodl export: error: {path}: {what} (to export an installed node, give '
                      'PACKAGE EXECUTABLE)', file=sys.stderr)
                return EXIT_USAGE
            try:
                source = parameters_of_file(path, args.with_mixins)
            except OSError as exc:
                from nodl.files import describe_os_error

                print(f'nodl export: error: {path}: {describe_os_error(exc)}', file=sys.stderr)
                return EXIT_USAGE
        elif len(args.definition) == 2:
            package, executable = args.definition
            source = parameters_of_registered(package, executable, with_mixins=args.with_mixins)
        else:
            print('nodl export: error: expected FILE or PACKAGE EXECUTABLE', file=sys.stderr)
            return EXIT_USAGE
        namespace = args.namespace or source.name
        if not IDENTIFIER.fullmatch(namespace):
            print(f"nodl export: error: '{namespace}' is not a C++ identifier, which the "
                  'generate_parameter_library namespace must be; give one with --namespace',
                  file=sys.stderr)
            return EXIT_USAGE
        show_diagnostics(without_info(source.diagnostics))
        if source.parameters is None:  # not registered: 2, as for a missing file; invalid: 1
            return failure_status(source.diagnostics)
        exported = export_genparamlib(source.parameters, namespace, source.source)
        show_diagnostics(exported.diagnostics)
        text = exported.text(f'generate_parameter_library parameters of {source.source}, '
                             'written by nodl export')
        if args.output == '-':
            sys.stdout.write(text)
            return EXIT_OK
        from nodl.writing import output_is_input, write_marked

        inputs = source.files + (args.definition if len(args.definition) == 1 else [])
        clash = output_is_input(args.output, inputs)
        if clash is not None:
            print(clash, file=sys.stderr)
            return EXIT_USAGE
        write_marked(args.output, text, force=args.force)  # a refusal or failure: the runner's line
        count = sum(1 for _ in _leaves(exported.data))
        print(f'wrote {args.output} ({count} parameter{"s" if count != 1 else ""})', file=sys.stderr)
        return EXIT_OK


def _leaves(tree: dict) -> list[object]:  # type: ignore[type-arg]
    found: list[object] = []
    for value in tree.values():
        if isinstance(value, dict) and isinstance(value.get('type'), str):
            found.append(value)
        elif isinstance(value, dict):
            found += _leaves(value)
    return found
