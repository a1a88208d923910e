"""The lock (constraints.txt) and the environment the suite runs in agree.

A dependency that moved under the suite (PyYAML 6.0.4 did, in a patch release) made
``make test`` red on a fresh clone. So every package of the environment is pinned with
``==`` (``make lock``, tools/lock.py), the environment ``make`` builds is checked against
the pins here, and pyproject.toml's ranges are checked to admit the pinned versions and
to stop before the next release series.
"""

from __future__ import annotations

import importlib.metadata
import re
import sys
from pathlib import Path

import pytest
from packaging.markers import Marker
from packaging.requirements import Requirement
from packaging.specifiers import SpecifierSet
from packaging.version import Version

from conftest import REPO

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - the suite runs on 3.11
    import tomli as tomllib

LOCK = REPO / 'constraints.txt'
PIN = re.compile(r'^(?P<name>[A-Za-z0-9][A-Za-z0-9._-]*)==(?P<version>[^\s;#]+)'
                 r'\s*(?:;\s*(?P<marker>[^#]+?))?\s*$')


def normal(name: str) -> str:
    return re.sub(r'[-_.]+', '-', name).lower()


def read_lock(path: Path = LOCK) -> dict[str, tuple[str, str | None]]:
    """{normalised name: (version, marker or None)}; fails on any line that is not a pin."""
    pins: dict[str, tuple[str, str | None]] = {}
    for number, line in enumerate(path.read_text(encoding='utf-8').splitlines(), 1):
        text = line.strip()
        if not text or text.startswith('#'):
            continue
        match = PIN.match(text)
        assert match, f'{path.name}:{number}: not pinned with ==: {text!r} (run make lock)'
        name = normal(match['name'])
        assert name not in pins, f'{path.name}:{number}: {name} is pinned twice'
        pins[name] = (match['version'], match['marker'])
    return pins


def applies(marker: str | None) -> bool:
    return marker is None or Marker(marker).evaluate()


def test_every_line_of_the_lock_is_an_exact_pin() -> None:
    pins = read_lock()
    # the environment `make` builds: the project's runtime, ROS, the test tools, the builders
    for name in ('pyyaml', 'ros-rclpy', 'ros-rmw-fastrtps-cpp', 'pytest', 'colcon-core',
                 'pip', 'setuptools', 'wheel', 'uv'):
        assert name in pins, f'{name} is not in the lock'
    # Python 3.10 gets its own, marked, pins (the compatibility tests install them)
    assert pins['tomli'][1] is not None and 'python_version' in pins['tomli'][1]


def test_a_range_or_an_unpinned_line_is_refused(tmp_path: Path) -> None:
    # the check above can fail: a line that admits several versions is caught
    loose = tmp_path / 'constraints.txt'
    loose.write_text('PyYAML>=6.0,<7\n', encoding='utf-8')
    with pytest.raises(AssertionError, match="not pinned with ==: 'PyYAML>=6.0,<7'"):
        read_lock(loose)


def installed_differences(pins: dict[str, tuple[str, str | None]]) -> list[str]:
    """Each pin this interpreter should have whose installed version differs (or is absent)."""
    differences = []
    for name, (version, marker) in sorted(pins.items()):
        if not applies(marker):
            continue
        try:
            found = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            differences.append(f'{name}: locked {version}, not installed')
            continue
        if Version(found) != Version(version):
            differences.append(f'{name}: locked {version}, installed {found}')
    return differences


def test_the_installed_environment_is_the_locked_one() -> None:
    differences = installed_differences(read_lock())
    assert not differences, (
        'the environment differs from constraints.txt (run `make install` after a new lock, '
        'or `make lock` after a new dependency):\n  ' + '\n  '.join(differences))


def test_a_moved_dependency_is_caught() -> None:
    assert installed_differences({'pyyaml': ('6.0.1', None)}) == [
        f'pyyaml: locked 6.0.1, installed {importlib.metadata.version("pyyaml")}']
    assert installed_differences({'no-such-package-here': ('1.0', None)}) == [
        'no-such-package-here: locked 1.0, not installed']
    # a pin for another interpreter is not this environment's business
    assert installed_differences({'pyyaml': ('6.0.1', 'python_version < "3.0"')}) == []


def project_requirements() -> list[Requirement]:
    project = tomllib.loads((REPO / 'pyproject.toml').read_text(encoding='utf-8'))['project']
    texts = list(project['dependencies'])
    for extra in project['optional-dependencies'].values():
        texts.extend(extra)
    return [r for r in map(Requirement, texts) if normal(r.name) != 'nodl-toolkit']


def test_pyproject_ranges_admit_the_lock_and_stop_before_the_next_series() -> None:
    pins = read_lock()
    problems = []
    for requirement in project_requirements():
        name = normal(requirement.name)
        if name not in pins:
            problems.append(f'{requirement}: not in the lock (run make lock)')
            continue
        version = Version(pins[name][0])
        spec: SpecifierSet = requirement.specifier
        if not spec.contains(version, prereleases=True):
            problems.append(f'{requirement}: does not admit the locked {version}')
        if not any(s.operator in ('<', '<=', '==', '~=') for s in spec):
            problems.append(f'{requirement}: no upper bound (a future release is not tested)')
        floors = [Version(s.version) for s in spec if s.operator in ('>=', '==', '~=')]
        if not floors:
            problems.append(f'{requirement}: no lower bound')
        elif name != 'setuptools' and max(floors) != version:
            # the floor is a version the suite passed on (setuptools' >=77 is a feature floor)
            problems.append(f'{requirement}: its floor {max(floors)} is not the tested {version}')
    assert not problems, '\n'.join(problems)
