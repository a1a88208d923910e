"""The ROS packages under ros/: their manifests, and the facts they share with pyproject.toml.

The builds themselves are tested in test_colcon_family.py (colcon) and
test_cmake_registration.py (pip, then colcon on the user's packages); these are the
cheap checks that the copies of a fact agree.
"""

from __future__ import annotations

import runpy
from pathlib import Path
from typing import Any

import pytest
import tomllib
from catkin_pkg.package import parse_package

from conftest import REPO

ROS = REPO / 'ros'
PACKAGES = {'nodl_toolkit': 'ament_python', 'ament_nodl': 'ament_cmake', 'ros2nodl': 'ament_python'}
PYPROJECT = tomllib.loads((REPO / 'pyproject.toml').read_text(encoding='utf-8'))


def toolkit_setup() -> dict[str, Any]:
    return runpy.run_path(str(ROS / 'nodl_toolkit' / 'setup.py'), run_name='not_main')


@pytest.mark.parametrize('name, build_type', sorted(PACKAGES.items()))
def test_each_package_has_a_valid_manifest(name: str, build_type: str) -> None:
    package = parse_package(str(ROS / name / 'package.xml'))
    package.validate()  # catkin_pkg's own checks (colcon-ros runs the same parser)
    assert package.name == name
    assert package.package_format == 3
    assert package.get_build_type() == build_type
    assert package.version == PYPROJECT['project']['version']


def test_ros_holds_the_family_and_nothing_else() -> None:
    assert sorted(p.name for p in ROS.iterdir()) == sorted(PACKAGES)


def test_ament_nodl_exports_its_dependency_on_the_toolkit() -> None:
    package = parse_package(str(ROS / 'ament_nodl' / 'package.xml'))
    # what makes colcon build nodl_toolkit before any package that depends on ament_nodl
    assert 'nodl_toolkit' in [d.name for d in package.build_export_depends]
    assert 'nodl_toolkit' in [d.name for d in package.buildtool_export_depends]


def test_the_repository_root_is_not_a_package() -> None:
    # colcon does not look below a package: the root must not be one
    for marker in ('package.xml', 'setup.py', 'setup.cfg', 'colcon.pkg'):
        assert not (REPO / marker).exists(), marker


@pytest.mark.parametrize('folder', ['examples', 'tests'])
def test_example_and_fixture_packages_are_hidden_from_colcon(folder: str) -> None:
    assert (REPO / folder / 'COLCON_IGNORE').is_file()
    assert list((REPO / folder).rglob('package.xml'))  # there is something to hide


@pytest.mark.parametrize('package', ['nodl', 'nodl_schema'])
def test_the_library_package_links_the_library(package: str) -> None:
    # the toolkit and the reference-compatible package built on it
    link = ROS / 'nodl_toolkit' / package
    assert link.is_symlink()
    assert link.resolve() == (REPO / package).resolve()


def test_the_colcon_setup_reads_pyproject_like_tomllib() -> None:
    # its fallback reader (Python 3.10 without tomli) must agree with tomllib on what it uses
    setup = toolkit_setup()
    text = (REPO / 'pyproject.toml').read_text(encoding='utf-8')
    assert setup['setup_arguments'](setup['_read_simple_toml'](text)) == \
        setup['setup_arguments'](PYPROJECT)


def test_the_colcon_setup_derives_everything_from_pyproject() -> None:
    arguments = toolkit_setup()['setup_arguments'](PYPROJECT)
    project = PYPROJECT['project']
    assert arguments['version'] == project['version']
    assert arguments['python_requires'] == project['requires-python']
    assert arguments['install_requires'] == project['dependencies']
    expected = {'console_scripts': sorted(f'{k} = {v}' for k, v in project['scripts'].items())}
    for group, entries in project['entry-points'].items():
        if group != 'ros2cli.command':  # registered by ros2nodl
            expected[group] = sorted(f'{k} = {v}' for k, v in entries.items())
    assert {g: sorted(e) for g, e in arguments['entry_points'].items()} == expected
    assert 'nodl' in arguments['packages'] and 'nodl_schema' in arguments['packages']


def test_ros2nodl_registers_the_same_ros2cli_command_as_pyproject(monkeypatch: pytest.MonkeyPatch) -> None:
    import setuptools

    captured: dict[str, Any] = {}
    monkeypatch.setattr(setuptools, 'setup', lambda **kwargs: captured.update(kwargs))
    monkeypatch.chdir(ROS / 'ros2nodl')
    runpy.run_path('setup.py', run_name='__main__')
    pyproject = [f'{k} = {v}' for k, v in PYPROJECT['project']['entry-points']['ros2cli.command'].items()]
    assert captured['entry_points'] == {'ros2cli.command': pyproject}
    assert captured['version'] == PYPROJECT['project']['version']
    assert captured['name'] == 'ros2nodl'


def test_pip_installs_the_ros_files_it_lists() -> None:
    data_files = PYPROJECT['tool']['setuptools']['data-files']
    listed = [source for sources in data_files.values() for source in sources]
    for source in listed:
        assert (REPO / source).is_file(), source
    # every CMake file of ament_nodl reaches share/ament_nodl/cmake
    cmake = sorted(p.name for p in (ROS / 'ament_nodl' / 'cmake').iterdir())
    assert sorted(Path(s).name for s in data_files['share/ament_nodl/cmake']) == cmake
