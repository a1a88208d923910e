"""ament_nodl: registration from CMake packages, with a real colcon build.

One colcon build (module scope) of the example workspace plus two broken
packages; every test inspects its outcome.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO

VENV = Path(sys.prefix)
INDEX = Path('share') / 'ament_index' / 'resource_index'


class Build:
    def __init__(self, root: Path, result: subprocess.CompletedProcess[str]) -> None:
        self.root = root
        self.result = result
        self.output = result.stdout + result.stderr
        self.install = root / 'install'

    def prefix(self, package: str) -> Path:
        return self.install / package

    def env(self, *packages: str) -> dict[str, str]:
        prefixes = [str(self.prefix(p)) for p in packages] + [str(VENV)]
        return dict(os.environ, AMENT_PREFIX_PATH=os.pathsep.join(prefixes),
                    ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')


def build_env() -> dict[str, str]:
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)  # the build must report every error without `make -k`
    env.update(AMENT_PREFIX_PATH=str(VENV), CMAKE_PREFIX_PATH=str(VENV),
               PATH=os.pathsep.join([str(VENV / 'bin'), env.get('PATH', '')]),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    return env


@pytest.fixture(scope='module')
def build(tmp_path_factory: pytest.TempPathFactory) -> Build:
    root = tmp_path_factory.mktemp('colcon_ws')
    src = root / 'src'
    src.mkdir()
    for package in sorted((REPO / 'examples' / 'workspace' / 'src').iterdir()):
        shutil.copytree(package, src / package.name)
    for fixture in ('broken_nodl', 'broken_config', 'relative_mixins', 'escaping_mixin',
                    'bad_node_name'):
        shutil.copytree(FIXTURES / 'colcon' / fixture, src / fixture)
    result = subprocess.run([str(VENV / 'bin' / 'colcon'), 'build', '--continue-on-error'],
                            cwd=root, env=build_env(), text=True, capture_output=True,
                            timeout=300)
    return Build(root, result)


def nodl(build: Build, *args: str) -> subprocess.CompletedProcess[str]:
    # the installed command, as a user of the workspace runs it
    return subprocess.run([str(VENV / 'bin' / 'nodl'), *args], cwd=build.root,
                          env=build.env('laser_driver', 'robot_interfaces_nodl'), text=True,
                          capture_output=True, timeout=60)


def test_the_examples_build_and_the_broken_packages_fail(build: Build) -> None:
    out = build.output
    assert build.result.returncode != 0, out
    assert 'Finished <<< robot_interfaces_nodl' in out, out
    assert 'Finished <<< laser_driver' in out, out
    assert 'Finished <<< relative_mixins' in out, out
    assert 'Failed   <<< broken_nodl' in out, out
    assert 'Failed   <<< broken_config' in out, out
    assert 'Failed   <<< escaping_mixin' in out, out
    assert 'Failed   <<< bad_node_name' in out, out
    assert '3 packages finished' in out, out


@pytest.mark.parametrize('package, files', [
    ('robot_interfaces_nodl', ['diagnostics.nodl.yaml']),
    ('laser_driver', ['laser_driver_node.nodl.yaml', 'motor_control.nodl.yaml']),
])
def test_definitions_are_installed_unchanged(build: Build, package: str, files: list[str]) -> None:
    installed = build.prefix(package) / 'share' / package / 'nodl'
    assert sorted(p.name for p in installed.iterdir()) == files
    for name in files:
        source = REPO / 'examples' / 'workspace' / 'src' / package / 'nodl' / name
        assert (installed / name).read_bytes() == source.read_bytes()


@pytest.mark.parametrize('package, resource, content', [
    ('laser_driver', 'nodl_nodes/laser_driver__laser_driver_node', 'nodl/laser_driver_node.nodl.yaml'),
    ('laser_driver', 'nodl_interfaces/laser_driver__motor_control', 'nodl/motor_control.nodl.yaml'),
    ('robot_interfaces_nodl', 'nodl_interfaces/robot_interfaces_nodl__diagnostics',
     'nodl/diagnostics.nodl.yaml'),
])
def test_index_entries_hold_the_installed_relative_path(build: Build, package: str, resource: str,
                                                        content: str) -> None:
    entry = build.prefix(package) / INDEX / resource
    assert entry.read_text(encoding='utf-8') == content
    assert (build.prefix(package) / 'share' / package / content).is_file()


def test_only_the_registered_entries_are_installed(build: Build) -> None:
    for package in ('laser_driver', 'robot_interfaces_nodl'):
        index = build.prefix(package) / INDEX
        nodl_entries = sorted(str(p.relative_to(index)) for p in index.glob('nodl_*/*'))
        expected = {
            'laser_driver': ['nodl_interfaces/laser_driver__motor_control',
                             'nodl_nodes/laser_driver__laser_driver_node'],
            'robot_interfaces_nodl': ['nodl_interfaces/robot_interfaces_nodl__diagnostics'],
        }[package]
        assert nodl_entries == expected
        # the build-time staging index stays in the build folder
        assert not list(build.prefix(package).rglob('ament_nodl_stage'))


def test_the_kind_is_enforced_at_build_time(build: Build) -> None:
    assert ('broken_nodl/nodl/a_node.nodl.yaml:1:1: error: expected an interface definition'
            in build.output), build.output


def test_a_broken_mixin_fails_the_build_at_its_entry(build: Build) -> None:
    lines = [line for line in build.output.splitlines() if 'talker.nodl.yaml:4:5:' in line]
    assert lines, build.output
    assert 'broken_nodl/nodl/talker.nodl.yaml:4:5: error: cannot resolve mixin ' \
           "'nodl://robot_interfaces_nodl/no_such_interface'" in lines[0]


def test_a_node_is_composed_with_the_rclcpp_base_at_build_time(build: Build) -> None:
    # valid against rclpy's base, not rclcpp's: an ament_cmake package's nodes are rclcpp's,
    # as nodl analyse, show and check take them from the package's build type
    lines = [line for line in build.output.splitlines() if 'time_source.nodl.yaml:8:7:' in line]
    assert lines and '[NODL308]' in lines[0], build.output


def test_every_invalid_file_of_a_package_is_reported(build: Build) -> None:
    # both files of broken_nodl, in one build, whatever make's parallelism
    assert 'broken_nodl: invalid NoDL definitions:' in build.output
    assert build.output.count(': error: ') >= 2


def test_a_failed_package_installs_nothing(build: Build) -> None:
    assert not (build.prefix('broken_nodl') / INDEX / 'nodl_nodes').exists()
    assert not (build.prefix('broken_nodl') / 'share' / 'broken_nodl' / 'nodl').exists()


def test_a_registration_error_fails_at_configure_time(build: Build) -> None:
    out = build.output
    assert 'ament_nodl_register_node(talker): file' in out, out
    assert 'broken_config/nodl/missing.nodl.yaml' in out
    assert 'does not exist' in out
    # it stopped before any build step
    assert not (build.root / 'build' / 'broken_config' / 'Makefile').exists()


def test_a_namespaced_node_name_fails_at_configure_time(build: Build) -> None:
    # PLUGIN and NODE_NAME themselves are built and read back in test_examples_system.py
    out = ' '.join(build.output.split())  # CMake wraps its messages
    assert ("ament_nodl_register_node(camera_driver): NODE_NAME 'front/camera' is not a valid "
            'node name' in out), build.output
    assert not (build.root / 'build' / 'bad_node_name' / 'Makefile').exists()


def test_show_an_installed_node_with_its_layers(build: Build) -> None:
    result = nodl(build, 'show', 'laser_driver', 'laser_driver_node', '--layers')
    assert result.returncode == 0, result.stderr
    layers = [line.strip() for line in result.stdout.splitlines() if '# layer:' in line]
    assert set(layers) == {'# layer: base:node',
                           '# layer: nodl://robot_interfaces_nodl/diagnostics',
                           '# layer: nodl://laser_driver/motor_control',
                           '# layer: main'}
    assert result.stdout.count('# layer: nodl://laser_driver/motor_control') == 2
    # main overrides the shared diagnostics.period default
    assert '  # layer: main\n  diagnostics.period:\n    type: double\n    default_value: 0.5' \
        in result.stdout


def test_list_the_installed_definitions(build: Build) -> None:
    result = nodl(build, 'list')
    assert result.returncode == 0, result.stderr
    listed = [tuple(line.split()) for line in result.stdout.splitlines()]
    share = lambda pkg, f: str(build.prefix(pkg) / 'share' / pkg / 'nodl' / f)  # noqa: E731
    # package, kind, name, origin (the ament index here), file
    assert listed == [
        ('laser_driver', 'node', 'laser_driver_node', 'index',
         share('laser_driver', 'laser_driver_node.nodl.yaml')),
        ('laser_driver', 'interface', 'motor_control', 'index',
         share('laser_driver', 'motor_control.nodl.yaml')),
        ('robot_interfaces_nodl', 'interface', 'diagnostics', 'index',
         share('robot_interfaces_nodl', 'diagnostics.nodl.yaml')),
    ]


def test_installed_definitions_validate_against_the_installed_index(build: Build) -> None:
    node = build.prefix('laser_driver') / 'share' / 'laser_driver' / 'nodl' / 'laser_driver_node.nodl.yaml'
    result = nodl(build, 'validate', '--resolve', '--kind', 'node', str(node))
    assert result.returncode == 0, result.stdout + result.stderr
    # without robot_interfaces_nodl on the path the mixin cannot resolve
    alone = subprocess.run([str(VENV / 'bin' / 'nodl'), 'validate', '--resolve', str(node)],
                           cwd=build.root, env=build.env('laser_driver'), text=True,
                           capture_output=True, timeout=60)
    assert alone.returncode == 1
    assert f'{node}:4:5: error: cannot resolve mixin ' \
           "'nodl://robot_interfaces_nodl/diagnostics'" in alone.stdout


# --- relative mixins: installed where the installed node file looks for them -------------

RELATIVE = FIXTURES / 'colcon' / 'relative_mixins'


@pytest.mark.parametrize('source, installed', [
    ('nodl/sensor_node.nodl.yaml', 'nodl/sensor_node.nodl.yaml'),
    ('nodl/diagnostics.yaml', 'nodl/diagnostics.yaml'),
    ('nodl/common/limits.nodl.yaml', 'nodl/common/limits.nodl.yaml'),
    ('shared/heartbeat.nodl.yaml', 'shared/heartbeat.nodl.yaml'),
])
def test_relative_mixins_are_installed_keeping_their_layout(build: Build, source: str,
                                                             installed: str) -> None:
    target = build.prefix('relative_mixins') / 'share' / 'relative_mixins' / installed
    assert target.read_bytes() == (RELATIVE / source).read_bytes()


def test_relative_mixins_are_not_registered(build: Build) -> None:
    index = build.prefix('relative_mixins') / INDEX
    assert sorted(str(p.relative_to(index)) for p in index.glob('nodl_*/*')) == [
        'nodl_nodes/relative_mixins__sensor_node']


def test_a_relative_mixin_that_would_leave_the_package_fails_at_configure_time(build: Build) -> None:
    out = ' '.join(build.output.split())  # CMake wraps its messages
    assert ("ament_nodl_register_node(deep_node): mixin '../../common.yaml' of '"
            in out), build.output
    assert 'would be installed outside share/escaping_mixin' in out
    assert not (build.root / 'build' / 'escaping_mixin' / 'Makefile').exists()


def test_show_an_installed_node_with_relative_mixins(build: Build) -> None:
    result = subprocess.run([str(VENV / 'bin' / 'nodl'), 'show', 'relative_mixins', 'sensor_node',
                             '--layers'], cwd=build.root, env=build.env('relative_mixins'),
                            text=True, capture_output=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    layers = {line.strip() for line in result.stdout.splitlines() if '# layer:' in line}
    assert layers == {'# layer: base:node', '# layer: diagnostics.yaml',
                      '# layer: file://common/limits.nodl.yaml',
                      '# layer: ../shared/heartbeat.nodl.yaml', '# layer: main'}
    # the installed copy, not the source tree, was read
    node = build.prefix('relative_mixins') / 'share' / 'relative_mixins' / 'nodl' / 'sensor_node.nodl.yaml'
    check = subprocess.run([str(VENV / 'bin' / 'nodl'), 'validate', '--resolve', str(node)],
                           cwd=build.root, env=build.env('relative_mixins'), text=True,
                           capture_output=True, timeout=60)
    assert check.returncode == 0, check.stdout + check.stderr


# Last: this test rebuilds a package of the shared workspace.
def test_a_removed_registration_does_not_linger_in_the_staging_index(build: Build) -> None:
    package = build.root / 'src' / 'robot_interfaces_nodl'
    cmake = package / 'CMakeLists.txt'
    text = cmake.read_text()
    registration = 'ament_nodl_register_interface(diagnostics FILE nodl/diagnostics.nodl.yaml)'
    assert registration in text
    # the interface is no longer registered, but a new node still references it
    cmake.write_text(text.replace(
        registration, 'ament_nodl_register_node(uses_diagnostics FILE nodl/uses.nodl.yaml)'))
    (package / 'nodl' / 'uses.nodl.yaml').write_text(
        'nodl_version: 2\nbase: node\nmixins:\n  - nodl://robot_interfaces_nodl/diagnostics\n'
        'main:\n  nodl_version: 2\n')
    result = subprocess.run([str(VENV / 'bin' / 'colcon'), 'build', '--packages-select',
                             'robot_interfaces_nodl'], cwd=build.root, env=build_env(), text=True,
                            capture_output=True, timeout=300)
    out = result.stdout + result.stderr
    assert result.returncode != 0, out
    assert ('robot_interfaces_nodl/nodl/uses.nodl.yaml:4:5: error: cannot resolve mixin '
            "'nodl://robot_interfaces_nodl/diagnostics'") in out, out
