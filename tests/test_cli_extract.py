"""``nodl extract``: drafts printed or written (overlay layout, one file), --diff, formats, exit statuses."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from conftest import REPO

FIXTURES = REPO / 'tests' / 'fixtures' / 'extract' / 'python'


def _run(*args: str, cwd: Path = REPO) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl_schema', 'extract', *args], cwd=cwd, text=True,
                          capture_output=True, timeout=60, env={**os.environ, 'PYTHONPATH': str(REPO)})


def test_overlay_layout_and_drafts_that_validate(tmp_path: Path) -> None:
    result = _run(str(FIXTURES / 'pkg'), '-o', str(tmp_path / 'out'))
    assert result.returncode == 0, result.stderr
    talker = tmp_path / 'out' / 'demo_pkg' / 'talker.nodl.yaml'
    assert talker.is_file() and (tmp_path / 'out' / 'demo_pkg' / 'pair__pair_server.nodl.yaml').is_file()
    text = talker.read_text(encoding='utf-8')
    assert 'by nodl extract' in text and 'nodl: generated; sha256=' in text
    check = subprocess.run([sys.executable, '-m', 'nodl_schema', 'validate', '--strict', str(talker)], cwd=REPO,
                           text=True, capture_output=True, timeout=60)
    assert check.returncode == 0, check.stdout
    # a draft edited by the user is never replaced without --force
    talker.write_text(text + '# mine\n', encoding='utf-8')
    refused = _run(str(FIXTURES / 'pkg'), '-o', str(tmp_path / 'out'))
    assert refused.returncode == 2 and 'NODL032' in refused.stdout
    assert talker.read_text(encoding='utf-8').endswith('# mine\n')
    assert _run(str(FIXTURES / 'pkg'), '-o', str(tmp_path / 'out'), '--force').returncode == 0


def test_one_file_output_needs_one_node(tmp_path: Path) -> None:
    one = _run(str(FIXTURES / 'real' / 'demo_nodes_py__talker.py'), '-o', str(tmp_path / 'talker.nodl.yaml'))
    assert one.returncode == 0 and (tmp_path / 'talker.nodl.yaml').is_file()
    several = _run(str(FIXTURES / 'real' / 'demo_nodes_py__introspection.py'), '-o', str(tmp_path / 'x.yaml'))
    assert several.returncode == 2 and 'NODL913' in several.stdout and not (tmp_path / 'x.yaml').exists()


def test_printed_draft_and_gaps_on_stderr() -> None:
    result = _run('tests/fixtures/extract/python/real/demo_nodes_py__talker_qos.py')
    assert result.returncode == 0
    assert result.stdout.startswith('# Extracted from tests/fixtures/extract/python/real/demo_nodes_py__talker_qos.py')
    assert 'NODL903' in result.stderr and '# GAP' in result.stdout
    assert _run('tests/fixtures/extract/python/real/demo_nodes_py__talker_qos.py', '--strict').returncode == 1


def test_diff_as_json_and_sarif(tmp_path: Path) -> None:
    definition = tmp_path / 'talker.nodl.yaml'
    definition.write_text('nodl_version: 2\nmain:\n  nodl_version: 2\n  publishers:\n    - name: chatter\n'
                          '      type: std_msgs/msg/Int32\n      qos: {history: KEEP_LAST, depth: 10, '
                          'reliability: RELIABLE}\n', encoding='utf-8')
    source = str(FIXTURES / 'real' / 'demo_nodes_py__talker.py')
    result = _run(source, '--diff', str(definition), '--format', 'json')
    assert result.returncode == 1
    assert [d['code'] for d in json.loads(result.stdout) if d['severity'] == 'error'] == ['NODL922']
    sarif = json.loads(_run(source, '--diff', str(definition), '--format', 'sarif').stdout)
    assert sarif['runs'][0]['results'][0]['ruleId'] == 'NODL922'
    same = tmp_path / 'same.nodl.yaml'
    same.write_text(definition.read_text(encoding='utf-8').replace('Int32', 'String'), encoding='utf-8')
    assert _run(source, '--diff', str(same)).returncode == 0
    junit = _run(source, '--diff', str(definition), '--format', 'junit')
    assert '<testsuite' in junit.stdout and 'NODL922' in junit.stdout


def test_bad_paths_and_sources_never_a_traceback(tmp_path: Path) -> None:
    missing = _run(str(tmp_path / 'nope'))
    assert missing.returncode == 2 and 'NODL020' in missing.stderr and 'Traceback' not in missing.stderr
    broken = _run(str(FIXTURES / 'cases' / 'syntax_error.py'), str(FIXTURES / 'real' / 'demo_nodes_py__talker.py'))
    assert broken.returncode == 1 and 'NODL906' in broken.stderr and 'Traceback' not in broken.stderr
    (tmp_path / 'util.py').write_text('x = 1\n', encoding='utf-8')
    nothing = _run(str(tmp_path))
    assert nothing.returncode == 2 and 'NODL912' in nothing.stderr
