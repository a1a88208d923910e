"""ament_nodl_generate_cpp in a real CMake configure and build of an ament_cmake package.

rclcpp is not installable here: tests/fixtures/generate/cpp_stub_packages/ stands
in for its CMake packages (imported targets whose headers are declarations
only); ament_cmake, the interface packages and their headers are the real ones of
the ROS wheels.  The package is configured and its generated libraries are
compiled with the system's C++ compiler; the CMake file API says which targets
exist, their sources and what they link.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO

VENV = Path(sys.prefix)
GENERATE = FIXTURES / 'generate'
STUB_PACKAGES = GENERATE / 'cpp_stub_packages'

CMAKELISTS = '''cmake_minimum_required(VERSION 3.8)
project(generated_nodes CXX)

find_package(ament_cmake REQUIRED)
find_package(ament_nodl REQUIRED)

ament_nodl_generate_cpp(talker_base nodl/talker.nodl.yaml)
ament_nodl_generate_cpp(camera_base nodl/managed_camera.nodl.yaml NAMESPACE camera CLASS_NAME Camera)
ament_nodl_generate_cpp(everything_base nodl/everything.nodl.yaml COMPONENT)
ament_nodl_generate_cpp(laser_base nodl/laser_driver.nodl.yaml)

ament_package()
'''

PACKAGE_XML = '''<?xml version="1.0"?>
<package format="3">
  <name>generated_nodes</name>
  <version>0.0.0</version>
  <description>Generated bases.</description>
  <maintainer email="maintainer@nodl-toolkit.example.org">NoDL</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <build_depend>ament_nodl</build_depend>
  <export><build_type>ament_cmake</build_type></export>
</package>
'''


def env() -> dict[str, str]:
    out = dict(os.environ)
    out.pop('MAKEFLAGS', None)
    out.update(AMENT_PREFIX_PATH=str(VENV),
               CMAKE_PREFIX_PATH=os.pathsep.join([str(STUB_PACKAGES), str(VENV)]),
               PATH=os.pathsep.join([str(VENV / 'bin'), out.get('PATH', '')]))
    return out


class Project:
    def __init__(self, root: Path) -> None:
        self.source = root / 'src'
        self.build = root / 'build'

    def configure(self) -> subprocess.CompletedProcess[str]:
        query = self.build / '.cmake' / 'api' / 'v1' / 'query' / 'codemodel-v2'
        query.parent.mkdir(parents=True, exist_ok=True)
        query.touch()
        return subprocess.run(['cmake', '-S', str(self.source), '-B', str(self.build),
                               f'-DPython3_EXECUTABLE={sys.executable}'],
                              env=env(), text=True, capture_output=True, timeout=300)

    def build_targets(self, *targets: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(['cmake', '--build', str(self.build), '--target', *targets],
                              env=env(), text=True, capture_output=True, timeout=600)

    def targets(self) -> dict[str, dict]:  # type: ignore[type-arg]
        reply = self.build / '.cmake' / 'api' / 'v1' / 'reply'
        index = json.loads(max(reply.glob('index-*.json')).read_text())
        model = json.loads((reply / index['reply']['codemodel-v2']['jsonFile']).read_text())
        out = {}
        for target in model['configurations'][0]['targets']:
            out[target['name']] = json.loads((reply / target['jsonFile']).read_text())
        return out


@pytest.fixture(scope='module')
def project(tmp_path_factory: pytest.TempPathFactory) -> Project:
    root = tmp_path_factory.mktemp('cmake_generate')
    project = Project(root)
    nodl = project.source / 'nodl'
    nodl.mkdir(parents=True)
    for name in ('talker', 'managed_camera', 'everything'):
        shutil.copy(GENERATE / f'{name}.nodl.yaml', nodl)
    for name in ('laser_driver', 'diagnostics'):  # a node with a relative mixin
        shutil.copy(REPO / 'examples' / f'{name}.nodl.yaml', nodl)
    (project.source / 'CMakeLists.txt').write_text(CMAKELISTS, encoding='utf-8')
    (project.source / 'package.xml').write_text(PACKAGE_XML, encoding='utf-8')
    result = project.configure()
    assert result.returncode == 0, result.stdout + result.stderr
    return project


def test_each_call_creates_a_library_of_the_generated_source(project: Project) -> None:
    targets = project.targets()
    for target, source in (('talker_base', 'talker_base.cpp'), ('camera_base', 'camera_base.cpp'),
                           ('everything_base', 'everything_base.cpp'),
                           ('laser_base', 'laser_driver_base.cpp')):
        assert target in targets, sorted(targets)
        info = targets[target]
        assert info['type'] in ('STATIC_LIBRARY', 'SHARED_LIBRARY')
        sources = [s['path'] for s in info['sources']]
        assert any(p.endswith(f'ament_nodl_generate_cpp/{target}/{source}') for p in sources), sources
        generated = [s for s in info['sources'] if s['path'].endswith(source)]
        assert generated[0].get('isGenerated') is True


def test_the_header_folder_is_a_public_include_directory(project: Project) -> None:
    info = project.targets()['talker_base']
    includes = [i['path'] for group in info['compileGroups'] for i in group['includes']]
    assert any(p.endswith('ament_nodl_generate_cpp/talker_base') for p in includes), includes


def test_the_libraries_link_what_the_generated_code_needs(project: Project) -> None:
    targets = project.targets()
    stubs = str((GENERATE / 'cpp_stubs').resolve())
    for target, packages in (
            ('talker_base', ['std_msgs']),
            ('camera_base', ['std_msgs', 'std_srvs']),
            ('everything_base', ['std_msgs', 'std_srvs', 'test_msgs']),
            ('laser_base', ['sensor_msgs', 'std_msgs', 'std_srvs'])):
        includes = [i['path'] for group in targets[target]['compileGroups']
                    for i in group['includes']]
        assert stubs in includes  # rclcpp (the stand-in's headers) through rclcpp::rclcpp
        for package in packages:  # the interface packages' C++ headers
            assert any(p.rstrip('/').endswith(f'include/{package}') for p in includes), \
                (target, package, includes)
        assert not any('python3' in p for p in includes)  # no other language's targets
    for target, expected in (
            ('talker_base', ['rcl_interfaces', 'rclcpp', 'std_msgs']),
            ('camera_base', ['rcl_interfaces', 'rclcpp', 'rclcpp_lifecycle', 'std_msgs', 'std_srvs']),
            ('everything_base', ['rcl_interfaces', 'rclcpp', 'rclcpp_action', 'rclcpp_components',
                                 'std_msgs', 'std_srvs', 'test_msgs'])):
        header = next((project.build / 'ament_nodl_generate_cpp' / target).glob('*.hpp'))
        line = next(text for text in header.read_text().splitlines()
                    if text.startswith('// nodl-dependencies:'))
        assert line.split(':', 1)[1].split() == expected


def test_the_generated_libraries_compile(project: Project) -> None:
    result = project.build_targets('talker_base', 'camera_base', 'everything_base', 'laser_base')
    assert result.returncode == 0, result.stdout + result.stderr


def test_a_changed_definition_or_mixin_regenerates(project: Project) -> None:
    first = project.build_targets('laser_base')
    assert first.returncode == 0, first.stdout + first.stderr
    again = project.build_targets('laser_base')
    assert 'Generating cpp' not in again.stdout  # nothing changed: nothing regenerated
    mixin = project.source / 'nodl' / 'diagnostics.nodl.yaml'
    os.utime(mixin, None)
    header = project.build / 'ament_nodl_generate_cpp' / 'laser_base' / 'laser_driver_base.hpp'
    before = header.stat().st_mtime_ns
    after_mixin = project.build_targets('laser_base')
    assert after_mixin.returncode == 0, after_mixin.stdout + after_mixin.stderr
    assert 'Generating cpp from NoDL definition nodl/laser_driver.nodl.yaml' in after_mixin.stdout
    assert header.stat().st_mtime_ns >= before
    definition = project.source / 'nodl' / 'talker.nodl.yaml'
    text = definition.read_text(encoding='utf-8')
    definition.write_text(text.replace('    - name: ~/chatter', '    - name: ~/chatter_renamed', 1)
                          if '~/chatter' in text else text + '\n', encoding='utf-8')
    result = project.build_targets('talker_base')
    assert result.returncode == 0, result.stdout + result.stderr
    talker = (project.build / 'ament_nodl_generate_cpp' / 'talker_base' / 'talker_base.hpp')
    if '~/chatter' in text:
        assert 'chatter_renamed' in talker.read_text(encoding='utf-8')


def test_a_broken_definition_fails_the_configure_with_its_diagnostics(tmp_path: Path) -> None:
    project = Project(tmp_path)
    (project.source / 'nodl').mkdir(parents=True)
    (project.source / 'nodl' / 'bad.nodl.yaml').write_text(
        'nodl_version: 2\nbase: node\nmain:\n  nodl_version: 2\n  publishers:\n'
        '    - {name: x, type: std_msgs/msg/String}\n', encoding='utf-8')
    (project.source / 'CMakeLists.txt').write_text(
        CMAKELISTS.split('ament_nodl_generate_cpp(talker_base')[0]
        + 'ament_nodl_generate_cpp(bad_base nodl/bad.nodl.yaml)\nament_package()\n', encoding='utf-8')
    (project.source / 'package.xml').write_text(PACKAGE_XML, encoding='utf-8')
    result = project.configure()
    assert result.returncode != 0
    assert 'ament_nodl_generate_cpp(bad_base)' in result.stderr
    assert 'bad.nodl.yaml:6:' in result.stderr, result.stderr


def test_ament_nodl_generate_python_installs_the_module(tmp_path: Path) -> None:
    project = Project(tmp_path)
    (project.source / 'nodl').mkdir(parents=True)
    shutil.copy(GENERATE / 'talker.nodl.yaml', project.source / 'nodl')
    (project.source / 'CMakeLists.txt').write_text(
        'cmake_minimum_required(VERSION 3.8)\nproject(generated_nodes NONE)\n'
        'find_package(ament_cmake REQUIRED)\nfind_package(ament_cmake_python REQUIRED)\n'
        'find_package(ament_nodl REQUIRED)\n'
        'ament_nodl_generate_python(nodl/talker.nodl.yaml)\nament_package()\n', encoding='utf-8')
    (project.source / 'package.xml').write_text(PACKAGE_XML, encoding='utf-8')
    assert project.configure().returncode == 0
    prefix = tmp_path / 'install'
    built = subprocess.run(['cmake', '--build', str(project.build)], env=env(), text=True,
                           capture_output=True, timeout=300)
    assert built.returncode == 0, built.stdout + built.stderr
    installed = subprocess.run(['cmake', '--install', str(project.build), '--prefix', str(prefix)],
                               env=env(), text=True, capture_output=True, timeout=300)
    assert installed.returncode == 0, installed.stdout + installed.stderr
    modules = list(prefix.glob('lib/python3*/site-packages/generated_nodes/*.py'))
    assert modules, list(prefix.rglob('*'))
    generated = subprocess.run(
        [str(VENV / 'bin' / 'nodl'), 'generate', str(GENERATE / 'talker.nodl.yaml'),
         '--language', 'python', '-o', str(tmp_path / 'direct')], env=env(), text=True,
        capture_output=True, timeout=120)
    assert generated.returncode == 0, generated.stderr
    for module in modules:
        assert module.read_bytes() == (tmp_path / 'direct' / module.name).read_bytes()
