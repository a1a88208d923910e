"""Argument types and checks shared by verbs: rejected at once, before any ROS start-up."""

from __future__ import annotations

import argparse
import os

__all__ = ['seconds', 'node_name', 'definition_problem', 'add_client_library_argument']


def seconds(text: str) -> float:
    """An ``argparse`` type: a number of seconds, zero or more."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds") from None
    if not value >= 0 or value == float('inf'):  # also rejects nan
        raise argparse.ArgumentTypeError(f"'{text}': expected a number of seconds, 0 or more")
    return value


def node_name(text: str) -> str:
    """An ``argparse`` type: a node name (``/namespace/name``, or ``name`` in ``/``)."""
    from nodl_schema.live.session import node_name_problem

    problem = node_name_problem(text)
    if problem is not None:
        raise argparse.ArgumentTypeError(f"'{text}' is not a node name: {problem}")
    return text


def _looks_like_a_path(text: str) -> bool:
    # A package name is letters, digits and '_': anything with a dot or a slash is a path.
    return any(c in text for c in './\\') or os.path.exists(text)


def definition_problem(targets: list[str]) -> str | None:
    """Why ``targets`` is not ``FILE`` or ``PACKAGE EXECUTABLE``, or None."""
    if len(targets) > 2:
        return f'expected FILE or PACKAGE EXECUTABLE, got {len(targets)} arguments'
    if len(targets) == 2 and _looks_like_a_path(targets[0]):
        return (f"'{targets[0]}' is a file, so one is expected: give FILE, or PACKAGE EXECUTABLE "
                '(a package name and one of its executables, looked up in the ament index)')
    return None


def add_client_library_argument(parser: argparse.ArgumentParser, default: str | None = None) -> None:
    """``--client-library``: whose base a node inherits (show, check, describe).

    ``default`` says, for the help, what happens without the option.
    """
    from nodl_schema.vocabulary import CLIENT_LIBRARIES

    default = default or ("from the package's build type for a registered node, ament_python -> "
                          f'rclpy, ament_cmake -> rclcpp; else {CLIENT_LIBRARIES[0]}')
    parser.add_argument('--client-library', choices=CLIENT_LIBRARIES, default=None,
                        help=f'the client library whose base the node inherits (default: {default})')
