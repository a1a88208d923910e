"""nodl.extract.cmake: which executables a package builds from which sources."""

from __future__ import annotations

import os
from pathlib import Path

from nodl.extract.cmake import MAX_DEPTH, read_cmake, read_cmake_text

CMAKE = Path(__file__).parent / 'fixtures' / 'extract' / 'cmake'


def _rel(targets, paths):
    return [os.path.relpath(p, os.path.dirname(targets.file)) for p in paths]


def test_real_demo_nodes_cpp_functions_and_components() -> None:
    targets = read_cmake(str(CMAKE / 'demo_nodes_cpp' / 'CMakeLists.txt'))
    assert targets.package == 'demo_nodes_cpp' and not targets.diagnostics
    # custom_executable(services add_two_ints_client ...): a function with cmake_parse_arguments
    assert _rel(targets, targets.executables['add_two_ints_client']) == ['src/services/add_two_ints_client.cpp']
    # set(allocator_file ...) in both branches of an if: either source builds allocator_tutorial
    assert _rel(targets, targets.executables['allocator_tutorial']) == [
        'src/topics/allocator_tutorial_custom.cpp', 'src/topics/allocator_tutorial_pmr.cpp']
    # create_demo_library(...) -> rclcpp_components_register_node(PLUGIN ... EXECUTABLE ...)
    assert targets.executable_of_plugin('demo_nodes_cpp::Talker') == 'talker'
    assert targets.library_of_plugin('demo_nodes_cpp::Talker') == 'talker_library'


def test_real_composition_components_without_executables() -> None:
    targets = read_cmake(str(CMAKE / 'composition' / 'CMakeLists.txt'))
    assert targets.plugins['composition::Talker'] == ('talker_component', None)
    assert targets.executable_of_plugin('composition::Talker') is None
    assert set(targets.executables) == {'manual_composition', 'linktime_composition', 'dlopen_composition'}


def test_real_teleop_output_name() -> None:
    targets = read_cmake(str(CMAKE / 'teleop_twist_joy' / 'CMakeLists.txt'))
    source = str(CMAKE / 'teleop_twist_joy' / 'src' / 'teleop_node.cpp')
    assert targets.executable_of_sources([source]) == 'teleop_node'


def test_foreach_macro_and_list(tmp_path: Path) -> None:
    text = '''
project(pkg)
set(NODES a b)
list(APPEND NODES c)
macro(node name)
  add_executable(${name}_node src/${name}.cpp)
endmacro()
foreach(n IN LISTS NODES)
  node(${n})
endforeach()
add_library(lib SHARED src/lib.cpp)
target_sources(lib PRIVATE src/more.cpp)
rclcpp_components_register_nodes(lib "pkg::A" "pkg::B")
'''
    targets = read_cmake_text(text, str(tmp_path / 'CMakeLists.txt'))
    assert sorted(targets.executables) == ['a_node', 'b_node', 'c_node']
    assert _rel(targets, targets.libraries['lib']) == ['src/lib.cpp', 'src/more.cpp']
    assert targets.library_of_plugin('pkg::B') == 'lib'


def test_unknowns_and_syntax_are_located(tmp_path: Path) -> None:
    text = 'project(p)\nadd_executable(x ${NOT_SET}/a.cpp)\nwhile(TRUE)\nendwhile()\nadd_executable(y "src/y.cpp"\n'
    targets = read_cmake_text(text, str(tmp_path / 'CMakeLists.txt'))
    got = [(d.code, d.line) for d in targets.diagnostics]
    assert got == [('NODL945', 5), ('NODL946', 2), ('NODL946', 3)]
    assert targets.executables == {'x': []}


def test_runaway_recursion_is_bounded(tmp_path: Path) -> None:
    text = 'function(f)\n  f()\nendfunction()\nf()\n'
    targets = read_cmake_text(text, str(tmp_path / 'CMakeLists.txt'))
    (diagnostic,) = targets.diagnostics
    assert diagnostic.code == 'NODL946' and str(MAX_DEPTH) in diagnostic.message


def test_unreadable_file_is_one_error(tmp_path: Path) -> None:
    targets = read_cmake(str(tmp_path / 'CMakeLists.txt'))
    (diagnostic,) = targets.diagnostics
    assert diagnostic.code == 'NODL931' and 'Errno' not in diagnostic.message


def test_install_programs_into_lib_package_are_executables(tmp_path: Path) -> None:
    text = ('project(mixed_pkg)\nset(SCRIPTS scripts/a.py scripts/b)\n'
            'install(PROGRAMS ${SCRIPTS} DESTINATION lib/${PROJECT_NAME})\n'
            'install(PROGRAMS scripts/c.py DESTINATION lib/${PROJECT_NAME}/ RENAME c_node)\n'
            'install(PROGRAMS scripts/tool.py DESTINATION bin)\n'
            'install(PROGRAMS ${UNKNOWN}/d.py DESTINATION lib/${PROJECT_NAME})\n'
            'install(TARGETS x DESTINATION lib/${PROJECT_NAME})\n')
    targets = read_cmake_text(text, str(tmp_path / 'CMakeLists.txt'))
    assert {k: os.path.relpath(v, tmp_path) for k, v in targets.programs.items()} == {
        'a.py': 'scripts/a.py', 'b': 'scripts/b', 'c_node': 'scripts/c.py'}
    assert [(d.code, d.line) for d in targets.diagnostics] == [('NODL946', 6)]
