"""Entry-point discovery and fault-tolerant plugin loading (nodl.plugins)."""

from __future__ import annotations

import importlib.metadata
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl import plugins

SITE = FIXTURES / 'plugins' / 'site'


@pytest.fixture
def fake_site(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.syspath_prepend(str(SITE))
    monkeypatch.setattr(plugins, '_cache', None)


def test_builtin_verbs_are_found_like_importlib_metadata_finds_them() -> None:
    ours = {(e.name, e.value) for e in plugins.iter_entry_points('nodl.verbs')}
    theirs = {(e.name, e.value) for e in importlib.metadata.entry_points(group='nodl.verbs')}
    assert ours == theirs
    assert ('validate', 'nodl.cli.verbs.validate:ValidateVerb') in ours


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
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, env=env,
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
    lines = [line for line in result.stderr.splitlines() if 'skipped plugin' not in line]
    assert len(lines) == 1
    assert 'internal error' in lines[0] and 'please report it' in lines[0]
    assert 'Traceback' not in result.stderr


# --------------------------------------------------------------------------
# Extension points: versions, priorities, the blocklist

VERSIONED = FIXTURES / 'plugins' / 'versioned_plugin'


@pytest.fixture(scope='module')
def versioned_site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The versioned plug-in package, installed by a real pip install into a temporary target."""
    root = tmp_path_factory.mktemp('versioned')
    source = root / 'source'
    shutil.copytree(VERSIONED, source)
    target = root / 'site'
    result = subprocess.run(
        [sys.executable, '-m', 'pip', 'install', '--no-deps', '--no-build-isolation', '--no-index',
         '--disable-pip-version-check', '--target', str(target), str(source)],
        cwd=root, text=True, capture_output=True, timeout=180,
        env={k: v for k, v in os.environ.items() if k != 'PIP_REQUIRE_VIRTUALENV'})
    assert result.returncode == 0, result.stdout + result.stderr
    return target


@pytest.fixture
def versioned(versioned_site: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.syspath_prepend(str(versioned_site))
    monkeypatch.setattr(plugins, '_cache', None)
    monkeypatch.delenv(plugins.BLOCKLIST_VARIABLE, raising=False)
    return versioned_site


def test_incompatible_versions_are_reported_and_skipped(versioned: Path) -> None:
    errors: list[plugins.PluginError] = []
    loaded = plugins.load_plugins('nodl.verbs', on_error=errors.append)
    assert {'greet', 'shout', 'validate'} <= set(loaded)
    assert sorted((e.name, e.distribution) for e in errors) == [
        ('future', 'nodl-versioned-plugin'), ('newer_minor', 'nodl-versioned-plugin')]
    future = next(e for e in errors if e.name == 'future')
    assert 'version 2.0 of the nodl.verbs extension point; this toolkit provides 1.0' in future.error


def test_extensions_are_ordered_by_priority_then_name(versioned: Path) -> None:
    names = list(plugins.load_plugins('nodl.verbs', on_error=lambda e: None))
    assert names[0] == 'shout'  # PRIORITY 200
    assert names[1:] == sorted(names[1:])


def test_instances_know_their_group_and_name(versioned: Path) -> None:
    verbs = plugins.instantiate_extensions('nodl.verbs', names=['greet'])
    assert (verbs['greet'].EXTENSION_GROUP, verbs['greet'].EXTENSION_NAME) == ('nodl.verbs', 'greet')
    resolvers = plugins.instantiate_extensions('nodl.resolvers')
    assert resolvers['echo'].EXTENSION_NAME == 'echo'


def test_a_third_party_resolver_extension_is_used_by_compose(versioned: Path) -> None:
    from nodl import compose

    composed = compose('nodl_version: 2\nmixins: [echo://hello]\nmain: {nodl_version: 2}\n')
    assert composed.interface is not None


def test_blocklist_leaves_out_one_extension_or_a_group(versioned: Path,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(plugins.BLOCKLIST_VARIABLE, f'nodl.verbs.greet{os.pathsep}nodl.verbs.future')
    names = {e.name for e in plugins.iter_entry_points('nodl.verbs')}
    assert 'greet' not in names and 'future' not in names and 'shout' in names
    assert 'greet' in {e.name for e in plugins.iter_entry_points('nodl.verbs', include_blocked=True)}
    assert plugins.is_blocked('nodl.verbs', 'greet') and not plugins.is_blocked('nodl.verbs', 'shout')
    monkeypatch.setenv(plugins.BLOCKLIST_VARIABLE, 'nodl.resolvers, nodl.verbs.newer_minor')
    assert plugins.iter_entry_points('nodl.resolvers') == []
    assert plugins.load_plugins('nodl.resolvers') == {}
    errors: list[plugins.PluginError] = []
    plugins.load_plugins('nodl.verbs', on_error=errors.append)
    assert [e.name for e in errors] == ['future']


def _nodl_with(site: Path, *args: str, **env: str) -> subprocess.CompletedProcess[str]:
    environment = {k: v for k, v in os.environ.items() if k != plugins.BLOCKLIST_VARIABLE}
    environment.update(PYTHONPATH=str(site), **env)
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, env=environment,
                          text=True, capture_output=True, timeout=60)


def test_cli_runs_an_installed_versioned_verb(versioned_site: Path) -> None:
    result = _nodl_with(versioned_site, 'greet', 'ada')
    assert result.returncode == 0, result.stderr
    assert result.stdout == 'greetings, ada (I am greet of nodl.verbs)\n'
    assert result.stderr == ''  # only the chosen verb is loaded: no warning about the others


def test_cli_reports_an_incompatible_verb_in_one_line(versioned_site: Path) -> None:
    listed = _nodl_with(versioned_site, '--help')
    assert listed.returncode == 0
    assert 'greet' in listed.stdout and 'future' not in listed.stdout.split('verbs:')[-1]
    assert "warning: skipped plugin 'future' of group 'nodl.verbs' (from nodl-versioned-plugin): " \
           'it implements version 2.0' in listed.stderr
    invoked = _nodl_with(versioned_site, 'future')
    assert invoked.returncode == 2 and 'Traceback' not in invoked.stderr


def test_cli_honours_the_blocklist(versioned_site: Path) -> None:
    blocked = _nodl_with(versioned_site, 'greet', 'ada', NODL_EXTENSION_BLOCKLIST='nodl.verbs.greet')
    assert blocked.returncode == 2
    assert "invalid choice: 'greet'" in blocked.stderr
    builtin = _nodl_with(versioned_site, 'schema', NODL_EXTENSION_BLOCKLIST='nodl.verbs.schema')
    assert builtin.returncode == 2


def test_plugins_in_a_zip_archive_are_found_through_importlib_metadata(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    archive = tmp_path / 'plugins.zip'
    with zipfile.ZipFile(archive, 'w') as zf:
        zf.writestr('zipped_nodl-1.0.dist-info/METADATA', 'Metadata-Version: 2.1\nName: zipped-nodl\n'
                    'Version: 1.0\n')
        zf.writestr('zipped_nodl-1.0.dist-info/entry_points.txt',
                    '[nodl.verbs]\nzipped = zipped_verb:ZippedVerb\n')
        zf.writestr('zipped_verb.py', 'class ZippedVerb:\n    """Zipped."""\n\n'
                    '    def main(self, args):\n        return 0\n')
    monkeypatch.syspath_prepend(str(archive))
    monkeypatch.setattr(plugins, '_cache', None)
    [spec] = [e for e in plugins.iter_entry_points('nodl.verbs') if e.name == 'zipped']
    assert spec.distribution == 'zipped-nodl'
    assert plugins.load_plugins('nodl.verbs', names=['zipped'])['zipped'].__doc__ == 'Zipped.'


@pytest.mark.parametrize(('version', 'caret', 'ok'), [
    ('1.0', '^1.0', True), ('1.3', '^1.2', True), ('1.1', '^1.2', False), ('2.0', '^1.0', False),
    ('1.0.4', '^1.0', True), ('0.9', '^1.0', False),
])
def test_satisfies_version(version: str, caret: str, ok: bool) -> None:
    assert plugins.satisfies_version(version, caret) is ok


def test_satisfies_version_refuses_what_is_not_a_caret_range() -> None:
    with pytest.raises(ValueError):
        plugins.satisfies_version('1.0', '1.0')
    with pytest.raises(ValueError):
        plugins.satisfies_version('one', '^1.0')


@pytest.mark.parametrize('group', sorted(plugins.EXTENSION_POINTS))
def test_each_extension_point_has_a_base_class_of_its_version(group: str) -> None:
    spec = plugins.EXTENSION_POINTS[group]
    base = spec.base_class()
    assert issubclass(base, plugins.ExtensionPoint)
    if spec.base is not None:
        assert spec.version == base.EXTENSION_POINT_VERSION  # type: ignore[attr-defined]


@pytest.mark.parametrize('group', ['nodl.verbs', 'nodl.resolvers'])
def test_builtins_are_extensions_of_their_point(group: str) -> None:
    base = plugins.EXTENSION_POINTS[group].base_class()
    loaded = plugins.load_plugins(group)
    assert loaded
    for name, cls in loaded.items():
        assert issubclass(cls, base), name


def test_readme_documents_every_extension_point() -> None:
    from site_pages import docs_text

    readme = docs_text()
    assert plugins.BLOCKLIST_VARIABLE in readme
    for group, spec in plugins.EXTENSION_POINTS.items():
        assert f'`{group}`' in readme, group
        # the base class the README names for the group is the one extensions must subclass
        base = (spec.base or 'nodl.plugins:ExtensionPoint').replace(':', '.')
        rows = [line for line in readme.splitlines() if line.startswith('| ') and f'`{group}`' in line]
        assert len(rows) == 1 and f'`{base}`' in rows[0], (group, base, rows)


BROKEN_EXTENSIONS = FIXTURES / 'plugins' / 'broken_extensions'


def test_a_broken_generator_and_check_are_reported_and_skipped(tmp_path: Path) -> None:
    """Plug-ins loaded by the library (not the command): the command reports them, once."""
    generated = _nodl_with(BROKEN_EXTENSIONS, 'generate', str(FIXTURES / 'generate' / 'talker.nodl.yaml'),
                           '--language', 'python', '-o', str(tmp_path))
    assert generated.returncode == 0, generated.stderr
    assert (tmp_path / 'talker_base.py').is_file()
    assert generated.stderr.count("warning: skipped plugin 'gone' of group 'nodl.generators' "
                                  '(from broken-nodl-extensions): ModuleNotFoundError') == 1
    analysed = _nodl_with(BROKEN_EXTENSIONS, 'analyse',
                          str(FIXTURES / 'analysis' / 'launch' / 'system.launch.xml'))
    assert 'Traceback' not in analysed.stderr
    assert "check 'exploding' (module_that_does_not_exist:Check) skipped: ModuleNotFoundError" \
        in analysed.stdout + analysed.stderr
    assert '[NODL567]' in analysed.stdout + analysed.stderr
