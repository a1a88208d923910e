"""``nodl params``."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb

if TYPE_CHECKING:
    from nodl.diagnostics import Diagnostic
    from nodl.reporting.junit import JUnitCase
    from nodl.reporting.reporters import ReporterExtension


class ParamsVerb(Verb):
    """Write a node's parameter defaults as a parameter file, or check parameter files without ROS."""

    failure = 'the definition is invalid, or (check) a parameter file has an error'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.usage = ('%(prog)s DEFINITION [--name /NS/NODE] [-o FILE]\n'
                        '       %(prog)s check PARAMS_FILE... (--definition DEFINITION [--name /NS/NODE] '
                        '| --launch LAUNCH_FILE)')
        parser.add_argument('args', nargs='+', metavar='DEFINITION | check PARAMS_FILE...',
                            help='a node definition (FILE or PACKAGE EXECUTABLE) to write the defaults '
                                 'of, or "check" and parameter files')
        parser.add_argument('--name', metavar='/NS/NODE',
                            help='the fully qualified node name (default: /NODE, the node name '
                                 'derived from the executable or file name)')
        parser.add_argument('-o', '--output', metavar='FILE', help='write the defaults here (default: stdout)')
        parser.add_argument('--force', action='store_true',
                            help='-o: replace the file even if nodl did not write it or it was '
                                 'edited since')
        parser.add_argument('--definition', nargs='+', metavar='DEFINITION',
                            help='check: the node definition (FILE or PACKAGE EXECUTABLE)')
        from nodl.cli.arguments import add_definitions_argument

        add_definitions_argument(parser)
        parser.add_argument('--launch', metavar='LAUNCH_FILE',
                            help='check: the launch file whose nodes the files are for (the files the '
                                 'launch file itself gives are checked too)')
        parser.add_argument('--launch-argument', action='append', default=[], metavar='NAME:=VALUE',
                            help='check: a launch argument (repeatable)')
        from nodl.cli.arguments import add_launch_code_arguments

        add_launch_code_arguments(parser)
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, 'check: how to print the diagnostics: a registered reporter '
                                    '(junit: one test case per parameter file)')
        parser.epilog = ('Node keys match as rcl matches them (/** any number of name tokens, /* one); '
                         'values are typed as rcl types them and checked as strictly as a node does: '
                         'the type exactly, every validator; required parameters must be set.')

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.arguments import run_with_definitions

        # registered definitions (and nodl:// mixins) are looked up in the definitions folders first
        return run_with_definitions(args, 'nodl params', lambda: self._main(args))

    def _main(self, args: argparse.Namespace) -> int:
        if args.args[0] == 'check':
            return self._check(args)
        return self._defaults(args)

    def _node_named(self, args: argparse.Namespace, target: list[str]) -> tuple[object, str] | int:
        """The node ``target`` names and its fully qualified name (``--name``, else derived);
        the exit status when there is none."""
        node, status = self._resolve(target)
        if node is None:
            return status
        fqn = self._fqn(args, target)
        return EXIT_USAGE if fqn is None else (node, fqn)

    @staticmethod
    def _resolve(target: list[str]) -> tuple[object, int]:
        from nodl.cli.report_options import show_diagnostics
        from nodl.reporting import without_info
        from nodl.targets import resolve_target

        if len(target) > 2:
            print('nodl params: error: give a definition FILE or PACKAGE EXECUTABLE', file=sys.stderr)
            return None, EXIT_USAGE
        try:
            node, diagnostics, _, _ = resolve_target(target)
        except (OSError, ValueError) as exc:
            from nodl.files import describe_os_error

            why = str(exc)
            if isinstance(exc, OSError):
                why, name = describe_os_error(exc), exc.filename or target[0]
                why = why if why.startswith(f'{name}:') else f'{name}: {why}'  # the path once
            print(f'nodl params: error: {why}', file=sys.stderr)
            return None, EXIT_USAGE
        show_diagnostics(without_info(diagnostics))
        return node, EXIT_OK if node is not None else EXIT_FAILURE

    @staticmethod
    def _fqn(args: argparse.Namespace, target: list[str]) -> str | None:
        from nodl.generate import default_node_name
        from nodl.targets import target_name

        if args.name is None:
            from nodl.naming import join_name

            return join_name('/', default_node_name(target_name(target)))
        name: str = args.name
        from nodl.naming.validation import full_name_error

        problem = full_name_error(name)
        if problem is not None:
            problem = problem.replace('topic name', 'a node name')
            print(f'nodl params: error: --name {name}: {problem}', file=sys.stderr)
            return None
        return name

    def _defaults(self, args: argparse.Namespace) -> int:
        from nodl.params import defaults_yaml

        if args.definition or args.launch or args.format != 'text':
            option = '--format' if args.format != 'text' else '--definition and --launch'
            print(f'nodl params: error: {option} belong{"s" * (option == "--format")} to '
                  '"nodl params check"', file=sys.stderr)
            return EXIT_USAGE
        found = self._node_named(args, args.args)
        if isinstance(found, int):
            return found
        node, fqn = found
        text = defaults_yaml(node, fqn)  # type: ignore[arg-type]
        if args.output is None or args.output == '-':
            sys.stdout.write(text)
            return EXIT_OK
        from nodl.writing import output_is_input, write_marked

        # the definition and its mixins (a parameter file must overwrite none of them)
        inputs = list(getattr(node, 'files', [])) + (args.args if len(args.args) == 1 else [])
        clash = output_is_input(args.output, inputs)
        if clash is not None:
            print(clash, file=sys.stderr)
            return EXIT_USAGE
        # marked, atomic; a user's or an edited file needs --force (the runner prints the refusal)
        write_marked(args.output, text, force=args.force)
        return EXIT_OK

    def _check(self, args: argparse.Namespace) -> int:
        from nodl.cli.report_options import reporter_for
        from nodl.params import check_launch_parameters, check_parameter_files

        files = args.args[1:]
        import os

        for path in files:  # a file that is not there is a usage error, said once
            if not os.path.isfile(path):
                why = 'is a directory, not a file' if os.path.isdir(path) else 'no such file'
                print(f'{path}: error: cannot read the parameter file: {why} [NODL020]',
                      file=sys.stderr)
                return EXIT_USAGE
        if (args.definition is None) == (args.launch is None):
            print('nodl params check: error: give exactly one of --definition and --launch',
                  file=sys.stderr)
            return EXIT_USAGE
        reporter = reporter_for(args, 'nodl params check')
        if reporter is None:
            return EXIT_USAGE
        if args.definition is not None:
            if not files:
                print('nodl params check: error: give at least one PARAMS_FILE', file=sys.stderr)
                return EXIT_USAGE
            found = self._node_named(args, args.definition)
            if isinstance(found, int):
                return found
            node, fqn = found
            diagnostics = check_parameter_files(files, node, fqn)  # type: ignore[arg-type]
        else:
            arguments = {}
            for item in args.launch_argument:
                name, sep, value = item.partition(':=')
                if not sep:
                    print(f'nodl params check: error: --launch-argument {item}: expected NAME:=VALUE',
                          file=sys.stderr)
                    return EXIT_USAGE
                arguments[name] = value
            from nodl.cli.arguments import launch_limits

            diagnostics = check_launch_parameters(args.launch, files, arguments,
                                                  limits=launch_limits(args))
        return _report(reporter, files, diagnostics)


def _report(reporter: ReporterExtension, files: list[str], diagnostics: list[Diagnostic]) -> int:
    """Write the check's report (text: the diagnostics, then one line when there is no error;
    JUnit: a test case per parameter file); the exit status."""
    from nodl.cli.report_options import write_report
    from nodl.diagnostics import Severity
    from nodl.reporting import format_text, plural
    from nodl.reporting.reporters import Report

    errors = sum(1 for d in diagnostics if d.severity is Severity.ERROR)
    warnings = sum(1 for d in diagnostics if d.severity is Severity.WARNING)
    checked = plural(len(files), 'parameter file') if files else 'the parameter files'
    counts = f', {plural(warnings, "warning")}' if warnings else ''
    if errors:
        summary = f'nodl params check: {checked} checked: {plural(errors, "error")}{counts}'
    else:  # success says so, in one line (the only summary the text shows)
        summary = f'nodl params check: {checked} checked: no errors{counts}'
    text = format_text(diagnostics) + ('' if errors else f'{summary}\n')
    write_report(reporter, Report('nodl params check', diagnostics, summary=summary, text=text,
                                  cases=lambda: _cases(files, diagnostics)))
    return EXIT_FAILURE if errors else EXIT_OK


def _cases(files: list[str], diagnostics: list[Diagnostic]) -> list[JUnitCase]:
    """A JUnit test case per parameter file given (then per other file a diagnostic is about:
    the files a launch file gives), failed when it holds an error."""
    from nodl.diagnostics import Severity
    from nodl.reporting.junit import JUnitCase

    by_file: dict[str, list[Diagnostic]] = {file: [] for file in files}
    for d in diagnostics:
        by_file.setdefault(d.file, []).append(d)
    return [JUnitCase(file, found, any(d.severity is Severity.ERROR for d in found))
            for file, found in by_file.items()]
