"""The README stays true: its quoted command output is what the tool prints."""

from __future__ import annotations

import os
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


def test_quoted_policy_example_is_what_the_tool_writes(tmp_path) -> None:  # type: ignore[no-untyped-def]
    block = re.search(r'`(nodl policy talker\.nodl\.yaml use_sim_time:=true\s+--name /robot/talker)` '
                      r'writes:\n\n```xml\n(.*?)```', README, re.S)
    assert block, 'README lost its `nodl policy` example'
    arguments = block.group(1).split()[2:]
    fixtures = REPO / 'tests' / 'fixtures' / 'policy'
    written = subprocess.run([sys.executable, '-m', 'nodl_schema', 'policy', *arguments],
                             cwd=fixtures, env={**os.environ, 'PYTHONPATH': str(REPO)},
                             text=True, capture_output=True, timeout=60)
    assert written.returncode == 0, written.stderr
    assert written.stdout == block.group(2)
    # the check of a copy with one grant added by hand, as quoted
    check = re.search(r'`nodl policy --check policy.xml talker.nodl.yaml use_sim_time:=true --name\s+'
                      r'/robot/talker` exits 1 with:\n\n```text\n(.*?)```', README, re.S)
    assert check, 'README lost its `nodl policy --check` example'
    (tmp_path / 'talker.nodl.yaml').write_text((fixtures / 'talker.nodl.yaml').read_text())
    (tmp_path / 'policy.xml').write_text(written.stdout.replace(
        '<topic>chatter</topic>', '<topic>chatter</topic>\n            <topic>cmd_vel</topic>', 1))
    result = subprocess.run([sys.executable, '-m', 'nodl_schema', 'policy', '--check', 'policy.xml',
                             'talker.nodl.yaml', 'use_sim_time:=true', '--name', '/robot/talker'],
                            cwd=tmp_path, env={**os.environ, 'PYTHONPATH': str(REPO)},
                            text=True, capture_output=True, timeout=60)
    assert result.returncode == 1
    assert result.stdout + result.stderr == check.group(1)
