"""ament_nodl_doc_check: `nodl doc --check` registered as a package test, with a real colcon
build, colcon test and colcon test-result: it passes while the pages in doc/ are what the
installed definitions give, and fails once a definition changed and the pages were not
written again.

The build uses this tree's ament_nodl CMake files and this tree's library (a `nodl` command
next to them runs `python -m nodl` from the tree), not the installed copies.
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


class Workspace:
    def __init__(self, root: Path, env: dict[str, str]) -> None:
        self.root, self.env = root, env
        self.package = root / 'src' / 'doc_checked'

    def run(self, *command: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
        return subprocess.run(list(command), cwd=self.root, env=env or self.env, text=True,
                              capture_output=True, timeout=300)

    def colcon(self, *args: str) -> subprocess.CompletedProcess[str]:
        return self.run(str(VENV / 'bin' / 'colcon'), *args)

    def build_and_test(self) -> tuple[subprocess.CompletedProcess[str], subprocess.CompletedProcess[str]]:
        built = self.colcon('build', '--event-handlers', 'console_direct+')
        assert built.returncode == 0, built.stdout + built.stderr
        tested = self.colcon('test', '--event-handlers', 'console_direct+')
        return tested, self.colcon('test-result', '--verbose')


@pytest.fixture(scope='module')
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Workspace:
    root = tmp_path_factory.mktemp('doc_ws')
    prefix = root / 'ament_nodl_prefix'
    shutil.copytree(REPO / 'ros' / 'ament_nodl' / 'cmake', prefix / 'share' / 'ament_nodl' / 'cmake')
    shutil.copy(REPO / 'ros' / 'ament_nodl' / 'cmake' / 'ament_nodl-config.cmake',
                prefix / 'share' / 'ament_nodl' / 'cmake' / 'ament_nodlConfig.cmake')
    (prefix / 'bin').mkdir()
    command = prefix / 'bin' / 'nodl'
    command.write_text(f'#!/bin/sh\nPYTHONPATH="{REPO}" exec "{sys.executable}" -m nodl "$@"\n',
                       encoding='utf-8')
    command.chmod(0o755)
    shutil.copytree(FIXTURES / 'colcon_doc', root / 'src')
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)
    env.update(AMENT_PREFIX_PATH=str(VENV), CMAKE_PREFIX_PATH=f'{prefix}{os.pathsep}{VENV}',
               PATH=os.pathsep.join([str(prefix / 'bin'), str(VENV / 'bin'), env.get('PATH', '')]),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    return Workspace(root, env)


def test_fresh_pages_pass_and_a_changed_definition_fails(workspace: Workspace) -> None:
    built = workspace.colcon('build', '--event-handlers', 'console_direct+')
    assert built.returncode == 0, built.stdout + built.stderr
    # the author writes the pages from the workspace (not the package's folder), as installed
    installed = dict(workspace.env, AMENT_PREFIX_PATH=os.pathsep.join(
        [str(workspace.root / 'install' / 'doc_checked'), str(VENV)]))
    written = workspace.run('nodl', 'doc', 'doc_checked', '-o', 'src/doc_checked/doc', env=installed)
    assert written.returncode == 0, written.stderr
    page = workspace.package / 'doc' / 'doc_checked' / 'talker.md'
    assert r'share\/doc\_checked\/nodl\/talker\.nodl\.yaml \(index\)' in page.read_text(encoding='utf-8')

    tested, result = workspace.build_and_test()
    assert tested.returncode == 0, tested.stdout + tested.stderr
    assert result.returncode == 0, result.stdout + result.stderr
    assert '0 errors, 0 failures' in result.stdout, result.stdout
    results = workspace.root / 'build' / 'doc_checked' / 'test_results' / 'doc_checked'
    assert 'nodl_doc_check' in (results / 'nodl_doc_check.xml').read_text(encoding='utf-8')

    definition = workspace.package / 'nodl' / 'talker.nodl.yaml'
    text = definition.read_text(encoding='utf-8')
    definition.write_text(text.replace('Publishes a greeting at a fixed rate.',
                                       'Publishes a greeting when asked.'), encoding='utf-8')
    before = page.read_bytes()
    tested, result = workspace.build_and_test()
    assert result.returncode != 0, result.stdout + result.stderr
    assert 'nodl_doc_check' in result.stdout and '1 failure' in result.stdout, result.stdout
    xml = (results / 'nodl_doc_check.xml').read_text(encoding='utf-8')
    assert 'doc_checked/talker.md' in xml and 'NODL275' in xml, xml
    assert page.read_bytes() == before  # --check writes nothing
