"""nodl doc on the command line: exit statuses, --check in CI, no traceback for user errors."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from conftest import FIXTURES, REPO

DOC = FIXTURES / 'doc'


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl_schema', 'doc', *args], cwd=REPO, text=True,
                          capture_output=True, timeout=60,
                          env={**os.environ, 'AMENT_PREFIX_PATH': sys.prefix})


def test_write_then_check_then_stale_fails(tmp_path: Path) -> None:
    out = str(tmp_path / 'docs')
    written = nodl(str(DOC / 'talker.nodl.yaml'), '-o', out, '--format', 'html')
    assert written.returncode == 0, written.stderr
    assert written.stdout.split() == [f'{out}/index.html', f'{out}/talker.html']
    assert nodl(str(DOC / 'talker.nodl.yaml'), '-o', out, '--format', 'html', '--check').returncode == 0
    page = tmp_path / 'docs' / 'talker.html'
    page.write_text(page.read_text().replace('hello', 'bye'))
    stale = nodl(str(DOC / 'talker.nodl.yaml'), '-o', out, '--format', 'html', '--check')
    assert stale.returncode == 1 and '[NODL275]' in stale.stderr and 'bye' in page.read_text()


def test_user_errors_have_codes_and_no_traceback(tmp_path: Path) -> None:
    missing = nodl('no_such_package', '-o', str(tmp_path))
    assert missing.returncode == 1 and '[NODL273]' in missing.stderr
    assert 'Traceback' not in missing.stderr
    partly = nodl(str(DOC / 'talker.nodl.yaml'), 'no_such_package', '-o', str(tmp_path / 'p'))
    assert partly.returncode == 1 and (tmp_path / 'p' / 'talker.md').is_file()
    (tmp_path / 'file').write_text('')
    assert nodl(str(DOC / 'talker.nodl.yaml'), '-o', str(tmp_path / 'file')).returncode == 2
    assert nodl(str(DOC / 'system.launch.xml'), '--arg', 'nope', '-o', str(tmp_path)).returncode == 2


def test_a_page_never_replaces_its_definition(tmp_path: Path) -> None:
    definition = tmp_path / 'talker.md'
    definition.write_bytes((DOC / 'talker.nodl.yaml').read_bytes())
    # a definition file that is also where the page would go: refused, the file unchanged
    os.symlink(definition, tmp_path / 'talker.nodl.yaml')
    result = nodl(str(tmp_path / 'talker.nodl.yaml'), '-o', str(tmp_path))
    assert result.returncode == 2 and '[NODL033]' in result.stderr
    assert definition.read_bytes() == (DOC / 'talker.nodl.yaml').read_bytes()
