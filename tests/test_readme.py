"""The README stays true: its quoted command output is what the tool prints."""

from __future__ import annotations

import re
import subprocess
import sys

from conftest import REPO

README = (REPO / 'README.md').read_text(encoding='utf-8')


def test_quoted_validate_output_matches_the_tool() -> None:
    block = re.search(r'```text\n\$ nodl validate (\S+)\n(.*?)```', README, re.S)
    assert block, 'README lost its `nodl validate` example'
    path, quoted = block.group(1), block.group(2)
    result = subprocess.run([sys.executable, '-m', 'nodl_schema', 'validate', path], cwd=REPO,
                            text=True, capture_output=True, timeout=60)
    for line in quoted.splitlines():
        if line and line != '...':
            assert line in result.stdout.splitlines(), line


def test_readme_names_the_two_commands() -> None:
    assert 'make demo' in README and 'make test' in README
