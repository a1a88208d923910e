"""The ``nodl`` command."""

from __future__ import annotations

import argparse
import sys

from nodl_schema.cli.runner import add_verbs, run_verb

__all__ = ['main', 'build_parser']


def build_parser() -> argparse.ArgumentParser:
    """The ``nodl`` argument parser with every installed verb."""
    parser = argparse.ArgumentParser(
        prog='nodl',
        description='NoDL toolkit: validate, compose and inspect ROS 2 node definitions.')
    from nodl_schema import __version__
    parser.add_argument('--version', action='version', version=f'%(prog)s {__version__}')
    add_verbs(parser)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``nodl``; returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    return run_verb(parser, args)


if __name__ == '__main__':
    sys.exit(main())
