"""Argument types and checks shared by verbs: rejected at once, before any ROS start-up."""

from __future__ import annotations

import argparse
import os

TYPE_CHECKING = False
if TYPE_CHECKING:
    from nodl_schema.launch.sandbox import LaunchLimits

__all__ = ['seconds', 'node_name', 'definition_problem', 'add_client_library_argument',
           'positive_seconds', 'mebibytes', 'add_launch_code_arguments', 'launch_limits',
           'LAUNCH_CODE_HELP']


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


def positive_seconds(text: str) -> float:
    """An ``argparse`` type: a number of seconds greater than 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds") from None
    if not value > 0 or value == float('inf'):  # also rejects nan
        raise argparse.ArgumentTypeError(f"'{text}': expected a number of seconds greater than 0")
    return value


def mebibytes(text: str) -> float:
    """An ``argparse`` type: a number of MiB greater than 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of MiB") from None
    if not value > 0 or value == float('inf'):  # also rejects nan
        raise argparse.ArgumentTypeError(f"'{text}': expected a number of MiB greater than 0")
    return value


#: What reading a launch file runs, for the verbs' help (their description's last paragraph).
LAUNCH_CODE_HELP = (
    'Reading a Python launch file runs its code, and $(eval ...) runs Python, as ros2 launch '
    'does: that code runs in a child process forked for it, limited by --launch-timeout and '
    '--launch-memory; $(command ...) is never run. --no-exec runs no launch-file code at all '
    '(for CI on untrusted changes): a Python launch file is then an error where it is '
    'included, and $(eval ...) a value unknown here.')


def add_launch_code_arguments(parser: argparse.ArgumentParser) -> None:
    """``--no-exec``, ``--launch-timeout`` and ``--launch-memory``: whether and how the Python
    code of a launch file (Python launch files, ``$(eval)``) runs (see :func:`launch_limits`)."""
    from nodl_schema.launch.sandbox import DEFAULT_MEMORY_MIB, DEFAULT_TIMEOUT

    group = parser.add_argument_group('launch-file code', LAUNCH_CODE_HELP)
    group.add_argument('--no-exec', action='store_true',
                       help='run no code of the launch files: a Python launch file is not read '
                            '(an error where it is included), $(eval ...) is a value unknown here')
    group.add_argument('--launch-timeout', type=positive_seconds, default=DEFAULT_TIMEOUT,
                       metavar='SECONDS',
                       help="wall-clock seconds the launch's Python code may take in all, in its "
                            f'child process (default: {DEFAULT_TIMEOUT:g})')
    group.add_argument('--launch-memory', type=mebibytes, default=DEFAULT_MEMORY_MIB, metavar='MIB',
                       help="MiB of memory the launch's Python code may allocate in its child "
                            f'process (default: {DEFAULT_MEMORY_MIB:g})')


def launch_limits(args: argparse.Namespace) -> 'LaunchLimits':
    """The :class:`~nodl_schema.launch.sandbox.LaunchLimits` the options of
    :func:`add_launch_code_arguments` give."""
    from nodl_schema.launch.sandbox import LaunchLimits

    return LaunchLimits(execute=not args.no_exec, timeout=args.launch_timeout,
                        memory_mib=args.launch_memory)
