"""Live-graph UX of `describe` and `check`, against real nodes in real processes: shared names,
"did you mean", an empty graph, a base mismatch summarised in one line."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from conftest import REPO


def nodl(*args: str, timeout: float = 90) -> subprocess.CompletedProcess[str]:
    result = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                            capture_output=True, timeout=timeout)
    assert 'Traceback' not in result.stderr, result.stderr
    return result


def test_describe_all_on_an_empty_graph_says_so_and_exits_2(tmp_path: Path) -> None:
    result = nodl('describe', '--all', '-o', str(tmp_path / 'out'), '--timeout', '1')
    assert result.returncode == 2
    assert 'no node found in the graph within 1 s' in result.stderr


def test_a_node_not_found_gets_did_you_mean(ros_node) -> None:
    node = ros_node('plain_node.py', 'graph_talker', '/ux')
    result = nodl('describe', '/ux/graph_talkr', '--timeout', '6')  # discovery takes up to 3 s
    assert result.returncode == 2
    assert f"did you mean '{node.fqn}'?" in result.stderr


def test_a_shared_name_warns_in_describe_and_check_refuses(ros_node, tmp_path: Path) -> None:
    first = ros_node('plain_node.py', 'twin', '/ux')
    ros_node('plain_node.py', 'twin', '/ux')
    # --watch 3.5: past the 3 s periodic announcements, so that the second twin is always seen
    described = nodl('describe', first.fqn, '--timeout', '10', '--watch', '3.5',
                     '-o', str(tmp_path / 'twin.nodl.yaml'))
    assert described.returncode == 0, described.stderr
    assert 'warning: 2 nodes in the graph are named /ux/twin' in described.stderr
    header = [line for line in (tmp_path / 'twin.nodl.yaml').read_text().splitlines() if line.startswith('#')]
    assert '# Warning: 2 nodes in the graph are named /ux/twin: what was observed is all of them ' \
        'together (give each node a unique name).' in header
    # a warning line of its own, not an item of what could not be observed
    assert not any(line.startswith('#   - ') and '/ux/twin' in line for line in header)
    checked = nodl('check', first.fqn, str(tmp_path / 'twin.nodl.yaml'), '--timeout', '10')
    assert checked.returncode == 2
    assert '2 nodes in the graph are named /ux/twin' in checked.stderr
    assert 'none is checked' in checked.stderr


def test_a_base_mismatch_is_one_line(ros_node, tmp_path: Path) -> None:
    node = ros_node('lifecycle_node.py', 'lc_ux', '/ux')
    definition = tmp_path / 'lc.nodl.yaml'
    definition.write_text('nodl_version: 2\nbase: node\nmain:\n  nodl_version: 2\n')
    result = nodl('check', node.fqn, str(definition), '--timeout', '10', '--no-parameters')
    assert result.returncode == 1, result.stdout + result.stderr
    lines = [line for line in result.stdout.splitlines() if ': error: ' in line]
    assert lines[0].startswith(f'{node.fqn}: error: base: the node serves the lifecycle services: '
                               'use `base: lifecycle_node`')
    assert not any('change_state' in line for line in lines), result.stdout  # folded into that line
    verbose = nodl('check', node.fqn, str(definition), '--timeout', '10', '--no-parameters', '-v')
    assert 'change_state' in verbose.stdout
