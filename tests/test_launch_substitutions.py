"""Launch substitutions (nodl.launch.substitutions): the 16 MiB limit on what a
substitution makes, in XML, YAML and Python launch files.

Each hostile case (``tests/fixtures/launch/hostile``) runs in a child process limited to
1 GiB of address space (``RLIMIT_AS``): without the limit the doubling chains need many
GB and fail there with MemoryError; with it, each is one located NODL521 error, in well
under a second and a few tens of MB, and the rest of the launch is still analysed.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from bounded_child import run_bounded
from conftest import FIXTURES
from nodl.launch import load_launch
from nodl.launch.errors import MAX_SUBSTITUTION_CHARS
from nodl.launch.substitutions import (
    LaunchConfiguration,
    PathJoinSubstitution,
    TextSubstitution,
    check_joined_size,
    perform,
)

HOSTILE = FIXTURES / 'launch' / 'hostile'
MEGABYTES = 1024   # the child's address space
MAX_SECONDS = 2.0  # measured: 0.02-0.1 s; generous for a loaded machine
MAX_PEAK_MB = 400  # measured: 40-110 MB (a 16 MiB value is held, and its parts)


def _analyse_bounded(path: Path) -> dict[str, Any]:
    return run_bounded(
        'from nodl.launch import load_launch',
        f'''
        result = load_launch({str(path)!r})
        out = {{'diagnostics': [[d.code, d.file, d.line, d.column, d.message] for d in result.diagnostics],
                'nodes': [n.name for n in result.nodes]}}
        ''', megabytes=MEGABYTES)


#: file -> (line, column, what the message names, the nodes still analysed)
CASES = {
    'let_chain.launch.xml': (24, 3, "launch configuration 'a21'", ['talker', 'second']),
    'arg_chain.launch.yaml': (24, 3, "launch argument 'a21'", ['listener']),
    'nested_var.launch.xml': (24, 3, "launch configuration 'v21'", ['listener']),
    'wide.launch.xml': (9, 3, "launch configuration 'seventeen'", ['talker']),
    'append_env.launch.xml': (23, 3, "environment variable 'GROWS'", ['talker']),
    'eval.launch.xml': (2, 3, "launch configuration 'huge'", ['talker']),
    'include_arg.launch.xml': (25, 3, "launch argument 'description' given to", ['included_listener']),
}


@pytest.mark.parametrize('name', sorted(CASES))
def test_a_value_past_16_mib_is_one_located_error_in_bounded_time_and_memory(name: str) -> None:
    line, column, what, nodes = CASES[name]
    got = _analyse_bounded(HOSTILE / name)
    diagnostics = got['out']['diagnostics']
    assert [d[:4] for d in diagnostics] == [['NODL521', str(HOSTILE / name), line, column]], diagnostics
    message = diagnostics[0][4]
    assert what in message and '16 MiB (16,777,216 characters)' in message, message
    assert got['out']['nodes'] == nodes  # the analysis went on; what uses the value is left out
    assert got['seconds'] < MAX_SECONDS, got
    assert got['peak_mb'] < MAX_PEAK_MB, got


def test_python_launch_substitutions_are_bounded_too() -> None:
    """SetLaunchConfiguration of LaunchConfigurations, DeclareLaunchArgument defaults made
    with PathJoinSubstitution, and a TextSubstitution written too large in Python: one
    error each, at the line that makes it; the node using the chain is left out."""
    path = HOSTILE / 'chain.launch.py'
    got = _analyse_bounded(path)
    diagnostics = got['out']['diagnostics']
    assert [d[:4] for d in diagnostics] == [['NODL521', str(path), 11, 24], ['NODL521', str(path), 15, 24],
                                            ['NODL521', str(path), 17, 20]], diagnostics
    assert "launch configuration 'a15'" in diagnostics[0][4]
    assert "launch argument 'b14'" in diagnostics[1][4]
    assert 'a text substitution is longer' in diagnostics[2][4]
    assert got['out']['nodes'] == ['kept']
    assert got['seconds'] < MAX_SECONDS and got['peak_mb'] < MAX_PEAK_MB, got


def test_exactly_16_mib_is_accepted_and_one_character_more_is_not(tmp_path: Path) -> None:
    # 16 characters doubled 20 times: exactly 16 MiB, the value a node parameter gets whole.
    lets = ''.join(f'<let name="a{i}" value="$(var a{i - 1})$(var a{i - 1})"/>\n' for i in range(1, 21))
    launch = tmp_path / 'edge.launch.xml'
    launch.write_text('<launch>\n<let name="a0" value="0123456789abcdef"/>\n' + lets +
                      '<let name="ok" value="$(var a20)"/>\n<let name="over" value="$(var a20)x"/>\n'
                      '<node pkg="p" exec="e" name="n"><param name="d" value="$(var ok)"/></node>\n'
                      '</launch>\n')
    result = load_launch(launch)
    assert [(d.code, d.line) for d in result.diagnostics] == [('NODL521', 24)]
    (node,) = result.nodes
    assert len(node.parameters[0].values['d']) == MAX_SUBSTITUTION_CHARS == 16 * 1024 * 1024


def test_the_limit_is_checked_before_the_text_is_made() -> None:
    """perform() stops at the first part that passes the limit: the parts before it are not
    joined (and a part that would be made after it is not performed at all)."""
    performed = []

    class Counted(TextSubstitution):
        def perform(self, context: Any) -> str:
            performed.append(1)
            return self.text

    big = 'x' * (MAX_SUBSTITUTION_CHARS // 2 + 1)
    from nodl.launch.errors import SubstitutionTooLarge

    with pytest.raises(SubstitutionTooLarge):
        perform(None, [Counted(big), Counted(big), Counted(big)])  # type: ignore[arg-type]
    assert len(performed) == 2
    with pytest.raises(SubstitutionTooLarge):
        check_joined_size([big, big], '/')
    check_joined_size(['a' * (MAX_SUBSTITUTION_CHARS - 2), 'b'], '/')  # exactly the limit


def test_a_path_join_is_bounded_before_it_is_joined(tmp_path: Path) -> None:
    from nodl.launch.context import LaunchContext
    from nodl.launch.errors import SubstitutionTooLarge
    from nodl.launch.model import LaunchResult

    context = LaunchContext(LaunchResult(str(tmp_path / 'x.launch.py')), {}, [])
    half = 'p' * (MAX_SUBSTITUTION_CHARS // 2)
    context.configurations['half'] = half
    join = PathJoinSubstitution([LaunchConfiguration('half'), LaunchConfiguration('half')])
    with pytest.raises(SubstitutionTooLarge):
        join.perform(context)  # 2 halves and a separator: one character too many
    assert len(PathJoinSubstitution([LaunchConfiguration('half'), 'q' * (len(half) - 1)]).perform(context)) \
        == MAX_SUBSTITUTION_CHARS


def test_nodl_analyse_reports_it_at_the_let_with_exit_1(tmp_path: Path) -> None:
    import subprocess
    import sys

    from conftest import REPO

    done = subprocess.run([sys.executable, '-m', 'nodl', 'analyse', str(HOSTILE / 'let_chain.launch.xml'),
                           '--format', 'json'], cwd=REPO, capture_output=True, text=True, timeout=60)
    assert done.returncode == 1, done.stderr
    assert 'Traceback' not in done.stderr
    report = json.loads(done.stdout)
    found = [d for d in report['findings'] if d['code'] == 'NODL521']
    assert [(d['line'], d['column']) for d in found] == [(24, 3)], found


def test_file_content_failures_say_why_in_words() -> None:
    # the system's own message, never "[Errno 2] ..." with the path twice
    result = load_launch(FIXTURES / 'launch' / 'file_content' / 'missing.launch.xml')
    messages = [d.message for d in result.diagnostics if d.code == 'NODL510']
    assert len(messages) == 2, [str(d) for d in result.diagnostics]
    assert messages[0].endswith("no_such_robot.urdf': No such file or directory")
    assert messages[1].endswith("latin1.txt': it is not UTF-8 text")
    assert not [m for m in messages if '[Errno' in m]
