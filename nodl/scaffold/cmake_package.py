"""The files of an ament_cmake package: CMakeLists.txt and a C++ node per definition.

The bases are generated at build time by ``ament_nodl_generate_cpp`` (so they
are never stale and never committed); ``src/<exe>.cpp`` is the user's
subclass, written once, with a placeholder for every callback and ``main``.
"""

from __future__ import annotations

from nodl.generate import GenerateOptions, default_class_name
from nodl.generate.cpp import plan_cpp
from nodl.generate.cpp.user import render_user_source
from nodl.scaffold.common import definition_path
from nodl.scaffold.model import Authorship, NodeSource, PlannedFile
from nodl.text_safety import UNSAFE, describe_character

__all__ = ['cmake_files', 'cpp_options']


def cpp_options(package: str, node: NodeSource, component: bool = False) -> GenerateOptions:
    """How a node's base is generated: class from the executable, the package as namespace."""
    return GenerateOptions(default_class_name(node.executable), node.executable, namespace=package,
                           component=component)


def _cmake_string(text: str) -> str:
    """``text`` as a CMake quoted argument: backslash, quote and ``$`` (a variable reference)
    escaped, tab and line breaks as CMake's escapes; ValueError for another control or a bidi
    character (CMake has no escape for them, and no name the scaffold writes may hold one)."""
    quoted = text.replace('\\', '\\\\').replace('"', '\\"').replace('$', '\\$')
    quoted = quoted.replace('\t', '\\t').replace('\n', '\\n').replace('\r', '\\r')
    found = UNSAFE.search(quoted)
    if found is not None:
        raise ValueError(f'{text!r} cannot be written in CMakeLists.txt: it holds '
                         f'{describe_character(found.group(0))}')
    return '"' + quoted + '"'


def _cmakelists(package: str, nodes: list[NodeSource], component: bool, licensed: bool) -> str:
    lines = ['cmake_minimum_required(VERSION 3.8)', f'project({package})', '',
             'if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")',
             '  add_compile_options(-Wall -Wextra -Wpedantic)', 'endif()', '',
             'find_package(ament_cmake REQUIRED)', 'find_package(ament_nodl REQUIRED)']
    if component:
        lines.append('find_package(rclcpp_components REQUIRED)')
    lines.append('')
    for node in nodes:
        options = cpp_options(package, node, component)
        exe, definition = node.executable, _cmake_string(definition_path(node))
        lines += [f'# {exe}: the base generated from its definition, and your subclass',
                  f'ament_nodl_generate_cpp({exe}_base {definition}',
                  f'  CLASS_NAME {options.class_name} NODE_NAME {options.node_name} '
                  f'NAMESPACE {options.namespace}{" COMPONENT" if component else ""})']
        if component:
            lines += [f'# a component library (load it into a container), and the executable {exe} '
                      'that runs it alone',
                      f'add_library({exe}_component SHARED src/{exe}.cpp)',
                      f'target_link_libraries({exe}_component {exe}_base)',
                      f'rclcpp_components_register_node({exe}_component',
                      f'  PLUGIN "{options.namespace}::{options.class_name}" EXECUTABLE {exe})']
        else:
            lines += [f'add_executable({exe} src/{exe}.cpp)',
                      f'target_link_libraries({exe} {exe}_base)']
        lines += [f'ament_nodl_register_node({exe} FILE {definition})', '']
    if component:
        libraries = ' '.join(f'{n.executable}_component' for n in nodes)
        lines += ['# rclcpp_components_register_node installs the executables',
                  f'install(TARGETS {libraries}',
                  '  ARCHIVE DESTINATION lib LIBRARY DESTINATION lib RUNTIME DESTINATION bin)']
    else:
        targets = ' '.join(n.executable for n in nodes)
        lines.append(f'install(TARGETS {targets} DESTINATION lib/${{PROJECT_NAME}})')
    lines += ['install(DIRECTORY config launch DESTINATION share/${PROJECT_NAME})', '',
              'if(BUILD_TESTING)',
              '  find_package(ament_lint_auto REQUIRED)',
              *(['  # Remove this once the files pass cpplint',
                 '  set(ament_cmake_cpplint_FOUND TRUE)'] if licensed else
                ['  # Remove these two once the files carry a license and copyright notice',
                 '  # (nodl new --license SPDX --maintainer NAME EMAIL writes them)',
                 '  set(ament_cmake_copyright_FOUND TRUE)',
                 '  set(ament_cmake_cpplint_FOUND TRUE)']),
              '  ament_lint_auto_find_test_dependencies()',
              '  find_package(ament_cmake_pytest REQUIRED)',
              '  ament_add_pytest_test(conformance test/test_conformance.py TIMEOUT 120)',
              'endif()', '', 'ament_package()']
    return '\n'.join(lines) + '\n'


def cmake_files(package: str, nodes: list[NodeSource], component: bool = False,
                author: Authorship = Authorship()) -> list[PlannedFile]:
    """CMakeLists.txt and ``src/<exe>.cpp`` per node (``component``: each node an rclcpp component
    registered with ``RCLCPP_COMPONENTS_REGISTER_NODE``, and an executable that runs it alone)."""
    files = [PlannedFile('CMakeLists.txt',
                         _cmakelists(package, nodes, component, author.license is not None), False)]
    for node in nodes:
        options = cpp_options(package, node, component)
        plan = plan_cpp(node.node, options)
        files.append(PlannedFile(f'src/{node.executable}.cpp',
                                 author.header('//') + render_user_source(plan, options.class_name),
                                 False))
    return files
