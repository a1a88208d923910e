"""`nodl schema`."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from conftest import REPO


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                          capture_output=True, timeout=60)


def test_each_kind_prints_a_self_contained_schema_with_stable_id() -> None:
    for kind in ('parameter', 'interface', 'node'):
        result = nodl('schema', kind)
        assert result.returncode == 0
        schema = json.loads(result.stdout)
        assert schema['$id'] == f'urn:nodl:schema:2:{kind}'
        refs = [line for line in result.stdout.splitlines() if '"$ref"' in line]
        assert refs and all('"#/' in line for line in refs)


def test_default_is_node() -> None:
    assert json.loads(nodl('schema').stdout)['$id'] == 'urn:nodl:schema:2:node'


def test_output_file(tmp_path: Path) -> None:
    target = tmp_path / 'interface.schema.json'
    result = nodl('schema', 'interface', '-o', str(target))
    assert result.returncode == 0 and result.stdout == ''
    assert json.loads(target.read_text())['title'] == 'NoDL interface definition'


def test_unwritable_output_is_exit_2(tmp_path: Path) -> None:
    result = nodl('schema', 'node', '-o', str(tmp_path / 'missing' / 'x.json'))
    assert result.returncode == 2
    assert 'cannot write' in result.stderr and 'Traceback' not in result.stderr
