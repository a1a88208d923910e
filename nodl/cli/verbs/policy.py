"""``nodl policy``."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

    from nodl.diagnostics import Diagnostic

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


def _complete_definition(**kwargs: Any) -> list[str]:
    from nodl.cli.completion import complete_definition

    return complete_definition(**kwargs)


def _name_value(token: str) -> tuple[str, str] | None:
    name, sep, value = token.partition(':=')
    if not sep or not name or '/' in name:
        return None
    return name, value


class PolicyVerb(Verb):
    """Write (or check) the least-privilege SROS 2 access-control policy of nodes or a launched system."""

    failure = 'the policy cannot be exact (a node without definition, a name that cannot be granted), ' \
              'or --check found missing or extra grants'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('targets', nargs='*', metavar='TARGET',
                            help='a launch file (*.launch.xml|py|yaml), or node definitions: FILE '
                                 'or PACKAGE EXECUTABLE (repeatable); NAME:=VALUE gives a launch '
                                 'argument (for definitions: a parameter of every node)'
                            ).completer = _complete_definition  # type: ignore[attr-defined]
        parser.add_argument('--name', action='append', default=[], metavar='/NS/NODE',
                            help='place the next definition under this name (repeatable, in order; '
                                 'default: its executable or file name at /)')
        parser.add_argument('--remap', action='append', default=[], metavar='FROM:=TO',
                            help='a remapping rule for the placed definitions, as rcl applies it '
                                 '(NODE:FROM:=TO for one node; repeatable)')
        parser.add_argument('-o', '--output', metavar='FILE',
                            help='write the policy to FILE (default: standard output)')
        parser.add_argument('--force', action='store_true',
                            help='-o: replace the file even if nodl did not write it or it was '
                                 'edited since')
        parser.add_argument('--check', metavar='POLICY_FILE',
                            help='compare an existing policy with what the system needs: missing and '
                                 'extra grants (writes nothing)')
        parser.add_argument('--live', action='store_true',
                            help='observe the running graph instead of reading definitions')
        parser.add_argument('--timeout', type=_seconds, default=5.0, metavar='S',
                            help='--live: seconds to wait for the graph (default: 5)')
        parser.add_argument('--settle', type=_seconds, default=3.5, metavar='S',
                            help='--live: seconds of discovery before the graph is taken; nodes '
                                 'of other processes appear up to one announcement period (3 s) '
                                 'late: raise it on a loaded machine (default: 3.5)')
        group = parser.add_mutually_exclusive_group()
        group.add_argument('--enclave-per', choices=('node', 'namespace'), default=None,
                           help='one enclave per node (default; path = the node\'s name) or per '
                                'namespace')
        group.add_argument('--enclave-map', metavar='FILE',
                           help='a YAML file mapping enclave paths to node names or patterns')
        parser.add_argument('--allow-missing', action='store_true',
                            help='write the policy even if a node has no definition (an empty '
                                 'profile with a comment marks the gap)')
        parser.add_argument('--allow-gaps', action='store_true',
                            help='write the policy even if a node\'s definition is an extracted draft '
                                 'with entities still under # GAP (nothing is granted for them; a '
                                 'comment in its profile marks each)')
        from nodl.cli.arguments import add_client_library_argument, add_definitions_argument

        add_client_library_argument(parser)
        add_definitions_argument(parser)
        parser.add_argument('--distro', default=None, metavar='DISTRO',
                            help='the ROS 2 distribution whose client libraries create the base '
                                 'entities (humble, iron, jazzy, kilted, rolling; default: kilted)')
        from nodl.cli.report_options import add_format_argument

        add_format_argument(parser, "format of --check's report: a registered reporter (the "
                                    'diagnostics of writing a policy are text on standard error)')
        from nodl.cli.arguments import add_launch_code_arguments
        from nodl.cli.diagnostic_options import add_diagnostic_options

        add_launch_code_arguments(parser)
        add_diagnostic_options(parser)
        _intermixed(parser)

    def main(self, args: argparse.Namespace) -> int:
        import os

        from nodl.cli.diagnostic_options import DiagnosticPolicy, PolicyError
        from nodl.policy.distros import DEFAULT_DISTRO, check_distro

        try:
            check_distro(DEFAULT_DISTRO if args.distro is None else args.distro)
            options = DiagnosticPolicy(args, 'nodl policy')
        except (ValueError, PolicyError) as exc:
            return _usage(str(exc).removeprefix('nodl policy: error: '))
        args.distro = DEFAULT_DISTRO if args.distro is None else args.distro
        targets, values = [], {}
        for token in args.targets:
            pair = _name_value(token)
            if pair is None:
                targets.append(token)
            else:
                values[pair[0]] = pair[1]
        if args.live and targets:
            return _usage('--live observes the running graph: give no TARGET with it')
        if not args.live and not targets:
            return _usage('give a launch file, node definitions (FILE or PACKAGE EXECUTABLE), or --live')
        if args.check and args.output:
            return _usage('--check writes nothing: drop -o')
        if args.output and args.output != '-':
            from nodl.writing import output_is_input

            inputs = [t for t in targets if os.path.isfile(t)] + [args.enclave_map or '']
            clash = output_is_input(args.output, inputs)
            if clash is not None:
                print(clash, file=sys.stderr)
                return EXIT_USAGE
        enclaves: Any = args.enclave_per or 'node'
        if args.enclave_map:
            from nodl.policy.enclaves import load_enclave_mapping

            try:
                mapping, problems = load_enclave_mapping(args.enclave_map)
            except OSError as exc:
                return _usage(f'cannot read {args.enclave_map}: {_os_words(exc)}')
            if mapping is None:
                _report(problems, args, options)
                return EXIT_USAGE
            enclaves = mapping
        result = self._expected(args, targets, values, enclaves)
        if isinstance(result, int):
            return result
        diagnostics = _report(result.diagnostics, args, options)
        if any(getattr(source, 'source', source) != 'file' for source in result.sources):  # looked up
            from nodl.targets.resolve import coverage_line

            print(coverage_line(result.sources), file=sys.stderr)
        if args.output and args.output != '-':  # what was read is known now: none is written
            from nodl.writing import output_is_input

            clash = output_is_input(args.output, [*result.files, args.enclave_map or '',
                                                  *_config_files(targets)])
            if clash is not None:
                print(clash, file=sys.stderr)
                return EXIT_USAGE
        from nodl.diagnostics import Severity

        failed = any(d.severity is Severity.ERROR for d in diagnostics)
        if args.check:
            return _check(args, result.policy, options, failed)
        if failed:
            print('nodl policy: no policy written: it could not be exact (see above)', file=sys.stderr)
            return EXIT_FAILURE
        from nodl.policy.writer import PolicyNotWritable, write_policy

        try:
            text = write_policy(result.policy)
        except PolicyNotWritable as exc:
            _report(exc.diagnostics, args, options)
            print('nodl policy: no policy written: SROS 2 would reject it', file=sys.stderr)
            return EXIT_FAILURE
        if args.output and args.output != '-':
            from nodl.writing import write_marked

            # marked, atomic; a user's or an edited policy needs --force (the runner prints why not)
            write_marked(args.output, text, force=args.force, style='xml')
        else:
            sys.stdout.write(text)
        return EXIT_OK

    def _expected(self, args: argparse.Namespace, targets: list[str], values: dict[str, str],
                  enclaves: Any) -> Any:
        if args.live:
            from nodl.live.session import LiveError
            from nodl.policy.live import live_policy

            try:
                live = live_policy(timeout=max(args.timeout, args.settle), settle=args.settle,
                                   distro=args.distro, enclaves=enclaves,
                                   client_library=args.client_library)
            except LiveError as exc:
                return _usage(str(exc))
            for line in live.unobserved:
                print(f'nodl policy: not observed: {line}', file=sys.stderr)
            return live.result
        from nodl.targets.placement import place_definitions, split_targets

        try:
            definitions, launches = split_targets(targets)
        except ValueError as exc:
            return _usage(str(exc))
        import os

        from nodl.cli.arguments import load_definitions

        first = next((d.file for d in definitions if d.file is not None), None) or \
            (launches[0] if launches else None)
        folders = load_definitions(args, 'nodl policy', os.path.dirname(os.path.abspath(first))
                                   if first else None, report=False)
        if isinstance(folders, int):
            return folders
        layout = folders.diagnostics
        if launches and (definitions or len(launches) > 1):
            return _usage('give one launch file, or node definitions, not both')
        if launches:
            if args.name or args.remap:
                return _usage('--name and --remap place definitions; a launch file names its nodes')
            from nodl.cli.arguments import launch_limits
            from nodl.policy.launched import launch_policy

            try:
                launched = launch_policy(launches[0], values, client_library=args.client_library,
                                         distro=args.distro, enclaves=enclaves,
                                         allow_missing=args.allow_missing,
                                         limits=launch_limits(args), definitions=folders,
                                         allow_gaps=args.allow_gaps)
                return launched._replace(diagnostics=layout + launched.diagnostics)
            except OSError as exc:
                return _usage(f'cannot read {launches[0]}: {_os_words(exc)}')
            except ValueError as exc:
                return _usage(str(exc))
        for definition in definitions:
            if definition.file is not None and not os.path.isfile(definition.file):
                what = 'is a directory' if os.path.isdir(definition.file) else 'no such file'
                return _usage(f'{definition.file}: {what}')
        parameters = {name: _typed(value) for name, value in values.items()}
        try:
            placed, problems = place_definitions(
                definitions, args.name, remaps=args.remap, parameters=parameters,
                client_library=args.client_library, folders=folders)
        except ValueError as exc:
            return _usage(str(exc))
        except OSError as exc:
            return _usage(f'cannot read {exc.filename or ""}: {_os_words(exc)}')
        from nodl.policy.generate import gapped_nodes, policy_for_instances

        result = policy_for_instances([p.instance for p in placed], distro=args.distro,
                                      enclaves=enclaves,
                                      allow_missing=args.allow_missing,
                                      gapped=gapped_nodes((p.instance.fqn, p.file, None)
                                                          for p in placed),
                                      allow_gaps=args.allow_gaps,
                                      notes=['Least-privilege SROS 2 policy written by nodl policy '
                                             'from node definitions.'])
        read = [d.file for d in definitions if d.file is not None] + [
            f for p in placed for f in [p.file, *p.instance.resolved.files]]
        return result._replace(diagnostics=layout + problems + result.diagnostics,
                               sources=tuple(p.provenance for p in placed)
                               + ('none',) * (len(definitions) - len(placed)),
                               files=tuple(dict.fromkeys(read)))


def _intermixed(parser: argparse.ArgumentParser) -> None:
    """Let options and targets come in any order (``a.yaml --name /x b.yaml``): the
    targets are collected wherever they are written (argparse's intermixed parsing, for
    this verb's parser only; the i-th ``--name`` still places the i-th definition)."""
    plain = parser.parse_known_args
    inner = [False]

    def parse_known_args(args: Any = None, namespace: Any = None) -> Any:
        if inner[0]:  # (the intermixed parse calls back here for its two passes)
            return plain(args, namespace)
        inner[0] = True
        try:
            return parser.parse_known_intermixed_args(args, namespace)
        finally:
            inner[0] = False

    parser.parse_known_args = parse_known_args  # type: ignore[method-assign]


def _seconds(text: str) -> float:
    from nodl.cli.arguments import seconds

    return seconds(text)


def _typed(value: str) -> Any:
    """A parameter value typed as YAML types it (``true`` -> True, ``5`` -> 5)."""
    import yaml

    try:
        return yaml.safe_load(value) if value else ''
    except yaml.YAMLError:
        return value


def _config_files(targets: list[str]) -> list[str]:
    """The configuration files that apply to the targets given as files (definitions folders
    and settings are read from them)."""
    import os

    from nodl.config import find_config_file

    found = (find_config_file(os.path.dirname(os.path.abspath(t))) for t in targets
             if os.path.isfile(t))
    return [f for f in found if f]


def _os_words(exc: OSError) -> str:
    from nodl.files import describe_os_error

    return describe_os_error(exc)


def _usage(message: str) -> int:
    print(f'nodl policy: error: {message}', file=sys.stderr)
    return EXIT_USAGE


def _report(diagnostics: list[Diagnostic], args: argparse.Namespace, options: Any,
            stream: Any = None, reporter: Any = None) -> list[Diagnostic]:
    """Show ``diagnostics`` after the overrides, without infos: on standard error as text, or
    on ``stream`` as ``reporter`` renders them (``--check``'s report)."""
    from nodl.cli.report_options import show_diagnostics, write_report
    from nodl.reporting import without_info
    from nodl.reporting.reporters import Report

    shown: list[Diagnostic] = []
    by_file: dict[str, list[Diagnostic]] = {}
    for d in diagnostics:
        by_file.setdefault(d.file, []).append(d)
    for file, group in by_file.items():
        shown += options.apply(file, group)
    shown = without_info(shown)
    if stream is not None and reporter is not None:
        write_report(reporter, Report('nodl policy', shown), stream)
    else:
        show_diagnostics(shown)
    return shown


def _check(args: argparse.Namespace, expected: Any, options: Any, failed: bool) -> int:
    from nodl.cli.report_options import reporter_for
    from nodl.diagnostics import Severity
    from nodl.policy.check import check_policy_file

    reporter = reporter_for(args, 'nodl policy')
    if reporter is None:
        return EXIT_USAGE
    try:
        found = check_policy_file(args.check, expected)
    except OSError as exc:
        return _usage(f'cannot read {args.check}: {_os_words(exc)}')
    shown = _report(found, args, options, sys.stdout, reporter)
    missing = sum(d.code in ('NODL604', 'NODL607') for d in shown)
    extra = sum(d.code in ('NODL605', 'NODL608') for d in shown)
    misplaced = sum(d.code == 'NODL609' for d in shown)
    errors = sum(d.severity is Severity.ERROR for d in shown)
    summary = f'{args.check}: {missing} missing, {extra} extra'
    if misplaced:
        summary += f', {misplaced} in another enclave'
    if errors - missing - extra - misplaced:
        summary += f', {errors - missing - extra - misplaced} other errors'
    if not errors and not failed:
        summary += ': the policy grants exactly what the system needs'
    print(summary, file=sys.stderr)
    return EXIT_FAILURE if errors or failed else EXIT_OK
