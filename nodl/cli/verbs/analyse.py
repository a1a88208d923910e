"""``nodl analyse`` (also spelled ``analyze``)."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class AnalyseVerb(Verb):
    """Analyse the system a launch file starts, or a set of node definitions: every node's final
    names, then the checks."""

    failure = 'the analysis found errors'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        from nodl.cli.arguments import add_client_library_argument, add_launch_code_arguments
        from nodl.cli.diagnostic_options import add_diagnostic_options

        parser.add_argument('launch_file', metavar='LAUNCH_FILE | DEFINITION',
                            help='a launch file: XML (.launch.xml), YAML (.launch.yaml) or Python '
                                 '(.launch.py); or node definitions (FILE or PACKAGE EXECUTABLE, '
                                 'as many as wanted), analysed as one system without a launch file')
        parser.add_argument('launch_arguments', nargs='*', metavar='NAME:=VALUE | DEFINITION',
                            help='launch arguments, as for ros2 launch (or more definitions)')
        from nodl.cli.arguments import add_definitions_argument, node_name

        add_definitions_argument(parser)
        placing = parser.add_argument_group(
            'placing definitions', 'Definitions analysed without a launch file are placed as nodl '
            "policy places them: by default each at /, named after the file's stem or the "
            'executable.')
        placing.add_argument('--name', action='append', default=[], type=node_name,
                             metavar='/NS/NODE',
                             help='the name of the next definition, in order (repeatable)')
        placing.add_argument('--remap', action='append', default=[], metavar='FROM:=TO',
                             help='a remapping rule given to every node (NODE:FROM:=TO: to one)')
        add_client_library_argument(parser)
        add_launch_code_arguments(parser)
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, 'how to print the report: a registered reporter')
        parser.add_argument('-o', '--output', metavar='FILE',
                            help='write the report to FILE instead of standard output')
        parser.add_argument('--log', metavar='FILE',
                            help='also write the whole report (the resolved system, then every '
                                 'finding) to FILE, for later debugging')
        parser.add_argument('--graph', metavar='FILE',
                            help='also draw the system: FILE.dot, FILE.svg or FILE.html '
                                 '(self-contained, interactive)')
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='also print informational findings (orphan publishers)')
        add_diagnostic_options(parser)

    def main(self, args: argparse.Namespace) -> int:
        import os

        from nodl.cli.diagnostic_options import DiagnosticPolicy, PolicyError
        from nodl.config import ConfigError

        prog = 'nodl analyse'
        graph_format = None  # the name of --graph FILE picks the format
        if args.graph:
            graph_format = os.path.splitext(args.graph)[1].lower().lstrip('.')
            if graph_format not in ('dot', 'svg', 'html'):
                print(f"{prog}: error: --graph {args.graph}: the name must end in .dot, .svg or "
                      '.html (it picks the format)', file=sys.stderr)
                return EXIT_USAGE
        from nodl.targets.placement import names_definitions

        if names_definitions(args.launch_file):
            return self._definitions(args, prog, graph_format)
        if args.name or args.remap:
            print(f'{prog}: error: --name and --remap place definitions; a launch file names its '
                  'nodes', file=sys.stderr)
            return EXIT_USAGE
        from nodl.cli.arguments import launch_arguments

        arguments = launch_arguments(args.launch_file, args.launch_arguments, prog)
        if isinstance(arguments, int):
            return arguments
        from nodl.launch.file_kind import not_a_launch_file

        other = not_a_launch_file(args.launch_file)
        if other is not None:
            print(f'{args.launch_file}: error: this is {other}, not a launch file; nodl analyse '
                  'reads a launch file (XML <launch>, YAML launch:, or Python with '
                  'generate_launch_description()) [NODL531]', file=sys.stderr)
            return EXIT_USAGE
        from nodl.writing import output_is_input

        for option, output in (('-o', args.output), ('--log', args.log), ('--graph', args.graph)):
            clash = output_is_input(output, [args.launch_file], option) if output else None
            if clash is not None:
                print(clash, file=sys.stderr)
                return EXIT_USAGE
        try:
            policy = DiagnosticPolicy(args, prog)
            from nodl.system.settings import load_settings

            settings = load_settings(args.launch_file)
        except (PolicyError, ConfigError) as exc:
            print(exc, file=sys.stderr)
            return EXIT_USAGE
        from nodl.cli.arguments import load_definitions

        # the layout's problems are findings of the analysis (not printed apart)
        definitions = load_definitions(args, prog, os.path.dirname(os.path.abspath(args.launch_file)),
                                       report=False)
        if isinstance(definitions, int):
            return definitions

        from nodl.analysis import analyse_launch
        from nodl.cli.arguments import launch_limits

        analysis = analyse_launch(args.launch_file, arguments, client_library=args.client_library,
                                  settings=settings, limits=launch_limits(args),
                                  definitions=definitions)
        return self._report(args, prog, analysis, policy, graph_format,
                            [args.launch_file, *_config_files(args.launch_file)])

    def _definitions(self, args: argparse.Namespace, prog: str, graph_format: str | None) -> int:
        """``nodl analyse DEFINITION...``: the definitions placed and analysed as one system."""
        import os

        from nodl.cli.diagnostic_options import DiagnosticPolicy, PolicyError
        from nodl.config import ConfigError
        from nodl.targets.placement import split_targets

        tokens = [args.launch_file, *args.launch_arguments]
        try:
            targets, launches = split_targets(tokens)
        except ValueError as exc:
            print(f'{prog}: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        if launches:
            print(f'{prog}: error: give a launch file, or node definitions, not both', file=sys.stderr)
            return EXIT_USAGE
        from nodl.launch.file_kind import not_a_launch_file

        files = [t.file for t in targets if t.file is not None]
        for file in files:
            if not os.path.isfile(file):
                why = 'is a directory' if os.path.isdir(file) else 'no such file'
                print(f'{file}: error: cannot read the definition: {why} [NODL020]', file=sys.stderr)
                return EXIT_USAGE
            other = not_a_launch_file(file)
            if other is not None and other != 'a NoDL node definition':
                print(f'{file}: error: this is not a node definition ({other}); nodl analyse '
                      'reads a launch file, or node definitions (FILE or PACKAGE EXECUTABLE) '
                      '[NODL531]', file=sys.stderr)
                return EXIT_USAGE
        from nodl.writing import output_is_input

        for option, output in (('-o', args.output), ('--log', args.log), ('--graph', args.graph)):
            clash = output_is_input(output, files, option) if output else None
            if clash is not None:
                print(clash, file=sys.stderr)
                return EXIT_USAGE
        start = os.path.dirname(os.path.abspath(files[0])) if files else os.getcwd()
        try:
            policy = DiagnosticPolicy(args, prog)
            from nodl.system.settings import load_settings

            settings = load_settings(os.path.join(start, 'definitions'))
        except (PolicyError, ConfigError) as exc:
            print(exc, file=sys.stderr)
            return EXIT_USAGE
        from nodl.cli.arguments import load_definitions

        definitions = load_definitions(args, prog, start, report=False)
        if isinstance(definitions, int):
            return definitions
        from nodl.system.run import analyse_definitions

        try:
            analysis = analyse_definitions(targets, args.name, remaps=args.remap,
                                           client_library=args.client_library, settings=settings,
                                           definitions=definitions)
        except (ValueError, OSError) as exc:
            from nodl.cli.arguments import usage_error

            return usage_error(prog, exc)
        return self._report(args, prog, analysis, policy, graph_format,
                            [*files, *_config_files(os.path.join(start, 'definitions'))])

    @staticmethod
    def _report(args: argparse.Namespace, prog: str, analysis: Any, policy: Any,
                graph_format: str | None, inputs: list[str]) -> int:
        """Print or write the report (and the log and graph): the exit status.

        ``inputs``: files read besides the analysis's own (the launch file, the configuration);
        an output naming any file read is refused before anything is written (NODL033)."""
        from nodl.analysis import report
        from nodl.cli.diagnostic_options import PolicyError
        from nodl.cli.output import write_file
        from nodl.writing import outputs_are_inputs

        clash = outputs_are_inputs((('-o', args.output), ('--log', args.log),
                                    ('--graph', args.graph)), [*inputs, *analysis.files()])
        if clash is not None:
            print(clash, file=sys.stderr)
            return EXIT_USAGE
        try:
            analysis.apply_overrides(policy.apply)
        except PolicyError as exc:
            print(exc, file=sys.stderr)
            return EXIT_USAGE
        from nodl.cli.report_options import reporter_for

        reporter = reporter_for(args, prog)
        if reporter is None:
            return EXIT_USAGE
        result = report.analysis_report(analysis, args.verbose)
        if args.log:
            from nodl.analysis.log import format_log

            write_file(args.log, format_log(analysis))
        if graph_format is not None:
            from nodl.graph import GraphError, render_graph

            try:
                write_file(args.graph, render_graph(analysis, graph_format))
            except GraphError as exc:
                print(f'{prog}: error: --graph {args.graph}: {exc}', file=sys.stderr)
                return EXIT_USAGE
        from nodl.cli.report_options import write_report

        write_report(reporter, result, path=args.output)  # a machine format: the verdict apart
        if analysis.unreadable:
            return EXIT_USAGE
        return EXIT_FAILURE if analysis.errors else EXIT_OK


def _config_files(near: str) -> list[str]:
    """The configuration file that applies to ``near`` (read for settings and overrides), if any."""
    import os

    from nodl.config import find_config_file

    found = find_config_file(os.path.dirname(os.path.abspath(near)))
    return [found] if found else []
