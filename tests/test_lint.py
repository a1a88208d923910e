"""The project's lint: ``ruff check`` with pyproject.toml's ``[tool.ruff]`` finds nothing.

The configuration chooses the files (the toolkit, its tests, benchmarks, tools and examples;
not tests/fixtures) and the rules; these tests run the real ruff of the environment on the tree.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from conftest import REPO

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

#: The rule families the project promises to keep at zero findings (issue 16).
REQUIRED_RULES = {'E', 'F', 'W', 'B', 'UP', 'I', 'SIM'}
#: The folders the lint covers.
LINTED = {'nodl', 'nodl_schema', 'tests', 'bench', 'tools', 'examples'}


def _ruff(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess[str]:
    # From the root, so that ruff reads pyproject.toml there; no cache written into the tree.
    return subprocess.run([sys.executable, '-m', 'ruff', 'check', '--no-cache', *args], cwd=REPO,
                          input=stdin, capture_output=True, text=True, timeout=120)


def test_ruff_finds_nothing() -> None:
    lint = _ruff('--output-format', 'concise')
    assert lint.returncode == 0, (
        'ruff check found problems (run `.venv/bin/ruff check` at the root; `--fix` applies the '
        'safe fixes):\n' + lint.stdout + lint.stderr)


def test_the_configuration_covers_the_code_and_keeps_the_rules() -> None:
    settings = tomllib.loads((REPO / 'pyproject.toml').read_text(encoding='utf-8'))['tool']['ruff']
    assert set(settings['lint']['select']) >= REQUIRED_RULES
    assert not settings['lint'].get('ignore'), 'a rule ignored everywhere: prefer fixing or a per-file reason'
    listed = _ruff('--show-files')
    assert listed.returncode == 0, listed.stderr
    files = [line.strip() for line in listed.stdout.splitlines() if line.strip()]
    folders = {Path(file).relative_to(REPO).parts[0] for file in files}
    assert folders == LINTED
    assert str(REPO / 'tests' / 'test_lint.py') in files
    assert not [file for file in files if '/tests/fixtures/' in file]


def test_a_finding_fails_the_lint() -> None:
    # The same configuration on a module of the toolkit with an unused import and unsorted imports.
    lint = _ruff('--output-format', 'concise', '--stdin-filename', 'nodl/_lint_probe.py',
                 stdin='import sys\nimport os\n\nprint(os.sep)\n')
    assert lint.returncode == 1
    assert 'F401' in lint.stdout and 'I001' in lint.stdout, lint.stdout
