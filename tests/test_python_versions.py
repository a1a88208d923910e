"""The library and the `nodl` command on Python 3.10 (ROS 2 Humble) and 3.12.

The ROS 2 wheels exist for CPython 3.11 only, so on the other versions the toolkit is
installed without extras (what a user of a system ROS does), and the non-live features
must work there. Each interpreter gets a fresh virtual environment into which the
toolkit's wheel (built once, from a copy of the repository) and its one dependency are
installed with pip, then the command runs on the examples.

A missing interpreter fails the test: these versions are supported, so the machine
that runs the suite must have them.
"""

from __future__ import annotations

import glob
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import REPO
from test_lock import LOCK, normal, read_lock

VERSIONS = ('3.10', '3.12')


def find_interpreter(version: str) -> str:
    """A working ``python<version>``: on PATH, or where pyenv and distributions put it."""
    candidates = [shutil.which(f'python{version}'), f'/usr/bin/python{version}',
                  f'/usr/local/bin/python{version}',
                  *sorted(glob.glob(os.path.expanduser(f'~/.pyenv/versions/{version}.*/bin/python{version}')),
                          reverse=True)]
    tried = []
    for candidate in filter(None, candidates):
        try:
            probe = subprocess.run([candidate, '-c', 'import sys; print("%d.%d" % sys.version_info[:2])'],
                                   capture_output=True, text=True, timeout=30)
        except OSError:
            continue
        tried.append(candidate)
        if probe.returncode == 0 and probe.stdout.strip() == version:
            return candidate
    pytest.fail(f'Python {version} is supported but no working python{version} was found '
                f'(tried: {", ".join(tried) or "nothing on PATH"}); install it to run this test')


def pip(*args: str) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k != 'PIP_REQUIRE_VIRTUALENV'}
    return subprocess.run([sys.executable, '-m', 'pip', '--disable-pip-version-check', '--no-input',
                           *args], capture_output=True, text=True, timeout=300, env=env)


@pytest.fixture(scope='module')
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The toolkit's wheel, built from a copy of the repository (no in-tree build folders)."""
    root = tmp_path_factory.mktemp('wheel')
    source = root / 'src'
    listed = subprocess.run(['git', 'ls-files', '-z', '--cached', '--others', '--exclude-standard'],
                            cwd=REPO, capture_output=True, check=True, timeout=60).stdout
    for name in filter(None, listed.decode().split('\0')):
        path = REPO / name
        if path.is_file() and not path.is_symlink():
            (source / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(path, source / name)
    result = pip('wheel', '--no-deps', '--no-build-isolation', '-w', str(root / 'dist'), str(source))
    assert result.returncode == 0, result.stdout + result.stderr
    [built] = (root / 'dist').glob('nodl_toolkit-*.whl')
    return built


@pytest.fixture(scope='module', params=VERSIONS)
def venv(request: pytest.FixtureRequest, wheel: Path,
         tmp_path_factory: pytest.TempPathFactory) -> Path:
    version: str = request.param
    python = find_interpreter(version)
    root = tmp_path_factory.mktemp(f'py{version}') / 'venv'
    made = subprocess.run([python, '-m', 'venv', '--without-pip', str(root)], capture_output=True,
                          text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    # this environment's pip installs into the new one (no ensurepip: faster), with the
    # lock's pins wherever they exist for this version (PyYAML, and tomli on 3.10)
    result = pip('--python', str(root / 'bin' / 'python'), 'install', '-c', str(LOCK), str(wheel))
    assert result.returncode == 0, result.stdout + result.stderr
    return root


def run(venv: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ('PYTHONPATH', 'AMENT_PREFIX_PATH')}
    env['PATH'] = os.pathsep.join([str(venv / 'bin'), env.get('PATH', '')])
    return subprocess.run(list(args), cwd=REPO / 'examples', env=env, text=True,
                          capture_output=True, timeout=120)


def test_the_environment_is_the_wanted_python_without_ros(venv: Path) -> None:
    probe = run(venv, str(venv / 'bin' / 'python'), '-I', '-c',
                'import sys, importlib.util as u; print("%d.%d" % sys.version_info[:2]); '
                'print(u.find_spec("rclpy") is None); import nodl; print(nodl.__file__)')
    assert probe.returncode == 0, probe.stderr
    version, no_rclpy, module = probe.stdout.splitlines()
    assert version in VERSIONS and no_rclpy == 'True'
    assert module.startswith(str(venv))


def test_the_dependencies_are_the_locked_ones(venv: Path) -> None:
    probe = run(venv, str(venv / 'bin' / 'python'), '-I', '-c',
                'import importlib.metadata as m\n'
                'for d in m.distributions(): print(d.metadata["Name"], d.version)')
    assert probe.returncode == 0, probe.stderr
    installed = dict(line.split(' ', 1) for line in probe.stdout.splitlines())
    pins = read_lock()
    checked = {normal(name): version for name, version in installed.items()
               if normal(name) in pins}
    assert 'pyyaml' in checked
    assert checked == {name: pins[name][0] for name in checked}


def test_nodl_validate_on_the_examples(venv: Path) -> None:
    result = run(venv, 'nodl', 'validate', '.')
    assert result.returncode == 0, result.stdout + result.stderr
    assert 'laser_driver.nodl.yaml: valid node definition' in result.stdout
    mistakes = run(venv, 'nodl', 'validate', 'mistakes/typos.yaml')
    assert mistakes.returncode == 1
    assert "mistakes/typos.yaml:4:7: error: invalid value 'lifecycle_nod' for 'base'" in mistakes.stdout


def test_nodl_show_composes_a_node(venv: Path) -> None:
    result = run(venv, 'nodl', 'show', 'laser_driver.nodl.yaml', '--layers')
    assert result.returncode == 0, result.stdout + result.stderr
    assert '# layer: main' in result.stdout


def test_live_features_say_what_is_missing(venv: Path) -> None:
    # no rclpy here: one line and exit status 2, not a traceback
    result = run(venv, 'nodl', 'describe', '/some_node', '--timeout', '1')
    assert result.returncode == 2, result.stdout + result.stderr
    assert 'Traceback' not in result.stderr
    assert 'rclpy' in result.stderr


def test_every_module_imports(venv: Path) -> None:
    # A module may need an optional package (rclpy for the live features, pytest for the
    # plugin); it may not use what this Python's standard library or syntax lacks.
    code = '''
import importlib, pkgutil, sys, nodl
for info in pkgutil.walk_packages(nodl.__path__, 'nodl.'):
    if info.name.endswith('__main__'):
        continue  # runs the command
    try:
        importlib.import_module(info.name)
    except ModuleNotFoundError as exc:
        top = (exc.name or '').partition('.')[0]
        if top in sys.stdlib_module_names or top in ('nodl', 'yaml'):
            print(info.name, repr(exc))
    except Exception as exc:
        print(info.name, repr(exc))
'''
    result = run(venv, str(venv / 'bin' / 'python'), '-I', '-c', code)
    assert result.returncode == 0, result.stderr
    assert result.stdout == ''
