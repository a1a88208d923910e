# PYTHON_ARGCOMPLETE_OK
"""The ``nodl`` command (shell completion: see :mod:`nodl.cli.completion`)."""

from __future__ import annotations

import argparse
import gc
import os
import sys

from nodl.cli.runner import HelpFormatter, add_verbs, run_verb
from nodl.version import __version__

__all__ = ['main', 'build_parser']


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The ``nodl`` argument parser (with only the verb ``argv`` names, if it names one)."""
    parser = argparse.ArgumentParser(
        prog='nodl', formatter_class=HelpFormatter,
        description='NoDL toolkit: validate, compose and inspect ROS 2 node definitions.')
    parser.add_argument('--version', action='version', version=f'%(prog)s {__version__}')
    add_verbs(parser, argv=argv)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``nodl``; returns the exit code."""
    program = argv is None  # (the command itself, not a caller passing arguments)
    if argv is None:
        argv = sys.argv[1:]
        if os.environ.get('_ARGCOMPLETE'):  # a shell asks for completions (argcomplete)
            # (loaded only then: completion is not part of running a verb)
            from nodl.cli.completion import autocomplete

            autocomplete(build_parser)
    parser = build_parser(argv)
    args = parser.parse_args(argv)
    code = run_verb(parser, args)
    if program:
        # The process ends now: what is still alive is moved out of the collector's generations,
        # so that the interpreter's shutdown does not walk it all once more (about 20 ms of
        # processor time after nodl analyse of nav2's bringup).
        gc.freeze()
    return code


if __name__ == '__main__':
    sys.exit(main())
