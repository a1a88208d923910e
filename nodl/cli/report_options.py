"""``--format NAME`` for every verb that reports: its choices are the registered reporters.

A verb calls :func:`add_format_argument` in ``add_arguments``,
:func:`reporter_for` in ``main`` and :func:`write_report` to write what it
found.  For a verb that reports diagnostics the choices are the names
registered under ``nodl.reporters`` (read from the installed metadata, nothing
imported); only the reporter ``--format`` names is loaded, when the verb
reports.  A verb with another kind of result (``nodl list``) offers only the
reporters that can show it.

This module is the one place the command line turns results into output:
:func:`write_report` (a report, on a stream or into a file, its summary apart
for a machine format), :func:`write_report_file` (a second report in a named
format, as ``nodl check --junit FILE`` writes) and :func:`show_diagnostics`
(the diagnostics a verb whose output is a document shows a person on standard
error, as the ``text`` reporter renders them).
"""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import TextIO

    from nodl.cli.diagnostic_options import DiagnosticPolicy
    from nodl.diagnostics import Diagnostic
    from nodl.reporting.reporters import Report, ReporterExtension

__all__ = ['BUILTIN_FORMATS', 'reporter_names', 'add_format_argument', 'reporter_for', 'load_reporter',
           'policy_and_reporter', 'write_report', 'write_report_file', 'show_diagnostics']

GROUP = 'nodl.reporters'
#: The built-in reporters, in the order --help lists them; plug-ins follow by name.
BUILTIN_FORMATS = ('text', 'json', 'sarif', 'junit')


def _ordered(names: set[str]) -> list[str]:
    return [n for n in BUILTIN_FORMATS if n in names] + sorted(names - set(BUILTIN_FORMATS))


def reporter_names(kind: str = 'diagnostics') -> list[str]:
    """The names of the registered reporters that can show a result of ``kind``."""
    from nodl.plugins import iter_entry_points

    names = {spec.name for spec in iter_entry_points(GROUP)}
    if kind == 'diagnostics':  # every reporter shows diagnostics: nothing to import
        return _ordered(names)
    from nodl.plugins import instantiate_extensions

    return _ordered({name for name, reporter in instantiate_extensions(GROUP).items()
                     if reporter.supports(kind)})


def add_format_argument(parser: argparse.ArgumentParser, help: str, *, kind: str = 'diagnostics',
                        extra: tuple[str, ...] = ()) -> None:
    """Declare ``--format`` (default ``text``): the registered reporters of ``kind``, then ``extra``
    (formats the verb writes itself, such as ``nodl monitor``'s ``jsonl`` stream)."""
    choices = [*reporter_names(kind), *extra]
    parser.add_argument('--format', choices=choices, default='text',
                        help=f'{help} (default: text; one of: {", ".join(choices)})')


def load_reporter(name: str) -> ReporterExtension | None:
    """The reporter registered as ``name``, loaded now (None when it cannot be loaded: the
    plug-in machinery has warned about it)."""
    from nodl.plugins import instantiate_extensions

    found: ReporterExtension | None = instantiate_extensions(GROUP, names=[name]).get(name)
    return found


def reporter_for(args: argparse.Namespace, prog: str,
                 kind: str = 'diagnostics') -> ReporterExtension | None:
    """The reporter ``--format`` names, loaded now; None (after one line on standard error)
    when it cannot be loaded or cannot show a result of ``kind``: a usage error."""
    name = args.format
    reporter = load_reporter(name)
    if reporter is None:
        print(f"{prog}: error: --format {name}: the reporter '{name}' could not be loaded (see the "
              'warning about it; give another --format)', file=sys.stderr)
        return None
    if not reporter.supports(kind):
        print(f"{prog}: error: --format {name}: this reporter cannot show a {kind} (use one of: "
              f"{', '.join(reporter_names(kind))})", file=sys.stderr)
        return None
    return reporter


def policy_and_reporter(args: argparse.Namespace, prog: str, kind: str = 'diagnostics'
                        ) -> tuple[DiagnosticPolicy, ReporterExtension] | None:
    """What a verb that reports diagnostics is asked for: the codes to ignore or promote
    (``--ignore`` / ``--error``, then the configuration files found upward from each file)
    and the reporter ``--format`` names.  None (after one line on standard error) for a bad
    code, configuration or format: a usage error."""
    from nodl.cli.diagnostic_options import DiagnosticPolicy, PolicyError

    try:
        policy = DiagnosticPolicy(args, prog)
    except PolicyError as exc:
        print(exc, file=sys.stderr)
        return None
    reporter = reporter_for(args, prog, kind)
    return None if reporter is None else (policy, reporter)


def write_report(reporter: ReporterExtension, report: Report, out: TextIO | None = None,
                 err: TextIO | None = None, *, path: str | None = None) -> None:
    """Write ``report`` as ``reporter`` renders it on ``out`` (standard output), or into the file
    ``path`` (atomically: a report is always replaceable; a failure is a
    :class:`~nodl.writing.WriteError`); a machine format's summary goes apart, on ``err``
    (standard error), for the person watching."""
    text = reporter.report(report)
    if path is not None:
        from nodl.cli.output import write_file

        write_file(path, text)
    else:
        (out or sys.stdout).write(text)
    if not reporter.FOR_PEOPLE and report.summary:
        print(report.summary, file=err or sys.stderr)


def write_report_file(name: str, report: Report, path: str) -> None:
    """Write ``report`` into the file ``path`` (atomically) in the registered format ``name``:
    a report besides the one ``--format`` prints, such as ``nodl check --junit FILE``.  A
    format that cannot be loaded is a :class:`~nodl.writing.WriteError` (NODL030), as a
    file that cannot be written is."""
    reporter = load_reporter(name)
    if reporter is None:
        from nodl.diagnostics import Diagnostic, Severity
        from nodl.writing import WriteError

        raise WriteError(Diagnostic(Severity.ERROR, f"not written: the reporter '{name}' could not "
                                    'be loaded (see the warning about it)', file=path,
                                    code='NODL030'))
    from nodl.cli.output import write_file

    write_file(path, reporter.report(report))


def show_diagnostics(diagnostics: Iterable[Diagnostic], stream: TextIO | None = None) -> None:
    """Show a person ``diagnostics`` on ``stream`` (standard error) as the ``text`` reporter
    renders them: what a verb whose output is a document (a definition, a parameter file,
    generated code) found on the way."""
    from nodl.reporting import format_text

    (stream or sys.stderr).write(format_text(diagnostics))
