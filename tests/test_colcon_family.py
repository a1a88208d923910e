"""The repository builds as a family of ROS packages with colcon, as a ROS user builds it.

One real ``colcon build`` (module scope) of a workspace whose ``src/`` holds a copy of
this repository (its packages: nodl_toolkit, ament_nodl, ros2nodl) next to packages
that ``<build_depend>ament_nodl</build_depend>``: an interface package, a node package
with ``nodl://`` mixins, a node package with relative mixins and a broken package.

The environment has the ROS 2 wheels but NOT the toolkit. The test virtual environment
has the toolkit installed, so the build runs in a *shadow* of it: a folder that is a
virtual environment of the same interpreter whose entries are symbolic links to the
test environment's, except every file the toolkit's distribution installed (its
RECORD: the ``nodl`` package, its metadata, the ``nodl`` command, the
``ament_nodl`` CMake files and index markers). Scripts are copied with their ``#!``
line pointing at the shadow's interpreter. Nothing is downloaded or installed, so it
takes a second, and what colcon sees is exactly "the ROS wheels, no toolkit".
"""

from __future__ import annotations

import importlib.metadata
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO

VENV = Path(sys.prefix)
INDEX = Path('share') / 'ament_index' / 'resource_index'
TOOLKIT = ('nodl_toolkit', 'ament_nodl', 'ros2nodl')
USERS = ('robot_interfaces_nodl', 'laser_driver', 'relative_mixins')


# --- the shadow environment -----------------------------------------------------------------

def _toolkit_files() -> set[Path]:
    """Every file the installed toolkit distribution put into the environment."""
    # the installed copy (the source tree's egg-info may come first on sys.path)
    [dist] = [d for d in importlib.metadata.distributions(path=[sysconfig.get_paths()['purelib']])
              if d.metadata['Name'] == 'nodl-toolkit']
    files = dist.files or []
    located = {Path(os.path.normpath(dist.locate_file(f))) for f in files}
    assert any(p.name == 'nodl' and p.parent.name == 'bin' for p in located), located
    # and its packages as a whole (byte code compiled later is not in the RECORD)
    purelib = Path(sysconfig.get_paths()['purelib'])
    located |= {purelib / p.relative_to(purelib).parts[0] for p in located
                if purelib in p.parents and len(p.relative_to(purelib).parts) > 1}
    return located


def _mirror(source: Path, target: Path, excluded: set[Path], python: Path) -> None:
    target.mkdir(parents=True, exist_ok=True)
    for entry in os.scandir(source):
        path = Path(entry.path)
        dest = target / entry.name
        if path in excluded:
            continue
        if entry.is_symlink():
            os.symlink(os.readlink(path), dest)  # relative links stay inside the shadow
        elif entry.is_dir() and any(path in e.parents for e in excluded):
            _mirror(path, dest, excluded, python)
            if not any(dest.iterdir()):
                dest.rmdir()  # held only the toolkit's files
        elif entry.is_file() and source.name == 'bin' and _is_venv_script(path):
            text = path.read_text(encoding='utf-8')
            first, _, rest = text.partition('\n')
            dest.write_text(f'#!{python}\n{rest}', encoding='utf-8')
            dest.chmod(0o755)
        else:
            os.symlink(path, dest)


def _is_venv_script(path: Path) -> bool:
    with open(path, 'rb') as f:
        return f.read(len(str(VENV)) + 2) == f'#!{VENV}'.encode()


def make_shadow(root: Path) -> Path:
    """A virtual environment with what the test environment has, minus the toolkit."""
    _mirror(VENV, root, _toolkit_files(), root / 'bin' / 'python')
    return root


# --- the build ------------------------------------------------------------------------------

class Build:
    def __init__(self, root: Path, shadow: Path, result: subprocess.CompletedProcess[str]) -> None:
        self.root = root
        self.shadow = shadow
        self.result = result
        self.output = result.stdout + result.stderr
        self.install = root / 'install'

    def env(self) -> dict[str, str]:
        """The shadow environment (the ROS wheels, no toolkit), without the workspace."""
        path = [p for p in os.environ.get('PATH', '').split(os.pathsep) if Path(p) != VENV / 'bin']
        env = {k: v for k, v in os.environ.items()
               if k not in ('PYTHONPATH', 'MAKEFLAGS', 'AMENT_PREFIX_PATH', 'CMAKE_PREFIX_PATH',
                            'COLCON_PREFIX_PATH', 'PYTHONHOME')}
        env.update(VIRTUAL_ENV=str(self.shadow), AMENT_PREFIX_PATH=str(self.shadow),
                   CMAKE_PREFIX_PATH=str(self.shadow), ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST',
                   PATH=os.pathsep.join([str(self.shadow / 'bin'), *path]))
        return env

    def sourced(self, command: str) -> subprocess.CompletedProcess[str]:
        """Run a shell command after sourcing the install space, as a user does."""
        return subprocess.run(['sh', '-c', f'. ./install/setup.sh && {command}'], cwd=self.root,
                              env=self.env(), text=True, capture_output=True, timeout=60)


def _copy_repository(target: Path) -> None:
    """What a clone holds: the tracked files and new ones not ignored (links kept)."""
    listed = subprocess.run(['git', 'ls-files', '-z', '--cached', '--others', '--exclude-standard'],
                            cwd=REPO, capture_output=True, check=True, timeout=60).stdout
    for name in filter(None, listed.decode().split('\0')):
        source = REPO / name
        if not os.path.lexists(source):
            continue  # deleted in the working tree
        dest = target / name
        dest.parent.mkdir(parents=True, exist_ok=True)
        if source.is_symlink():
            os.symlink(os.readlink(source), dest)
        elif source.is_file():
            shutil.copy2(source, dest)


@pytest.fixture(scope='module')
def build(tmp_path_factory: pytest.TempPathFactory) -> Build:
    base = tmp_path_factory.mktemp('family')
    shadow = make_shadow(base / 'shadow')
    root = base / 'ws'
    src = root / 'src'
    _copy_repository(src / 'nodl')
    for package in ('robot_interfaces_nodl', 'laser_driver'):
        shutil.copytree(REPO / 'examples' / 'workspace' / 'src' / package, src / package)
    for package in ('relative_mixins', 'broken_definitions'):
        shutil.copytree(FIXTURES / 'colcon' / package, src / package)
    probe = Build(root, shadow, subprocess.CompletedProcess([], 0, '', ''))
    result = subprocess.run([str(shadow / 'bin' / 'colcon'), 'build', '--continue-on-error'],
                            cwd=root, env=probe.env(), text=True, capture_output=True, timeout=300)
    return Build(root, shadow, result)


# --- the environment is what it claims ------------------------------------------------------

def test_the_shadow_has_the_ros_wheels_but_not_the_toolkit(build: Build) -> None:
    python = str(build.shadow / 'bin' / 'python')
    probe = subprocess.run(
        [python, '-c', 'import sys, importlib.util as u, catkin_pkg, colcon_core; '
         'print(sys.prefix); print(u.find_spec("nodl"))'],
        cwd=build.root, env=build.env(), text=True, capture_output=True, timeout=60)
    assert probe.returncode == 0, probe.stderr
    assert probe.stdout.splitlines() == [str(build.shadow), 'None']
    assert shutil.which('nodl', path=build.env()['PATH']) is None
    assert not (build.shadow / 'share' / 'ament_nodl').exists()
    assert (build.shadow / 'share' / 'ament_cmake_core').exists()


# --- colcon finds the family and orders it -------------------------------------------------

def test_colcon_finds_the_three_packages_of_the_repository(build: Build) -> None:
    started = sorted(line.split()[-1] for line in build.result.stdout.splitlines()
                     if line.startswith('Starting >>> '))
    # not the repository root, nor the example and fixture packages inside it (COLCON_IGNORE):
    # copies of two of them are in src/ too, and a duplicate name would stop colcon
    assert started == sorted(TOOLKIT + USERS + ('broken_definitions',)), build.output


def test_the_family_and_its_users_build_and_the_broken_package_fails(build: Build) -> None:
    out = build.output
    assert build.result.returncode != 0, out
    for package in TOOLKIT + USERS:
        assert f'Finished <<< {package}' in out, out
    assert 'Failed   <<< broken_definitions' in out, out
    assert f'{len(TOOLKIT + USERS)} packages finished' in out, out


def test_packages_that_depend_on_ament_nodl_build_after_the_toolkit(build: Build) -> None:
    out = build.output
    for user in USERS + ('broken_definitions',):
        started = out.index(f'Starting >>> {user}')
        assert out.index('Finished <<< nodl_toolkit') < started, out
        assert out.index('Finished <<< ament_nodl') < started, out


def test_the_build_used_the_workspace_nodl_command(build: Build) -> None:
    cache = (build.root / 'build' / 'laser_driver' / 'CMakeCache.txt').read_text()
    assert f'AMENT_NODL_EXECUTABLE:FILEPATH={build.install}/nodl_toolkit/bin/nodl' in cache


def test_the_broken_package_fails_with_file_line_column(build: Build) -> None:
    assert ('broken_definitions/nodl/odometry_node.nodl.yaml:10:13: error: unknown parameter '
            "type 'dubble'") in build.output, build.output
    assert 'broken_definitions: invalid NoDL definitions:' in build.output


# --- what is installed ----------------------------------------------------------------------

def test_ament_nodl_is_an_ament_cmake_package_with_config_extras(build: Build) -> None:
    cmake = build.install / 'ament_nodl' / 'share' / 'ament_nodl' / 'cmake'
    # ament_package() generates the configuration files; every CMake file of the package
    # is installed but the pip-only configuration
    source = {p.name for p in (REPO / 'ros' / 'ament_nodl' / 'cmake').iterdir()}
    assert sorted(p.name for p in cmake.iterdir()) == sorted(
        source - {'ament_nodl-config.cmake'} | {'ament_nodlConfig.cmake',
                                                'ament_nodlConfig-version.cmake'})
    assert 'ament_nodl-extras.cmake' in (cmake / 'ament_nodlConfig.cmake').read_text()
    assert (build.install / 'ament_nodl' / INDEX / 'packages' / 'ament_nodl').is_file()


def test_nodl_toolkit_does_not_install_a_second_ament_nodl(build: Build) -> None:
    prefix = build.install / 'nodl_toolkit'
    assert not (prefix / 'share' / 'ament_nodl').exists()
    assert sorted(p.name for p in (prefix / INDEX / 'packages').iterdir()) == ['nodl_toolkit']
    assert (prefix / 'share' / 'nodl_toolkit' / 'package.xml').is_file()
    assert (prefix / 'bin' / 'nodl').is_file()


def test_nodl_show_on_the_installed_result(build: Build) -> None:
    result = build.sourced('nodl show laser_driver laser_driver_node --layers')
    assert result.returncode == 0, result.stdout + result.stderr
    layers = {line.strip() for line in result.stdout.splitlines() if '# layer:' in line}
    assert layers == {'# layer: base:node', '# layer: nodl://robot_interfaces_nodl/diagnostics',
                      '# layer: nodl://laser_driver/motor_control', '# layer: main'}
    which = build.sourced('command -v nodl')
    assert which.stdout.strip() == f'{build.install}/nodl_toolkit/bin/nodl'


def test_relative_mixins_resolve_from_the_installed_result(build: Build) -> None:
    result = build.sourced('nodl show relative_mixins sensor_node --layers')
    assert result.returncode == 0, result.stdout + result.stderr
    assert '# layer: ../shared/heartbeat.nodl.yaml' in result.stdout


def test_nodl_list_sees_every_registration_of_the_workspace(build: Build) -> None:
    result = build.sourced('nodl list')
    assert result.returncode == 0, result.stderr
    assert [tuple(line.split()[:3]) for line in result.stdout.splitlines()] == [
        ('laser_driver', 'node', 'laser_driver_node'),
        ('laser_driver', 'interface', 'motor_control'),
        ('relative_mixins', 'node', 'sensor_node'),
        ('robot_interfaces_nodl', 'interface', 'diagnostics'),
    ]


def test_ros2nodl_registers_the_ros2_command(build: Build) -> None:
    # ros2cli is not on the Python registry: load the entry point as ros2cli does
    code = ('import importlib.metadata as m\n'
            'eps = [e for e in m.entry_points(group="ros2cli.command") if e.name == "nodl"]\n'
            'print(sorted(e.dist.name for e in eps))\n'
            'command = eps[0].load()()\n'
            'import nodl; print(nodl.__file__)\n'
            'print(command.EXTENSION_POINT_VERSION)\n')
    result = build.sourced(f"python -c '{code}'")
    assert result.returncode == 0, result.stderr
    dists, module, version = result.stdout.splitlines()
    assert dists == "['ros2nodl']"  # once: nodl_toolkit leaves it to ros2nodl
    assert module.startswith(f'{build.install}/nodl_toolkit/')
    assert version == '0.1'


def test_the_colcon_setup_reads_the_one_pyproject(build: Build) -> None:
    # ros/nodl_toolkit/setup.py derives its entry points from pyproject.toml: compare the
    # installed console script and verbs with the test environment's (from pip)
    code = ('import importlib.metadata as m\n'
            'print(sorted((e.group, e.name, e.value) for e in m.distribution("nodl_toolkit")'
            '.entry_points))\n')
    result = build.sourced(f"python -c '{code}'")
    assert result.returncode == 0, result.stderr
    [dist] = [d for d in importlib.metadata.distributions(path=[sysconfig.get_paths()['purelib']])
              if d.metadata['Name'] == 'nodl-toolkit']
    pip_installed = sorted((e.group, e.name, e.value) for e in dist.entry_points
                           if e.group != 'ros2cli.command')
    assert result.stdout.strip() == str(pip_installed)
