"""Building the verb parser and running a verb, for ``nodl`` and ``ros2 nodl``."""

from __future__ import annotations

import argparse
import sys

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

from nodl_schema.cli.verb import EXIT_INTERNAL, EXIT_USAGE, help_text

__all__ = ['VERB_GROUP', 'add_verbs', 'run_verb']

VERB_GROUP = 'nodl.verbs'


def add_verbs(parser: argparse.ArgumentParser, dest: str = '_verb',
              argv: list[str] | None = None) -> dict[str, Any]:
    """Add one sub-command per verb plugin; a broken plugin is reported and skipped.

    With ``argv``, verbs are added on demand: when its first argument names
    a verb, only that verb is loaded and given a parser (what ros2cli does
    too); otherwise, for help or a mistyped verb, every verb is.
    """
    from nodl_schema.plugins import iter_entry_points, load_plugins

    wanted = None
    if argv:
        first = next((a for a in argv if not a.startswith('-')), None)
        if first is not None and first in {e.name for e in iter_entry_points(VERB_GROUP)}:
            wanted = [first]
    verbs: dict[str, Any] = {}
    # An explicit prog spares argparse building a help formatter on every run.
    subparsers = parser.add_subparsers(title='verbs', metavar='VERB', dest=dest,
                                       prog=parser.prog)
    for name, factory in sorted(load_plugins(VERB_GROUP, names=wanted).items()):
        try:
            verb = factory()
            text = help_text(verb)
            sub = subparsers.add_parser(name, help=text, description=text)
            verb.add_arguments(sub)
        except Exception as exc:  # noqa: BLE001 - a broken plugin must not break the tool
            print(f"warning: skipped verb '{name}': {type(exc).__name__}: {exc}", file=sys.stderr)
            continue
        sub.set_defaults(**{dest: verb})
        verbs[name] = verb
    return verbs


def run_verb(parser: argparse.ArgumentParser, args: argparse.Namespace, dest: str = '_verb') -> int:
    """Run the verb chosen in ``args``; internal errors become one line, not a traceback."""
    verb = getattr(args, dest, None)
    if verb is None:
        parser.print_help()
        return EXIT_USAGE
    try:
        return int(verb.main(args))
    except KeyboardInterrupt:
        print('interrupted', file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except Exception as exc:  # noqa: BLE001 - the last line of defence
        name = type(verb).__name__
        print(f'nodl: internal error in {name}: {type(exc).__name__}: {exc} (this is a bug in '
              'the toolkit or a plugin; please report it with the command and the input files)',
              file=sys.stderr)
        return EXIT_INTERNAL
