"""Mixin references and their resolvers (nodl.composition.resolvers and plugins)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl import plugins
from nodl.composition import ResolutionError, ResolveContext, compose, load_resolvers
from nodl.composition.path_resolver import PathResolver
from nodl.composition.resolvers import RESOLVER_GROUP, package_root, scheme_of
from nodl.registry.nodl_resolver import AmentIndexResolver

SITE = FIXTURES / 'composition' / 'site'


@pytest.fixture
def resolver_site(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.syspath_prepend(str(SITE))
    monkeypatch.setattr(plugins, '_cache', None)


@pytest.mark.parametrize('reference, scheme', [
    ('nodl://pkg/name', 'nodl'),
    ('file://sub/x.nodl.yaml', 'file'),
    ('x.nodl.yaml', 'file'),
    ('../x.nodl.yaml', 'file'),
    ('sub/dir/x.nodl.yaml', 'file'),
    ('foo://x', 'foo'),
    ('git+https://example.org/x', 'git+https'),
    ('a.b-c://x', 'a.b-c'),
    ('1abc://x', 'file'),      # a scheme starts with a letter
    ('http:/x', 'file'),       # no ://
    ('C:\\nodl\\x.yaml', 'file'),
    ('x://', 'x'),
])
def test_scheme_of(reference: str, scheme: str) -> None:
    assert scheme_of(reference) == scheme


def test_package_root_is_the_nearest_folder_with_a_package_xml(tmp_path: Path) -> None:
    outer = tmp_path / 'ws' / 'outer'
    inner = outer / 'sub' / 'inner'
    deep = inner / 'nodl' / 'deeper'
    deep.mkdir(parents=True)
    (outer / 'package.xml').write_text('<package/>')
    assert package_root(str(deep)) == str(outer)
    (inner / 'package.xml').write_text('<package/>')
    assert package_root(str(deep)) == str(inner)
    assert package_root(str(inner)) == str(inner)
    assert package_root(str(outer / 'sub')) == str(outer)


def test_package_root_is_none_without_a_package_xml(tmp_path: Path) -> None:
    (tmp_path / 'a' / 'b').mkdir(parents=True)
    if any((parent / 'package.xml').is_file() for parent in tmp_path.parents):
        pytest.fail(f'the temporary folder {tmp_path} is inside a package; cannot test')
    assert package_root(str(tmp_path / 'a' / 'b')) is None


def test_package_root_of_a_relative_start(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    (tmp_path / 'pkg' / 'nodl').mkdir(parents=True)
    (tmp_path / 'pkg' / 'package.xml').write_text('<package/>')
    monkeypatch.chdir(tmp_path / 'pkg')
    assert package_root('nodl') == str(tmp_path / 'pkg')


def test_the_fixture_packages_have_their_roots() -> None:
    assert package_root(str(FIXTURES / 'composition' / 'errors' / 'pkg' / 'nodl')) == str(
        FIXTURES / 'composition' / 'errors' / 'pkg')


def test_builtin_resolvers_are_found_through_entry_points() -> None:
    specs = {spec.name: spec.value for spec in plugins.iter_entry_points(RESOLVER_GROUP)}
    assert specs['nodl'] == 'nodl.registry.nodl_resolver:AmentIndexResolver'
    assert specs['file'] == 'nodl.composition.path_resolver:PathResolver'
    resolvers = load_resolvers()
    assert isinstance(resolvers['nodl'], AmentIndexResolver)
    assert isinstance(resolvers['file'], PathResolver)


def test_third_party_resolvers_load_and_broken_ones_are_reported(
        resolver_site: None, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    errors: list[plugins.PluginError] = []
    resolvers = load_resolvers(on_error=errors.append)
    assert {'nodl', 'file', 'mem'} <= set(resolvers)
    assert 'broken_factory' not in resolvers and 'missing_module' not in resolvers
    assert [(e.name, e.distribution) for e in errors] == [
        ('missing_module', 'third-party-resolvers'), ('broken_factory', 'third-party-resolvers')]
    assert 'ModuleNotFoundError' in errors[0].error
    assert errors[1].error == 'RuntimeError: cannot construct'
    # without on_error the library prints nothing: the errors wait for take_plugin_errors()
    # (the nodl command prints them), each once however often the resolvers are loaded
    monkeypatch.setattr(plugins, '_pending', [])
    monkeypatch.setattr(plugins, '_kept', set())
    load_resolvers()
    load_resolvers()
    assert capsys.readouterr() == ('', '')
    kept = plugins.take_plugin_errors()
    assert [(e.name, e.group) for e in kept] == [('missing_module', 'nodl.resolvers'),
                                                 ('broken_factory', 'nodl.resolvers')]
    assert "warning: skipped plugin 'broken_factory' of group 'nodl.resolvers'" in str(kept[1])
    assert plugins.take_plugin_errors() == []


def test_a_third_party_scheme_is_used_by_compose(resolver_site: None) -> None:
    composed = compose('nodl_version: 2\nmixins: [mem://gain]\nmain: {nodl_version: 2}\n')
    assert composed.interface.parameters['gain'].default_value == 1.5
    assert composed.interface.parameters['gain'].origin == 'mem://gain'


def test_a_third_party_resolution_error_is_placed_at_the_mixin(resolver_site: None) -> None:
    from nodl import ValidationError

    with pytest.raises(ValidationError) as exc:
        compose('nodl_version: 2\nmixins:\n  - mem://nope\nmain: {nodl_version: 2}\n')
    [error] = exc.value.errors
    assert (error.line, error.column) == (3, 5)
    assert error.message == ("cannot resolve mixin 'mem://nope': no document 'nope' in memory "
                             '(searched: memory:nope)')


def test_validate_resolve_uses_plugin_resolvers_in_a_real_process() -> None:
    import os

    env = dict(os.environ, PYTHONPATH=str(SITE))
    node = FIXTURES / 'composition' / 'site_node.nodl.yaml'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--resolve',
                             str(node)], cwd=REPO, env=env, text=True, capture_output=True,
                            timeout=60)
    assert result.returncode == 1, result.stdout + result.stderr
    assert f"{node}:5:5: error: cannot resolve mixin 'mem://nope'" in result.stdout
    assert ':4:5:' not in result.stdout  # mem://gain resolved
    # the command prints what the library skipped, one line per broken plugin (not per file)
    assert result.stderr.count("skipped plugin 'missing_module'") == 1
    assert result.stderr.count("skipped plugin 'broken_factory'") == 1


def test_resolution_error_carries_what_was_searched() -> None:
    exc = ResolutionError('gone', ['/a', '/b'])
    assert (exc.message, exc.searched, str(exc)) == ('gone', ['/a', '/b'], 'gone')
    assert ResolutionError('x').searched == []


def test_ament_resolver_refuses_a_malformed_reference() -> None:
    with pytest.raises(ResolutionError) as exc:
        AmentIndexResolver().resolve('nodl://Bad/name', ResolveContext(None, None))
    assert 'is not of the form nodl://<package>/<name>' in exc.value.message


def test_path_resolver_errors(tmp_path: Path) -> None:
    node = tmp_path / 'node.nodl.yaml'
    node.write_text('')
    context = ResolveContext(str(node), str(tmp_path))
    with pytest.raises(ResolutionError) as exc:
        PathResolver().resolve('nope.nodl.yaml', context)
    assert exc.value.searched == [str(tmp_path / 'nope.nodl.yaml')]
    with pytest.raises(ResolutionError) as exc:
        PathResolver().resolve('../x.nodl.yaml', context)
    assert 'leaves the package directory' in exc.value.message
    (tmp_path / 'folder.nodl.yaml').mkdir()
    with pytest.raises(ResolutionError) as exc:
        PathResolver().resolve('folder.nodl.yaml', context)
    assert f'no file {tmp_path / "folder.nodl.yaml"}' in exc.value.message
    with pytest.raises(ResolutionError) as exc:
        PathResolver().resolve('x.nodl.yaml', ResolveContext(None, None))
    assert 'needs the location of the node file' in exc.value.message
