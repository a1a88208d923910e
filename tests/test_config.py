"""nodl.toml / [tool.nodl] configuration (nodl.config) and overrides (nodl.overrides)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from nodl.config import ConfigCache, ConfigError, find_config_file, load_config
from nodl.diagnostics import Diagnostic, Severity
from nodl.overrides import Overrides, apply_directives, apply_overrides, directive_codes

REPO = Path(__file__).resolve().parent.parent
WARN = Diagnostic(Severity.WARNING, 'w', (), 'f', 1, 1, code='NODL216')
SHORT = Diagnostic(Severity.WARNING, 's', (), 'f', 2, 1, code='NODL205')
ERR = Diagnostic(Severity.ERROR, 'e', (), 'f', 3, 1, code='NODL101')
INTERFACE = ('nodl_version: 2\npublishers:\n  - name: chatter\n    type: std_msgs/String\n'
             '    qos: {history: KEEP_LAST, depth: 1, reliability: RELIABLE}\n')


def test_overrides_drop_and_promote_and_the_stronger_wins() -> None:
    out = apply_overrides([WARN, SHORT, ERR], Overrides(ignore=['NODL216'], error=['NODL205']))
    assert [(d.code, d.severity) for d in out] == [('NODL205', 'error'), ('NODL101', 'error')]
    merged = Overrides(ignore=['NODL205'], error=['NODL216']).then(Overrides(error=['NODL205']))
    assert merged == Overrides(error=['NODL216', 'NODL205'])


def test_directives_only_in_leading_comments_and_never_for_errors() -> None:
    assert directive_codes('# nodl: ignore=NODL216, nodl205 (why)\nx: 1\n') == {'NODL216', 'NODL205'}
    assert directive_codes('x: 1\n# nodl: ignore=NODL216\n') == frozenset()
    text = '# nodl: ignore=NODL216,NODL101\n'
    (kept,) = apply_directives(text, [WARN, ERR])
    assert (kept.code, kept.severity, kept.line) == (ERR.code, ERR.severity, ERR.line)
    assert kept.message.startswith(ERR.message)
    assert "'# nodl: ignore=NODL101' does not silence it" in kept.message
    assert apply_directives('# nodl: ignore=NODL216\n', [ERR]) == [ERR]  # not named: as it is


def test_a_directive_cannot_hide_a_trojan_source_error(tmp_path: Path) -> None:
    """'# nodl: ignore=NODL219,NODL220' in a hostile definition silences neither (errors: a file
    cannot hide its own), and says so; --ignore does, as the README says."""
    from nodl.loading import check_source

    hostile = Path(__file__).parent / 'fixtures' / 'text_safety' / 'hostile.nodl.yaml'
    path = tmp_path / 'hostile.nodl.yaml'
    path.write_text('# nodl: ignore=NODL219,NODL220\n' + hostile.read_text(encoding='utf-8'),
                    encoding='utf-8')
    found = check_source(path).diagnostics
    assert {d.code for d in found} == {'NODL219', 'NODL220'}
    assert all('does not silence it' in d.message for d in found)
    assert apply_overrides(found, Overrides(ignore=['NODL219', 'NODL220'])) == []


def test_found_upward_nodl_toml_first_and_pyproject_without_table_passed_over(tmp_path: Path) -> None:
    (tmp_path / 'pyproject.toml').write_text('[tool.nodl]\nerror = ["nodl205"]\n', encoding='utf-8')
    inner = tmp_path / 'pkg' / 'nodl'
    inner.mkdir(parents=True)
    (tmp_path / 'pkg' / 'pyproject.toml').write_text('[project]\nname = "x"\n', encoding='utf-8')
    assert find_config_file(str(inner)) == str(tmp_path / 'pyproject.toml')
    assert load_config(str(tmp_path / 'pyproject.toml')) == Overrides(error=['NODL205'])
    (tmp_path / 'pkg' / 'nodl.toml').write_text('ignore = ["NODL216"]\n', encoding='utf-8')
    assert ConfigCache().overrides_for(str(inner / 'a.nodl.yaml')) == Overrides(ignore=['NODL216'])


@pytest.mark.parametrize('text, message', [
    ('ignor = ["NODL216"]\n', "unknown key 'ignor'; did you mean 'ignore'?"),
    ('ignore = "NODL216"\n', "'ignore' must be a list of codes"),
    ('error = ["NODL2166"]\n', "unknown code 'NODL2166' in 'error'; did you mean 'NODL216'?"),
    ('ignore = ["NODL216"]\nerror = ["NODL216"]\n', 'NODL216 is both ignored and an error'),
    ('ignore = [\n', 'invalid TOML'),
])
def test_bad_configuration_is_one_clear_line(tmp_path: Path, text: str, message: str) -> None:
    config = tmp_path / 'nodl.toml'
    config.write_text(text, encoding='utf-8')
    with pytest.raises(ConfigError) as info:
        load_config(str(config))
    assert str(info.value).startswith(f'{config}: error: ')
    assert message in str(info.value)


def _nodl(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=60)


def test_validate_applies_configuration_and_the_command_line_wins(tmp_path: Path) -> None:
    (tmp_path / 'a.nodl.yaml').write_text(INTERFACE, encoding='utf-8')
    (tmp_path / 'nodl.toml').write_text('ignore = ["NODL216"]\n', encoding='utf-8')
    result = _nodl('validate', '--strict', 'a.nodl.yaml', cwd=tmp_path)
    assert result.returncode == 1
    assert '[NODL205]' in result.stdout and '[NODL216]' not in result.stdout
    result = _nodl('validate', '--strict', '--ignore', 'nodl205', 'a.nodl.yaml', cwd=tmp_path)
    assert (result.returncode, result.stdout.splitlines()[-1]) == (0, '1 file, 0 errors, 0 warnings')
    result = _nodl('validate', '--error', 'NODL216,NODL205', 'a.nodl.yaml', cwd=tmp_path)
    assert result.returncode == 1 and '2 errors' in result.stdout


def test_unknown_codes_and_bad_files_are_usage_errors(tmp_path: Path) -> None:
    (tmp_path / 'a.nodl.yaml').write_text(INTERFACE, encoding='utf-8')
    result = _nodl('validate', '--ignore', 'NODL21', 'a.nodl.yaml', cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith("nodl validate: error: unknown code 'NODL21' for --ignore; "
                                    "did you mean 'NODL21")
    (tmp_path / 'nodl.toml').write_text('ignor = []\n', encoding='utf-8')
    result = _nodl('validate', 'a.nodl.yaml', cwd=tmp_path)
    assert result.returncode == 2 and 'Traceback' not in result.stderr
    assert "unknown key 'ignor'; did you mean 'ignore'?" in result.stderr
