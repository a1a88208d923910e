"""The scaffold library: which files a package gets, their kinds, dependencies, escaping, and
the ament_cmake variant in a real CMake configure and g++ compile (rclcpp stand-ins).

Golden files of the ament_cmake package are under tests/fixtures/scaffold/cmake/
(``pytest --update-golden`` rewrites them).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl_schema.scaffold import ScaffoldError, load_nodes, plan_package, write_package

GENERATE = FIXTURES / 'generate'
GOLDEN = FIXTURES / 'scaffold' / 'cmake'
VENV = Path(sys.prefix)
SOURCES = [[str(GENERATE / f'{n}.nodl.yaml')] for n in ('talker', 'managed_camera', 'everything')]


def plan(build_type: str, package: str = 'demo_nodes'):  # type: ignore[no-untyped-def]
    return plan_package(package, load_nodes(SOURCES, build_type), build_type)


def test_python_package_files_and_kinds() -> None:
    files = {f.path: f for f in plan('ament_python').files}
    generated = sorted(p for p, f in files.items() if f.generated)
    assert generated == ['demo_nodes/everything_base.py', 'demo_nodes/managed_camera_base.py',
                         'demo_nodes/talker_base.py', 'nodl/everything.nodl.yaml',
                         'nodl/managed_camera.nodl.yaml', 'nodl/talker.nodl.yaml']
    for path in ('setup.py', 'setup.cfg', 'package.xml', 'README.md', 'resource/demo_nodes',
                 'demo_nodes/__init__.py', 'demo_nodes/talker.py', 'config/talker.params.yaml',
                 'launch/demo_nodes.launch.xml', 'test/test_conformance.py',
                 'test/test_generated.py', 'test/test_flake8.py', 'test/test_pep257.py',
                 'test/test_copyright.py'):
        assert path in files and not files[path].generated, path


def test_cmake_package_files_and_kinds() -> None:
    files = {f.path: f for f in plan('ament_cmake').files}
    assert sorted(p for p, f in files.items() if f.generated) == [
        'nodl/everything.nodl.yaml', 'nodl/managed_camera.nodl.yaml', 'nodl/talker.nodl.yaml']
    for path in ('CMakeLists.txt', 'package.xml', 'src/talker.cpp', 'src/everything.cpp',
                 'src/managed_camera.cpp', 'test/test_conformance.py'):
        assert path in files
    assert 'setup.py' not in files


@pytest.mark.parametrize('path', ['CMakeLists.txt', 'package.xml', 'README.md',
                                  'src/talker.cpp', 'src/managed_camera.cpp', 'src/everything.cpp',
                                  'launch/demo_nodes.launch.xml', 'test/test_conformance.py'])
def test_cmake_package_golden(path: str, golden) -> None:  # type: ignore[no-untyped-def]
    files = {f.path: f.text for f in plan('ament_cmake').files}
    golden.check(files[path], GOLDEN / path)


@pytest.mark.parametrize('build_type, expected', [
    ('ament_python', {'exec_depend': ['lifecycle_msgs', 'rcl_interfaces', 'rclpy', 'std_msgs',
                                      'std_srvs', 'test_msgs']}),
    ('ament_cmake', {'build_depend': ['rcl_interfaces', 'rclcpp', 'rclcpp_action', 'rclcpp_lifecycle',
                                'std_msgs', 'std_srvs', 'test_msgs']}),
])
def test_package_xml_is_valid_and_derives_the_dependencies(build_type: str,
                                                           expected: dict[str, list[str]],
                                                           tmp_path: Path) -> None:
    from catkin_pkg.package import parse_package_string

    text = next(f.text for f in plan(build_type).files if f.path == 'package.xml')
    package = parse_package_string(text)
    package.validate()
    assert package.get_build_type() == build_type
    for kind, names in expected.items():
        assert sorted(d.name for d in getattr(package, f'{kind}s')) == names
    assert 'ament_nodl' in [d.name for d in package.buildtool_depends]
    assert 'nodl_toolkit' in [d.name for d in package.test_depends]


def test_names_and_descriptions_are_escaped_in_readme_and_xml(tmp_path: Path) -> None:
    definition = tmp_path / 'odd.nodl.yaml'
    definition.write_text('''nodl_version: 2
base: node
main:
  nodl_version: 2
  description: "A </description> <b>bold</b> | pipe & *star* `tick`"
  parameters:
    "x_y": {type: int, default_value: 1, description: "a | b\\n# not a heading"}
  publishers:
    - name: ~/out
      type: std_msgs/msg/String
      description: "[link](javascript:alert(1)) <script>"
      qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}
''', encoding='utf-8')
    result = plan_package('odd_pkg', load_nodes([[str(definition)]], 'ament_python'),
                          'ament_python')
    files = {f.path: f.text for f in result.files}
    from catkin_pkg.package import parse_package_string

    parsed = parse_package_string(files['package.xml'])  # still well-formed XML
    assert parsed.name == 'odd_pkg'
    assert parsed.description.startswith('A &lt;/description&gt; &lt;b&gt;bold')
    readme = files['README.md']
    assert '<script>' not in readme and '<b>' not in readme
    assert '\\[link\\](javascript:alert(1)) \\<script\\>' in readme
    table = [l for l in readme.splitlines() if 'x_y' in l and 'parameter' in l]
    assert table and all(l.count(' | ') == 3 for l in table), table
    assert '\n# not a heading' not in readme


def test_write_refuses_an_existing_folder_and_update_keeps_user_files(tmp_path: Path) -> None:
    result = plan('ament_python')
    write_package(result, str(tmp_path))
    with pytest.raises(ScaffoldError, match='--update'):
        write_package(result, str(tmp_path))
    user = tmp_path / 'demo_nodes' / 'demo_nodes' / 'talker.py'
    base = tmp_path / 'demo_nodes' / 'demo_nodes' / 'talker_base.py'
    user.write_text('mine\n', encoding='utf-8')
    base.write_text('stale\n', encoding='utf-8')
    report = write_package(result, str(tmp_path), update=True)
    assert user.read_text(encoding='utf-8') == 'mine\n'
    assert base.read_text(encoding='utf-8') != 'stale\n'
    assert 'demo_nodes/demo_nodes/talker.py' in report.kept
    assert report.written == ['demo_nodes/demo_nodes/talker_base.py']
    # regenerating again writes nothing: the output is byte-identical
    assert write_package(plan('ament_python'), str(tmp_path), update=True).written == []


@pytest.mark.parametrize('package', ['Demo', '1pkg', 'my-pkg', ''])
def test_invalid_package_names(package: str) -> None:
    with pytest.raises(ScaffoldError, match='not a valid ROS package name'):
        plan('ament_python', package)


def test_a_registered_definition_names_its_executable(tmp_path: Path) -> None:
    """PACKAGE EXECUTABLE: the executable keeps the registered name."""
    prefix = tmp_path / 'prefix'
    index = prefix / 'share' / 'ament_index' / 'resource_index'
    (index / 'packages').mkdir(parents=True)
    (index / 'packages' / 'other').write_text('', encoding='utf-8')
    (index / 'nodl_nodes').mkdir()
    (index / 'nodl_nodes' / 'other__my_talker').write_text('nodl/talker.nodl.yaml',
                                                            encoding='utf-8')
    (prefix / 'share' / 'other' / 'nodl').mkdir(parents=True)
    shutil.copy(GENERATE / 'talker.nodl.yaml', prefix / 'share' / 'other' / 'nodl')
    old = os.environ.get('AMENT_PREFIX_PATH', '')
    os.environ['AMENT_PREFIX_PATH'] = os.pathsep.join([str(prefix), old])
    try:
        nodes = load_nodes([['other', 'my_talker']], 'ament_python')
    finally:
        os.environ['AMENT_PREFIX_PATH'] = old
    assert [n.executable for n in nodes] == ['my_talker']
    files = {f.path for f in plan_package('pkg', nodes, 'ament_python').files}
    assert {'pkg/my_talker.py', 'pkg/my_talker_base.py', 'nodl/talker.nodl.yaml'} <= files


def test_the_cmake_package_configures_and_compiles(tmp_path: Path) -> None:
    """A real CMake configure of the ament_cmake package (rclcpp from the stand-ins) and a
    compile of every generated base and every user source with the system's compiler."""
    write_package(plan('ament_cmake'), str(tmp_path / 'src'))
    source, build = tmp_path / 'src' / 'demo_nodes', tmp_path / 'build'
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)
    env.update(AMENT_PREFIX_PATH=str(VENV),
               CMAKE_PREFIX_PATH=os.pathsep.join([str(GENERATE / 'cpp_stub_packages'), str(VENV)]),
               PATH=os.pathsep.join([str(VENV / 'bin'), env.get('PATH', '')]))
    configure = subprocess.run(['cmake', '-S', str(source), '-B', str(build), '-G', 'Unix Makefiles',
                                '-DBUILD_TESTING=OFF', f'-DPython3_EXECUTABLE={sys.executable}'],
                               env=env, text=True, capture_output=True, timeout=300)
    assert configure.returncode == 0, configure.stdout + configure.stderr
    targets = ['talker_base', 'managed_camera_base', 'everything_base',
               'src/talker.cpp.o', 'src/managed_camera.cpp.o', 'src/everything.cpp.o']
    compiled = subprocess.run(['make', '-C', str(build), *targets], env=env, text=True,
                              capture_output=True, timeout=600)
    assert compiled.returncode == 0, compiled.stdout + compiled.stderr
    assert 'warning' not in compiled.stderr, compiled.stderr


def test_component_packages_register_each_node_and_compile(tmp_path: Path) -> None:
    """``nodl new --component``: each node a library whose class registers itself as a component,
    run alone by the executable rclcpp_components_register_node makes (real configure, stand-ins)."""
    with pytest.raises(ScaffoldError, match='--component needs --build-type ament_cmake'):
        plan_package('demo_nodes', load_nodes(SOURCES, 'ament_python'), 'ament_python', component=True)
    result = plan_package('demo_nodes', load_nodes(SOURCES[:2], 'ament_cmake'), 'ament_cmake',
                          component=True)
    files = {f.path: f.text for f in result.files}
    assert '<depend>rclcpp_components</depend>' in files['package.xml']
    assert 'rclcpp_components' not in {f.path: f.text for f in plan('ament_cmake').files}['package.xml']
    for exe, cls in (('talker', 'Talker'), ('managed_camera', 'ManagedCamera')):
        assert files[f'src/{exe}.cpp'].endswith(f'RCLCPP_COMPONENTS_REGISTER_NODE(demo_nodes::{cls})\n')
        assert 'int main(' not in files[f'src/{exe}.cpp']
    write_package(result, str(tmp_path / 'src'))
    source, build = tmp_path / 'src' / 'demo_nodes', tmp_path / 'build'
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)
    env.update(AMENT_PREFIX_PATH=str(VENV),
               CMAKE_PREFIX_PATH=os.pathsep.join([str(GENERATE / 'cpp_stub_packages'), str(VENV)]),
               PATH=os.pathsep.join([str(VENV / 'bin'), env.get('PATH', '')]))
    configure = subprocess.run(['cmake', '-S', str(source), '-B', str(build), '-G', 'Unix Makefiles',
                                '-DBUILD_TESTING=OFF', f'-DPython3_EXECUTABLE={sys.executable}'],
                               env=env, text=True, capture_output=True, timeout=300)
    assert configure.returncode == 0, configure.stdout + configure.stderr
    assert (build / 'rclcpp_components_registered.txt').read_text().splitlines() == [
        'demo_nodes::Talker talker_component talker',
        'demo_nodes::ManagedCamera managed_camera_component managed_camera']
    compiled = subprocess.run(['make', '-C', str(build), 'src/talker.cpp.o', 'src/managed_camera.cpp.o'],
                              env=env, text=True, capture_output=True, timeout=600)
    assert compiled.returncode == 0, compiled.stdout + compiled.stderr
    assert 'warning' not in compiled.stderr, compiled.stderr


def test_python_package_files_keep_ament_flake8s_line_length(tmp_path: Path) -> None:
    """The lint test the package carries (ament_flake8: 99 columns) passes on every file
    `nodl new` writes, generated bases included (checked with ruff's pycodestyle rules)."""
    write_package(plan('ament_python'), str(tmp_path))
    ruff = shutil.which('ruff', path=str(VENV / 'bin')) or shutil.which('ruff')
    assert ruff, 'ruff is part of the test extra'
    lint = subprocess.run([ruff, 'check', '--isolated', '--no-cache', '--select', 'E,W,F',
                           '--line-length', '99', str(tmp_path / 'demo_nodes')],
                          capture_output=True, text=True, timeout=120)
    assert lint.returncode == 0, lint.stdout + lint.stderr
