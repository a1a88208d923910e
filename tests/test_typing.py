"""The public API is typed: ``mypy --strict`` accepts the library and a consumer's script."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO

CONSUMER = FIXTURES / 'typing' / 'consumer.py'


@pytest.fixture(scope='module')
def mypy_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One mypy cache for this module's runs: the library is analysed once, not per test.

    It starts empty in every test run (never the tree's .mypy_cache), so nothing stale
    from an earlier run can hide an error.
    """
    return tmp_path_factory.mktemp('mypy') / 'cache'


def _mypy(cache: Path, *args: str) -> subprocess.CompletedProcess[str]:
    # The configuration is pyproject.toml's [tool.mypy] (strict = true).
    return subprocess.run(
        [sys.executable, '-m', 'mypy', '--config-file', str(REPO / 'pyproject.toml'),
         '--cache-dir', str(cache), *args],
        cwd=REPO, text=True, capture_output=True, timeout=600)


def test_the_configuration_is_strict() -> None:
    import tomllib

    config = tomllib.loads((REPO / 'pyproject.toml').read_text())
    assert config['tool']['mypy']['strict'] is True
    assert config['tool']['mypy']['packages'] == ['nodl', 'nodl_schema']
    assert any(r.lower().startswith('types-pyyaml')
               for r in config['project']['optional-dependencies']['test'])


def test_mypy_strict_accepts_the_library_and_a_consumer_script(mypy_cache: Path) -> None:
    # One run for both: the consumer is checked against the library as installed in the tree.
    result = _mypy(mypy_cache, '--strict', 'nodl', 'nodl_schema', str(CONSUMER))
    assert result.returncode == 0, result.stdout + result.stderr


def test_mypy_strict_catches_a_misuse_of_the_public_api(tmp_path: Path, mypy_cache: Path) -> None:
    """The consumer check can fail: a wrong use of a public name is an error."""
    script = tmp_path / 'misuse.py'
    script.write_text('from nodl import load_node\n\n'
                      'def name(path: str) -> int:\n'
                      '    return load_node(path).main\n')
    result = _mypy(mypy_cache, '--strict', str(script))
    assert result.returncode == 1
    assert 'misuse.py:4: error: Incompatible return value type' in result.stdout


def _literal_all(path: Path) -> list[str]:
    tree = ast.parse(path.read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == '__all__' for t in node.targets):
            value = ast.literal_eval(node.value)  # raises unless it is a literal
            assert isinstance(value, list)
            return value
    raise AssertionError(f'{path} has no __all__')


def test_the_root_all_is_a_literal_list_equal_to_the_lazy_exports() -> None:
    """``nodl`` is the one package that loads its names on first use (the command line
    imports it first): its ``__all__`` and the table of where each name lives agree."""
    import nodl

    names = _literal_all(Path(nodl.__file__ or ''))
    assert len(names) == len(set(names))
    assert set(names) == set(nodl._EXPORTS)
    assert sorted(names) == sorted(nodl.__all__)
    for name in names:
        assert getattr(nodl, name) is not None


@pytest.mark.parametrize('package', ['nodl.model', 'nodl.system', 'nodl.policy', 'nodl.targets'])
def test_all_is_a_literal_list_of_names_the_package_has(package: str) -> None:
    import importlib

    module = importlib.import_module(package)
    names = _literal_all(Path(module.__file__ or ''))
    assert len(names) == len(set(names))
    assert sorted(names) == sorted(module.__all__)
    for name in names:
        assert getattr(module, name) is not None


def test_the_public_names_are_imported_for_type_checkers() -> None:
    """Every name of ``nodl.__all__`` is imported under TYPE_CHECKING (so mypy knows it)."""
    tree = ast.parse((REPO / 'nodl' / '__init__.py').read_text())
    imported: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) and node.test.id == 'TYPE_CHECKING':
            for child in ast.walk(node):
                if isinstance(child, ast.ImportFrom):
                    imported.update(alias.asname or alias.name for alias in child.names)
    assert set(_literal_all(REPO / 'nodl' / '__init__.py')) <= imported


def test_the_package_is_marked_typed() -> None:
    assert (REPO / 'nodl' / 'py.typed').is_file()


def test_the_consumer_script_imports_every_public_name() -> None:
    """A name added to nodl.__all__ is type-checked as a user would use it."""
    import ast

    import nodl

    tree = ast.parse(CONSUMER.read_text(encoding='utf-8'))
    imported = {alias.asname or alias.name for node in ast.walk(tree)
                if isinstance(node, ast.ImportFrom) and node.module == 'nodl'
                for alias in node.names}
    assert sorted(set(nodl.__all__) - imported) == []
