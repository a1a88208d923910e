"""``--format NAME`` for every verb that reports: its choices are the registered reporters.

A verb calls :func:`add_format_argument` in ``add_arguments`` and
:func:`reporter_for` in ``main``.  For a verb that reports diagnostics the
choices are the names registered under ``nodl.reporters`` (read from the
installed metadata, nothing imported); only the reporter ``--format`` names is
loaded, when the verb reports.  A verb with another kind of result
(``nodl list``) offers only the reporters that can show it.
"""

from __future__ import annotations

import argparse
import sys

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import TextIO

    from nodl.reporting.reporters import Report, ReporterExtension

__all__ = ['BUILTIN_FORMATS', 'reporter_names', 'add_format_argument', 'reporter_for', 'write_report']

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


def reporter_for(args: argparse.Namespace, prog: str,
                 kind: str = 'diagnostics') -> ReporterExtension | None:
    """The reporter ``--format`` names, loaded now; None (after one line on standard error)
    when it cannot be loaded or cannot show a result of ``kind``: a usage error."""
    from nodl.plugins import instantiate_extensions

    name = args.format
    found = instantiate_extensions(GROUP, names=[name])
    reporter: ReporterExtension | None = found.get(name)
    if reporter is None:
        print(f"{prog}: error: --format {name}: the reporter '{name}' could not be loaded (see the "
              'warning about it; give another --format)', file=sys.stderr)
        return None
    if not reporter.supports(kind):
        print(f"{prog}: error: --format {name}: this reporter cannot show a {kind} (use one of: "
              f"{', '.join(reporter_names(kind))})", file=sys.stderr)
        return None
    return reporter


def write_report(reporter: ReporterExtension, report: Report, out: TextIO | None = None,
                 err: TextIO | None = None) -> None:
    """Write ``report`` as ``reporter`` renders it on ``out`` (standard output); a machine format's
    summary goes apart, on ``err`` (standard error), for the person watching."""
    (out or sys.stdout).write(reporter.report(report))
    if not reporter.FOR_PEOPLE and report.summary:
        print(report.summary, file=err or sys.stderr)
