"""Building the verb parser and running a verb, for ``nodl`` and ``ros2 nodl``."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys

from nodl.cli.output import COLOR_CHOICES, OutputError, guarded_streams
from nodl.cli.verb import (
    EXIT_BROKEN_PIPE,
    EXIT_INTERNAL,
    EXIT_INTERRUPTED,
    EXIT_USAGE,
    VerbExtension,
    exit_status_epilog,
    help_text,
)
from nodl.plugins import instantiate_extensions, iter_entry_points, take_plugin_errors
from nodl.write_error import WriteError

__all__ = ['VERB_GROUP', 'HelpFormatter', 'add_verbs', 'add_common_arguments', 'run_verb']

VERB_GROUP = 'nodl.verbs'


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """argparse's formatter, sized like it without importing shutil.

    argparse builds a formatter for every ``add_argument`` and sizes it with
    ``shutil.get_terminal_size()``; importing shutil (and bz2, lzma, zlib)
    costs the command line ~3 ms of start-up on every run.
    """

    def __init__(self, prog: str, indent_increment: int = 2, max_help_position: int = 24,
                 width: int | None = None) -> None:
        if width is None:
            try:
                width = int(os.environ.get('COLUMNS', '0'))
            except ValueError:
                width = 0
            if width <= 0:
                try:
                    width = os.get_terminal_size(sys.__stdout__.fileno()).columns  # type: ignore[union-attr]
                except (AttributeError, ValueError, OSError):
                    width = 0
            width = (width or 80) - 2  # as argparse does
        super().__init__(prog, indent_increment, max_help_position, width)


def add_verbs(parser: argparse.ArgumentParser, dest: str = '_verb',
              argv: list[str] | None = None) -> dict[str, VerbExtension]:
    """Add one sub-command per verb plugin; a broken plugin is reported and skipped.

    With ``argv``, verbs are added on demand: when its first argument names
    a verb, only that verb is loaded and given a parser (what ros2cli does
    too); otherwise, for help or a mistyped verb, every verb is.
    """
    wanted = None
    if argv:
        first = next((a for a in argv if not a.startswith('-')), None)
        if first is not None and first in {e.name for e in iter_entry_points(VERB_GROUP)}:
            wanted = [first]
    verbs: dict[str, VerbExtension] = {}
    # An explicit prog spares argparse building a help formatter on every run.
    subparsers = parser.add_subparsers(title='verbs', metavar='VERB', dest=dest,
                                       prog=parser.prog)
    verbs_found = instantiate_extensions(VERB_GROUP, names=wanted, on_error=_warn_plugin)
    for name, verb in sorted(verbs_found.items()):
        try:
            text = help_text(verb)
            sub = subparsers.add_parser(name, help=text, description=text,
                                        epilog=exit_status_epilog(verb),
                                        formatter_class=HelpFormatter)
            verb.add_arguments(sub)
            if sub.epilog and 'exit status:' not in sub.epilog:
                # A verb's own epilog comes first; the exit statuses always close --help.
                sub.epilog = f'{sub.epilog}\n\n{exit_status_epilog(verb)}'
            add_common_arguments(sub)
        except Exception as exc:  # noqa: BLE001 - a broken plugin must not break the tool
            print(f"warning: skipped verb '{name}': {type(exc).__name__}: {exc}", file=sys.stderr)
            continue
        sub.set_defaults(**{dest: verb})
        verbs[name] = verb
    return verbs


def add_common_arguments(parser: argparse.ArgumentParser) -> None:
    """The options every verb has (``--color``)."""
    if any('--color' in a.option_strings for a in parser._actions):
        return  # the verb declares its own
    parser.add_argument('--color', choices=COLOR_CHOICES, default='auto',
                        help='colour severity words: auto (on a terminal, unless NO_COLOR is '
                             'set), always or never (default: auto)')


def run_verb(parser: argparse.ArgumentParser, args: argparse.Namespace, dest: str = '_verb') -> int:
    """Run the verb chosen in ``args``, with the exit statuses of :data:`~nodl.cli.verb.EXIT_STATUSES`.

    Internal errors become one line, not a traceback; output that cannot be
    written is one ``cannot write ...`` line and status 2; a closed pipe ends
    quietly with status 141; Ctrl-C keeps what was printed and ends with 130.
    """
    verb = getattr(args, dest, None)
    if verb is None:
        parser.print_help()
        return EXIT_USAGE
    with guarded_streams(getattr(args, 'color', 'auto')) as (out, _):
        try:
            try:
                code = int(verb.main(args))
            finally:
                out.flush()  # what the verb printed reaches its reader, also when it failed
            return code
        except KeyboardInterrupt:
            _report('interrupted')
            return EXIT_INTERRUPTED
        except BrokenPipeError:
            _silence_stdout()
            return EXIT_BROKEN_PIPE
        except OutputError as exc:
            _silence_stdout()
            _report(f'error: {exc}')
            return EXIT_USAGE
        except WriteError as exc:  # a file not written or not replaced: its own coded line
            with contextlib.suppress(OSError):
                sys.stderr.write(f'{exc.diagnostic}\n')
            return EXIT_USAGE
        except Exception as exc:  # noqa: BLE001 - the last line of defence
            name = type(verb).__name__
            _report(f'internal error in {name}: {type(exc).__name__}: {exc} (this is a bug in '
                    'the toolkit or a plugin; please report it with the command and the input files)')
            return EXIT_INTERNAL
        finally:
            _show_plugin_errors()


def _warn_plugin(error: object) -> None:
    """A plugin the command skips: one warning line on standard error."""
    print(error, file=sys.stderr)


def _show_plugin_errors() -> None:
    """The plugins (resolvers, generators, ...) the library skipped while the verb ran."""
    for error in take_plugin_errors():
        try:
            print(error, file=sys.stderr)
        except Exception:  # noqa: BLE001 - stderr closed or broken: nowhere left to say it
            return


def _report(line: str) -> None:
    """One line on standard error, even if it can no longer be written."""
    try:
        sys.stderr.write(f'nodl: {line}\n')
        sys.stderr.flush()
    except (OSError, Exception):  # noqa: BLE001 - nowhere left to say it
        pass


def _silence_stdout() -> None:
    """Point standard output at /dev/null, so that Python's own flush at exit cannot fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.__stdout__.fileno())  # type: ignore[union-attr]
        os.close(devnull)
    except (OSError, AttributeError, ValueError):
        pass
