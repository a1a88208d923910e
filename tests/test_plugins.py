"""Entry-point discovery and fault-tolerant plugin loading (nodl_schema.plugins)."""

from __future__ import annotations

import importlib.metadata
import os
import subprocess
import sys

import pytest

from conftest import FIXTURES, REPO
from nodl_schema import plugins

SITE = FIXTURES / 'plugins' / 'site'


@pytest.fixture
def fake_site(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.syspath_prepend(str(SITE))
    monkeypatch.setattr(plugins, '_cache', None)


def test_builtin_verbs_are_found_like_importlib_metadata_finds_them() -> None:
    ours = {(e.name, e.value) for e in plugins.iter_entry_points('nodl.verbs')}
    theirs = {(e.name, e.value) for e in importlib.metadata.entry_points(group='nodl.verbs')}
    assert ours == theirs
    assert ('validate', 'nodl_schema.cli.verbs.validate:ValidateVerb') in ours


def test_all_groups_agree_with_importlib_metadata() -> None:
    for group in ('console_scripts', 'ros2cli.command', 'pytest11'):
        ours = {(e.name, e.value) for e in plugins.iter_entry_points(group)}
        theirs = {(e.name, e.value) for e in importlib.metadata.entry_points(group=group)}
        assert ours == theirs, group


def test_third_party_plugins_load_and_broken_ones_are_reported(fake_site: None) -> None:
    errors: list[plugins.PluginError] = []
    loaded = plugins.load_plugins('nodl.verbs', on_error=errors.append)
    assert loaded['hello'].__name__ == 'HelloVerb'
    assert 'validate' in loaded
    assert [(e.name, e.distribution) for e in errors] == [('broken', 'broken-nodl-plugin')]
    assert 'ModuleNotFoundError' in errors[0].error
    assert "skipped plugin 'broken'" in str(errors[0])


def test_load_only_named_plugins(fake_site: None) -> None:
    assert list(plugins.load_plugins('nodl.verbs', names=['hello'])) == ['hello']


def test_other_groups_are_separate(fake_site: None) -> None:
    assert [e.name for e in plugins.iter_entry_points('some.other.group')] == ['ignored']


def _nodl(*args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, PYTHONPATH=str(SITE))
    return subprocess.run([sys.executable, '-m', 'nodl_schema', *args], cwd=REPO, env=env,
                          text=True, capture_output=True, timeout=60)


def test_cli_runs_a_third_party_verb_loading_only_that_verb() -> None:
    result = _nodl('hello', 'world')
    assert result.returncode == 0
    assert result.stdout == 'hello world\n'
    # verbs are loaded on demand: the broken plugin is not even imported
    assert 'broken' not in result.stderr


def test_a_broken_verb_is_reported_and_skipped_not_fatal() -> None:
    listed = _nodl('--help')
    assert listed.returncode == 0
    assert "warning: skipped plugin 'broken'" in listed.stderr
    assert 'validate' in listed.stdout and 'hello' in listed.stdout
    invoked = _nodl('broken')
    assert invoked.returncode == 2
    assert "warning: skipped plugin 'broken'" in invoked.stderr
    assert "invalid choice: 'broken'" in invoked.stderr
    assert 'Traceback' not in invoked.stderr


def test_help_lists_plugin_verbs_with_their_docstring() -> None:
    result = _nodl('--help')
    assert result.returncode == 0
    assert 'Say hello (a third-party verb).' in result.stdout
    assert 'validate' in result.stdout


def test_internal_error_is_one_line_asking_to_report_it() -> None:
    result = _nodl('crash')
    assert result.returncode == 3
    lines = [l for l in result.stderr.splitlines() if 'skipped plugin' not in l]
    assert len(lines) == 1
    assert 'internal error' in lines[0] and 'please report it' in lines[0]
    assert 'Traceback' not in result.stderr
