"""nodl doc on the command line: exit statuses, --check in CI, no traceback for user errors."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

from conftest import FIXTURES, REPO

DOC = FIXTURES / 'doc'


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl', 'doc', *args], cwd=REPO, text=True,
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


def test_rosdoc2_builds_the_pages_of_a_package_doc_folder(tmp_path: Path) -> None:
    """A real `rosdoc2 build --package-path` (rosdoc2 0.2.1) of a package whose doc/ holds
    what `nodl doc` wrote: the node page is in the site, linked from its index.  Offline: any
    HTTP request would go to a closed port on loopback, and none is made."""
    package = tmp_path / 'greeter'
    shutil.copytree(DOC / 'rosdoc2_pkg', package)
    written = nodl(str(DOC / 'talker.nodl.yaml'), '-o', str(package / 'doc'))
    assert written.returncode == 0, written.stderr
    closed = 'http://127.0.0.1:9'
    env = {**os.environ, 'AMENT_PREFIX_PATH': sys.prefix, 'http_proxy': closed,
           'https_proxy': closed, 'HTTP_PROXY': closed, 'HTTPS_PROXY': closed, 'no_proxy': ''}
    built = subprocess.run([str(Path(sys.prefix) / 'bin' / 'rosdoc2'), 'build', '--package-path',
                            str(package), '--output-directory', str(tmp_path / 'site'),
                            '--doc-build-directory', str(tmp_path / 'build'),
                            '--cross-reference-directory', str(tmp_path / 'xref')],
                           cwd=tmp_path, env=env, text=True, capture_output=True, timeout=120)
    log = built.stdout + built.stderr
    assert built.returncode == 0, log
    assert 'build succeeded' in log and 'WARNING' not in log, log
    assert 'intersphinx' not in log.replace('enabling intersphinx', '').replace(
        'extending intersphinx mapping', ''), log  # no inventory fetched (nor failing to be)
    site = tmp_path / 'site' / 'greeter'
    page = (site / 'user_docs' / 'talker.html').read_text(encoding='utf-8')
    assert 'Publishes a greeting at a fixed rate.' in page
    assert 'std_msgs/msg/String' in page and 'id="node-talker"' in page
    assert 'Greetings per second.' in page  # the parameter table
    assert 'user_docs/talker.html' in (site / 'user_docs.html').read_text(encoding='utf-8')
