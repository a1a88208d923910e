"""``nodl generate``."""

from __future__ import annotations

import argparse
import sys

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class GenerateVerb(Verb):
    """Generate a node's base class (Python or C++) from its definition."""

    failure = 'the definition is invalid or cannot be generated, or (--check) the output is stale'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('target', nargs='+', metavar='FILE | PACKAGE EXECUTABLE',
                            help='a node definition file, or a package and one of its executables')
        parser.add_argument('--language', required=True, metavar='LANGUAGE',
                            help='the target language: python (rclpy) or cpp (rclcpp); '
                                 'generator plug-ins add others')
        parser.add_argument('-o', '--output', required=True, metavar='DIR',
                            help='the folder the files are written to (created if missing)')
        parser.add_argument('--class-name', metavar='NAME',
                            help='the class stem: NAMEBase (default: from the executable or file name)')
        parser.add_argument('--node-name', metavar='NAME',
                            help='the default node name (default: from the executable or file name)')
        parser.add_argument('--namespace', default='', metavar='NS',
                            help='C++: the namespace of the generated class')
        parser.add_argument('--component', action='store_true',
                            help='C++: register the class as an rclcpp component')
        parser.add_argument('--check', action='store_true',
                            help='write nothing; fail if a generated file is missing or differs')
        parser.add_argument('--force', action='store_true',
                            help='replace files nodl did not write, or generated files edited since')
        from nodl.cli.arguments import add_definitions_argument

        add_definitions_argument(parser)
        parser.epilog = ('The generator implements what the node itself provides (main); the base '
                         "comes from the language's client library, mixins from other code. "
                         'Regenerating is idempotent: unchanged files are not rewritten.')

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.arguments import run_with_definitions

        # registered definitions (and nodl:// mixins) are looked up in the definitions folders first
        return run_with_definitions(args, 'nodl generate', lambda: self._main(args))

    def _main(self, args: argparse.Namespace) -> int:
        import os

        from nodl.cli.report_options import show_diagnostics
        from nodl.generate import (
            GenerateOptions,
            GenerationError,
            check_options,
            default_class_name,
            default_node_name,
            load_generators,
            write_files,
        )
        from nodl.reporting import without_info
        from nodl.targets import resolve_target, target_name

        if len(args.target) > 2:
            print('nodl generate: error: give a definition FILE or PACKAGE EXECUTABLE', file=sys.stderr)
            return EXIT_USAGE
        generators = load_generators()
        generator = generators.get(args.language)
        if generator is None:
            known = ', '.join(sorted(generators)) or 'none installed'
            print(f'nodl generate: error: no generator for language {args.language!r} '
                  f'(available: {known})', file=sys.stderr)
            return EXIT_USAGE
        name = target_name(args.target)
        options = GenerateOptions(
            class_name=default_class_name(name) if args.class_name is None else args.class_name,
            node_name=default_node_name(name) if args.node_name is None else args.node_name,
            namespace=args.namespace, component=args.component)
        problems = check_options(options, getattr(generator, 'LANGUAGE', '') or args.language)
        if problems:  # before reading the definition: a usage error
            show_diagnostics(problems)
            return EXIT_USAGE
        try:
            node, diagnostics, _, _ = resolve_target(args.target,
                                                    client_library=generator.CLIENT_LIBRARY or None)
        except (OSError, ValueError) as exc:
            if isinstance(exc, OSError):
                from nodl.files import describe_os_error

                words = describe_os_error(exc)
                name = exc.filename or args.target[0]
                exc = ValueError(words if words.startswith(f'{name}:') else f'{name}: {words}')
            print(f'nodl generate: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        shown = without_info(diagnostics)
        if shown:
            show_diagnostics(shown)
        if node is None:
            return EXIT_FAILURE
        try:
            files = generator.generate(node, options)
        except GenerationError as exc:
            print(f'nodl generate: error: {exc}', file=sys.stderr)
            return EXIT_FAILURE
        from nodl.writing import output_is_input

        for item in files:  # the definition (or a mixin of it) is never overwritten
            clash = output_is_input(os.path.join(args.output, item.path), node.files)
            if clash is not None:
                print(clash, file=sys.stderr)
                return EXIT_USAGE
        # a refusal (a file of the user's, an edited one) or a failed write: the runner's one line
        changed = write_files(files, args.output, check=args.check, force=args.force)
        if args.check:
            for path in changed:
                print(f'{path}: stale or missing: run nodl generate without --check to update it',
                      file=sys.stderr)
            return EXIT_FAILURE if changed else EXIT_OK
        for path in changed:
            print(path)
        return EXIT_OK
