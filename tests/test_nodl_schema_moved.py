"""The toolkit's former paths (``nodl_schema.X``) still work, for one release, as ``nodl.X``.

The library moved to :mod:`nodl`; ``nodl_schema`` is now the name of the reference
implementation's package, whose own module names are not redirected.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from conftest import REPO


def run(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-W', 'always::DeprecationWarning', '-c', code],
                          cwd=REPO, capture_output=True, text=True, timeout=60)


def test_a_former_module_path_is_the_new_module_with_a_warning() -> None:
    done = run('import nodl_schema.loading as old, nodl.loading as new; print(old is new)\n'
               'from nodl_schema.cli.main import main; import nodl.cli.main as m; '
               'print(main is m.main)')
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ['True', 'True']
    assert 'DeprecationWarning: nodl_schema.loading moved to nodl.loading' in done.stderr
    assert 'nodl_schema.cli.main moved to nodl.cli.main' in done.stderr


def test_a_former_top_level_name_warns_and_is_the_new_one() -> None:
    done = run('import nodl, nodl_schema\nprint(nodl_schema.load_node is nodl.load_node)')
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == 'True'
    assert 'nodl_schema.load_node moved to nodl.load_node' in done.stderr


@pytest.mark.parametrize('module', ['models', 'composition', 'loader', 'validation', 'rewrite'])
def test_the_reference_modules_are_not_redirected(module: str) -> None:
    done = run(f'import importlib, nodl\nm = importlib.import_module("nodl_schema.{module}")\n'
               'print(m.__name__, m is getattr(nodl, m.__name__.split(".")[-1], None))')
    # either the compatibility package's own module, or not there: never nodl's
    if done.returncode == 0:
        assert done.stdout.split() == [f'nodl_schema.{module}', 'False']
    else:
        assert 'ModuleNotFoundError' in done.stderr
    assert 'moved to nodl' not in done.stderr


def test_an_unknown_name_is_an_attribute_error() -> None:
    done = run('import nodl_schema\nnodl_schema.no_such_thing')
    assert done.returncode == 1
    assert "AttributeError: module 'nodl_schema' has no attribute 'no_such_thing'" in done.stderr
