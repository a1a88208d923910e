"""``nodl new``: a complete ROS 2 package from node definitions (like ``ros2 pkg create``, and more).

:func:`plan_package` turns definitions into the files of a package, each
marked *generated* (rewritten by ``--update``: the definitions under
``nodl/`` and the generated bases) or *user* (written once, never
overwritten unless ``force``: the node's implementation, ``package.xml``,
the build files, parameter files, launch file, tests and README).
:func:`write_package` writes a plan.  Nothing here prints or exits;
problems raise :class:`ScaffoldError` with a message for the user.

Build types:

* ``ament_python``: ``setup.py``/``setup.cfg``, the package's module with
  ``<exe>_base.py`` (generated, committed; the package's test
  ``test/test_generated.py`` fails when it is stale, through ``nodl generate
  --check``) and ``<exe>.py`` (the user's subclass with ``main``); the
  definitions are installed and registered by ``nodl_data_files``.
* ``ament_cmake``: ``CMakeLists.txt`` generates each base at build time
  (``ament_nodl_generate_cpp``), builds ``src/<exe>.cpp`` (the user's
  subclass with ``main``) and registers the definitions
  (``ament_nodl_register_node``); with ``component``, each node is a
  component library registered with ``RCLCPP_COMPONENTS_REGISTER_NODE``
  and run alone by the executable ``rclcpp_components_register_node`` makes.
"""

from __future__ import annotations

import os
import re
from collections.abc import Sequence

from nodl.files import describe_os_error
from nodl.generate import GenerationError, default_node_name
from nodl.packaging import relative_mixins
from nodl.plan.identifiers import CPP_KEYWORDS, PYTHON_KEYWORDS
from nodl.reporting import without_info
from nodl.scaffold.cmake_package import cmake_files
from nodl.scaffold.common import common_files
from nodl.scaffold.model import (
    Authorship,
    NodeSource,
    PackagePlan,
    PlannedFile,
    ScaffoldError,
    WriteReport,
    authorship,
)
from nodl.scaffold.python_package import python_files
from nodl.targets import resolve_target
from nodl.writing import (
    WriteError,
    check_replaceable,
    check_within,
    holds_text,
    marked_text,
    output_is_input,
    write_file,
)

__all__ = ['BUILD_TYPES', 'ScaffoldError', 'NodeSource', 'PlannedFile', 'PackagePlan', 'Authorship',
           'executable_name', 'load_nodes', 'plan_package', 'write_package', 'WriteReport',
           'authorship', 'check_package_name']

#: ``--build-type`` -> the client library of its nodes.
BUILD_TYPES: dict[str, str] = {'ament_python': 'rclpy', 'ament_cmake': 'rclcpp'}

_PACKAGE_NAME = re.compile(r'[a-z][a-z0-9_]*')
_EXECUTABLE = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')


def executable_name(path: str) -> str:
    """The executable named after a definition file (``talker.nodl.yaml`` -> ``talker``)."""
    return default_node_name(path)


def load_nodes(sources: Sequence[Sequence[str]], build_type: str) -> list[NodeSource]:
    """Resolve each definition (``[FILE]`` or ``[PACKAGE, EXECUTABLE]``) for the build type's library.

    Raises :class:`ScaffoldError` with the diagnostics of a definition that is
    invalid, and for two nodes that would get the same executable.
    """
    if build_type not in BUILD_TYPES:
        raise ScaffoldError(f'unknown build type {build_type!r}; expected one of: '
                            f'{", ".join(BUILD_TYPES)}')
    nodes: list[NodeSource] = []
    for source in sources:
        try:
            node, diagnostics, file, _ = resolve_target(list(source), client_library=BUILD_TYPES[build_type])
        except (OSError, ValueError) as exc:
            if isinstance(exc, OSError):  # in words, the path once, no '[Errno N]'
                words, name = describe_os_error(exc), exc.filename or source[0]
                raise ScaffoldError(words if words.startswith(f'{name}:') else
                                    f'{name}: {words}') from None
            raise ScaffoldError(str(exc)) from None
        if node is None:
            raise ScaffoldError(f'{" ".join(source)}: the definition is invalid',
                                without_info(diagnostics))
        executable = source[1] if len(source) == 2 else executable_name(file)
        if not _EXECUTABLE.fullmatch(executable):
            raise ScaffoldError(f'{executable!r} is not a usable executable name (letters, digits '
                                'and _, not starting with a digit); rename the definition file')
        if any(n.executable == executable for n in nodes):
            raise ScaffoldError(f'two definitions would both be the executable {executable!r}; '
                                'rename one of the files')
        nodes.append(NodeSource(executable, file, node, relative_mixins(file)))
    if not nodes:
        raise ScaffoldError('give at least one node definition (--from FILE)')
    return nodes


def check_package_name(package: str) -> None:
    """Raise :class:`ScaffoldError` for a name that cannot be a ROS package of Python or C++ code.

    REP 144's rules (lowercase letters, digits and single ``_``, starting with a
    letter, two characters at least), and not a Python or C++ keyword: the name is
    the package's Python module and its C++ namespace.
    """
    if not _PACKAGE_NAME.fullmatch(package) or len(package) < 2 or '__' in package:
        raise ScaffoldError(f'{package!r} is not a valid ROS package name: lowercase letters, '
                            'digits and single _, starting with a letter, at least 2 characters')
    keyword = [language for language, words in (('Python', PYTHON_KEYWORDS), ('C++', CPP_KEYWORDS))
               if package in words]
    if keyword:
        raise ScaffoldError(f'{package!r} is a {" and a ".join(keyword)} keyword: the package name '
                            f'is its Python module and C++ namespace; choose another '
                            f'(e.g. {package}_nodes)')


def plan_package(package: str, nodes: Sequence[NodeSource], build_type: str, *,
                 component: bool = False, author: Authorship | None = None) -> PackagePlan:
    """Every file of the package ``package`` holding ``nodes`` (see the module docstring).

    ``component`` (ament_cmake only): every node is an rclcpp component.
    ``author``: the maintainer and license (package.xml, setup.py, copyright headers).
    """
    if component and build_type != 'ament_cmake':
        raise ScaffoldError('--component needs --build-type ament_cmake (rclcpp components)')
    check_package_name(package)
    author = author or Authorship()
    if build_type not in BUILD_TYPES:
        raise ScaffoldError(f'unknown build type {build_type!r}; expected one of: '
                            f'{", ".join(BUILD_TYPES)}')
    try:
        files = common_files(package, list(nodes), build_type, component, author)
        if build_type == 'ament_python':
            files += python_files(package, list(nodes), author)
        else:
            files += cmake_files(package, list(nodes), component, author)
    except GenerationError as exc:
        raise ScaffoldError(str(exc)) from None
    files.sort(key=lambda f: f.path)
    return PackagePlan(package, build_type, list(nodes), files)


def write_package(plan: PackagePlan, out_dir: str, *, update: bool = False,
                  force: bool = False) -> WriteReport:
    """Write ``plan`` into ``out_dir/<package>``.

    A new package needs a folder that does not exist yet.  ``update``:
    rewrite the generated files and add missing user files, keeping every
    user file that exists.  ``force``: replace user files too.  Raises
    :class:`ScaffoldError` for a folder that exists without either.

    Files are written atomically (:mod:`nodl.writing`); generated
    files carry a content marker, and ``update`` refuses to replace one that
    was edited since (or has no marker) unless ``force``: a
    :class:`~nodl.writing.WriteError` (NODL031/NODL032), raised
    before anything is written, as are a file that is one of the definitions (or
    mixins) read (NODL033, even with ``force``) and a folder under ``out_dir`` that is a
    symbolic link leading outside it (NODL708); NODL030 when a write fails.
    """
    root = os.path.join(out_dir, plan.package)
    if os.path.exists(root) and not (update or force):
        raise ScaffoldError(f'{root} exists; use --update to regenerate its generated files and add '
                            'missing ones, or --force to replace every file')
    report = WriteReport()
    pending: list[tuple[str, str, PlannedFile]] = []
    inputs = [f for node in plan.nodes for f in [node.definition, *node.node.files]]
    for item in plan.files:
        path = os.path.join(root, item.path)
        shown = os.path.join(plan.package, item.path)
        outside = check_within(path, out_dir) or output_is_input(path, inputs)
        if outside is not None:
            raise WriteError(outside)
        exists = os.path.lexists(path)
        if exists and not item.generated and not force:
            report.kept.append(shown)
            continue
        text = marked_text(path, item.text) if item.generated else item.text
        if exists and holds_text(path, text):
            report.unchanged.append(shown)
            continue
        refusal = check_replaceable(path, text, force=force)
        if refusal is not None:
            raise WriteError(refusal)
        pending.append((path, text, item))
    for path, text, item in pending:
        write_file(path, text, mode=0o755 if item.executable else None, make_parents=True,
                   within=out_dir)
        report.written.append(os.path.join(plan.package, item.path))
    return report
