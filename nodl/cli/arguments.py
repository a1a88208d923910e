"""Argument types and checks shared by verbs: rejected at once, before any ROS start-up."""

from __future__ import annotations

import argparse
import os
import sys
from typing import TYPE_CHECKING

from nodl.cli.report_options import show_diagnostics
from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from nodl.config import ConfigError
from nodl.diagnostics import Severity
from nodl.naming import full_name_error, join_name, namespace_error, node_name_error, split_name
from nodl.vocabulary import CLIENT_LIBRARIES, LAUNCH_CODE_MEMORY_MIB, LAUNCH_CODE_TIMEOUT

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from nodl.launch.sandbox import LaunchLimits
    from nodl.registry.overlay import Definitions

__all__ = ['seconds', 'node_name', 'node_name_problem', 'definition_problem', 'add_client_library_argument',
           'positive_seconds', 'mebibytes', 'add_launch_code_arguments', 'launch_limits',
           'LAUNCH_CODE_HELP', 'add_definitions_argument', 'load_definitions',
           'definitions_failed', 'run_with_definitions', 'launch_arguments', 'usage_error']


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
    problem = node_name_problem(text)
    if problem is not None:
        raise argparse.ArgumentTypeError(f"'{text}' is not a node name: {problem}")
    return text


def node_name_problem(name: str) -> str | None:
    """Why ``name`` is not the name of a running node (``/namespace/name`` or ``name``), or None.

    rcl's rules, as :mod:`nodl.naming` implements them (the fully qualified name, its
    namespace and its base name), without the ``~`` and ``{}`` substitutions, which a
    running node's name never holds; worded for the person who typed it.
    """
    if not name.strip():
        return 'a node name must not be empty'
    if name == '/':
        return "'/' is a namespace, not a node name"
    if any(c in name for c in '~{}'):
        return "a running node's name holds no '~' or '{}' substitutions; write /namespace/name"
    fqn = name if name.startswith('/') else join_name('/', name)
    reason = full_name_error(fqn)
    if reason is None:
        namespace, base = split_name(fqn)
        reason = namespace_error(namespace) or node_name_error(base)
    if reason is None:
        return None
    if 'number' in reason:
        token = next(t for t in fqn.split('/') if t[:1].isdigit())
        return f"token '{token}' starts with a digit; name tokens must start with a letter or '_'"
    if 'characters other than' in reason:
        char = next(c for c in fqn if not (c.isascii() and (c.isalnum() or c in '_/')))
        return f"contains {char!r}; a node name holds letters, digits, '_' and '/' between its tokens"
    if "end with a '/'" in reason:
        return "ends with '/'; write /namespace/name"
    if 'repeated' in reason:
        return "contains a repeated '/'"
    return f'is too long ({len(fqn)} characters): {reason}'


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
    group = parser.add_argument_group('launch-file code', LAUNCH_CODE_HELP)
    group.add_argument('--no-exec', action='store_true',
                       help='run no code of the launch files: a Python launch file is not read '
                            '(an error where it is included), $(eval ...) is a value unknown here')
    group.add_argument('--launch-timeout', type=positive_seconds, default=LAUNCH_CODE_TIMEOUT,
                       metavar='SECONDS',
                       help="wall-clock seconds the launch's Python code may take in all, in its "
                            f'child process (default: {LAUNCH_CODE_TIMEOUT:g})')
    group.add_argument('--launch-memory', type=mebibytes, default=LAUNCH_CODE_MEMORY_MIB, metavar='MIB',
                       help="MiB of memory the launch's Python code may allocate in its child "
                            f'process (default: {LAUNCH_CODE_MEMORY_MIB:g})')


def launch_limits(args: argparse.Namespace) -> LaunchLimits:
    """The :class:`~nodl.launch.sandbox.LaunchLimits` the options of
    :func:`add_launch_code_arguments` give."""
    from nodl.launch.sandbox import LaunchLimits

    return LaunchLimits(execute=not args.no_exec, timeout=args.launch_timeout,
                        memory_mib=args.launch_memory)


def launch_arguments(launch_file: str, items: Sequence[str], prog: str) -> dict[str, str] | int:
    """The launch arguments ``NAME:=VALUE`` given with ``launch_file``, as a mapping; EXIT_USAGE
    after saying why when one is not ``NAME:=VALUE`` or the launch file cannot be read (NODL020)."""
    arguments: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition(':=')
        if not sep or not name:
            print(f"{prog}: error: launch argument '{item}' is not NAME:=VALUE", file=sys.stderr)
            return EXIT_USAGE
        arguments[name] = value
    if not os.path.isfile(launch_file):
        why = 'is a directory' if os.path.isdir(launch_file) else 'no such file'
        print(f'{launch_file}: error: cannot read the launch file: {why} [NODL020]', file=sys.stderr)
        return EXIT_USAGE
    return arguments


def usage_error(prog: str, exc: ValueError | OSError) -> int:
    """Say what a library call refused (a ValueError's words; an OSError in words, without
    ``[Errno N]``) as ``PROG: error: ...``: EXIT_USAGE."""
    from nodl.files import describe_os_error

    why = describe_os_error(exc) if isinstance(exc, OSError) else str(exc)
    print(f'{prog}: error: {why}', file=sys.stderr)
    return EXIT_USAGE


def add_definitions_argument(parser: argparse.ArgumentParser) -> None:
    """``--definitions DIR`` (repeatable): definitions folders (overlays) looked in before the
    ament index, after which come ``NODL_PATH`` and ``nodl.toml``'s ``definitions``."""
    parser.add_argument('--definitions', action='append', default=[], metavar='DIR',
                        help='a definitions folder (DIR/<package>/<executable>.nodl.yaml, '
                             'DIR/<package>/interfaces/<name>.nodl.yaml, DIR/<package>/nodes.yaml) '
                             'looked in before NODL_PATH, nodl.toml\'s definitions and the ament '
                             'index; repeat it for more (the first that has a definition wins)')


def load_definitions(args: argparse.Namespace, prog: str, start: str | None = None,
                     report: bool = True) -> Definitions | int:
    """The definitions folders of a run (:func:`nodl.targets.resolve.gather_definitions`:
    ``--definitions``, ``NODL_PATH``, the configuration that applies to the folder ``start``,
    default the current one).  A ``--definitions`` folder that does not exist, or a
    configuration that cannot be used, is printed and gives exit status 2 (returned instead).
    With ``report``, what is wrong with the folders' layouts is printed on standard error
    (:func:`definitions_failed` says whether that is an error)."""
    from nodl.targets.resolve import gather_definitions

    given: list[str] = getattr(args, 'definitions', None) or []
    for folder in given:
        if not os.path.isdir(folder):
            why = 'not a folder' if os.path.exists(folder) else 'no such folder'
            print(f'{prog}: error: --definitions {folder}: {why} [NODL246]', file=sys.stderr)
            return EXIT_USAGE
    try:
        definitions = gather_definitions(given, start=start)
    except ConfigError as exc:
        print(exc, file=sys.stderr)
        return EXIT_USAGE
    if report and definitions.diagnostics:
        show_diagnostics(definitions.diagnostics)
    return definitions


def definitions_failed(definitions: Definitions) -> bool:
    """True when a definitions folder's layout has errors (the verb then exits 1 at least)."""
    return any(d.severity is Severity.ERROR for d in definitions.diagnostics)


def run_with_definitions(args: argparse.Namespace, prog: str, run: Callable[[], int],
                         start: str | None = None) -> int:
    """``run()`` with the definitions folders of :func:`load_definitions` in force (every
    look-up of a registered definition consults them first): its exit status, made 1 at
    least when a folder's layout has errors."""
    from nodl.registry.overlay import using

    definitions = load_definitions(args, prog, start)
    if isinstance(definitions, int):
        return definitions
    with using(definitions):
        status = run()
    return EXIT_FAILURE if status == EXIT_OK and definitions_failed(definitions) else status
