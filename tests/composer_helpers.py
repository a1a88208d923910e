"""Shared by the composer's tests: the fixture definitions folder and launch files."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

from conftest import REPO

FIXTURES = REPO / 'tests' / 'fixtures' / 'composer'
DEFINITIONS = FIXTURES / 'definitions'
LAUNCH = FIXTURES / 'launch'
EXAMPLE = REPO / 'examples' / 'system'


def definitions(*folders: Path) -> Any:
    """The definitions folders (the fixture's by default), as --definitions gives them."""
    from nodl.targets.resolve import gather_definitions

    return gather_definitions([str(f) for f in (folders or (DEFINITIONS,))], use_config=False)


def copy_launch(tmp: Path) -> Path:
    """A copy of the fixture launch folder (the tests edit it)."""
    target = tmp / 'launch'
    shutil.copytree(LAUNCH, target)
    return target


def example_definitions(tmp: Path) -> Path:
    """The example system's definitions as a definitions folder (no colcon build needed):
    DIR/<package>/<executable>.nodl.yaml, the shared mixin under interfaces/."""
    root = tmp / 'example_definitions'
    for package in ('rover_base', 'rover_sensors', 'rover_navigation', 'rover_tools'):
        for file in (EXAMPLE / package / 'nodl').glob('*.nodl.yaml'):
            folder = root / package / ('interfaces' if file.name == 'diagnostics.nodl.yaml' else '')
            folder.mkdir(parents=True, exist_ok=True)
            shutil.copy(file, folder / file.name)
    return root


def example_copy(tmp: Path) -> Path:
    """A copy of the example system's launch and config folders (and nodl.toml)."""
    target = tmp / 'system'
    for name in ('launch', 'config'):
        shutil.copytree(EXAMPLE / name, target / name)
    shutil.copy(EXAMPLE / 'nodl.toml', target / 'nodl.toml')
    return target
