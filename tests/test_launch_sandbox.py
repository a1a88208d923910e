"""The launch's Python code in a forked child under limits (nodl.launch.sandbox).

The hostile launch files (tests/fixtures/launch/sandbox) end, crash, loop, allocate and
recurse in the child; the test process itself (the parent) must live through each and get
one located error.  Memory tests run under a small --launch-memory.
"""

from __future__ import annotations

import os
import textwrap
from pathlib import Path
from typing import Any

import pytest

from conftest import FIXTURES
from nodl.diagnostics import Severity
from nodl.launch import load_launch, sandbox
from nodl.launch.sandbox import LaunchLimits

SANDBOX = FIXTURES / 'launch' / 'sandbox'
#: Short limits: a hostile case costs at most about a second.
TIGHT = LaunchLimits(timeout=1.5, memory_mib=128)


def _found(result: Any) -> list[tuple[str, str, int, int]]:
    return [(d.code, os.path.basename(d.file), d.line, d.column) for d in result.diagnostics]


@pytest.mark.parametrize('name, code, says', [
    ('exits.launch.py', 'NODL527', 'exit status 0: os._exit()'),
    ('segfault.launch.py', 'NODL527', 'killed by SIGSEGV (a segmentation fault'),
    ('recurses.launch.py', 'NODL527', 'killed by SIGSEGV'),
    ('loops.launch.py', 'NODL528', 'did not finish within --launch-timeout 1.5 s'),
])
def test_a_hostile_launch_file_is_one_located_error_and_the_parent_lives(name: str, code: str,
                                                                         says: str) -> None:
    result = load_launch(SANDBOX / name, {}, limits=TIGHT)
    assert _found(result) == [(code, name, 1, 1)]
    assert says in result.diagnostics[0].message and result.diagnostics[0].severity is Severity.ERROR
    assert 'the nodes it would start are missing from the analysis' in result.diagnostics[0].message
    assert result.nodes == []


def test_unbounded_allocation_stops_at_the_memory_limit_at_its_line() -> None:
    result = load_launch(SANDBOX / 'allocates.launch.py', {}, limits=TIGHT)
    assert _found(result) == [('NODL529', 'allocates.launch.py', 8, 22)]
    assert 'more memory than --launch-memory 128 MiB allows' in result.diagnostics[0].message


def test_the_time_limit_holds_for_all_the_code_of_a_launch(tmp_path: Path) -> None:
    """Two includes that loop: the first uses up the time, the second is not run at all."""
    main = tmp_path / 'two.launch.xml'
    main.write_text(f'<launch>\n  <include file="{SANDBOX}/loops.launch.py"/>\n'
                    f'  <include file="{SANDBOX / "loops.launch.py"}" if="true"/>\n'
                    f'  <include file="{SANDBOX}/good.launch.py"/>\n</launch>\n')
    import time

    start = time.monotonic()
    result = load_launch(main, {}, limits=LaunchLimits(timeout=1.0))
    assert time.monotonic() - start < 3.5
    assert _found(result)[0] == ('NODL528', 'two.launch.xml', 2, 3)
    assert all(code == 'NODL528' for code, *_ in _found(result))
    assert 'already took the --launch-timeout of 1 s' in result.diagnostics[-1].message
    assert result.nodes == []  # good.launch.py too: the time was spent


def test_an_included_crash_is_at_its_include_and_the_rest_is_read() -> None:
    result = load_launch(SANDBOX / 'mixed.launch.xml', {}, limits=TIGHT)
    assert _found(result) == [('NODL527', 'mixed.launch.xml', 5, 3)]
    assert "'" + str(SANDBOX / 'segfault.launch.py') + "'" in result.diagnostics[0].message
    assert [n.name for n in result.nodes] == ['talker', 'listener']


def test_after_too_many_failures_the_rest_is_not_run(tmp_path: Path) -> None:
    main = tmp_path / 'many.launch.xml'
    for i in range(6):  # six files: each failure is one more child without the culprit
        (tmp_path / f'exits{i}.launch.py').write_bytes((SANDBOX / 'exits.launch.py').read_bytes())
    includes = ''.join(f'  <include file="{tmp_path}/exits{i}.launch.py"/>\n' for i in range(6))
    main.write_text(f'<launch>\n{includes}  <node pkg="demo" exec="listener" name="l"/>\n</launch>\n')
    result = load_launch(main, {}, limits=TIGHT)
    codes = _found(result)
    assert [c for c, *_ in codes] == ['NODL527'] * 6 and [line for _, _, line, _ in codes] == [2, 3, 4, 5, 6, 7]
    assert 'exit status 0' in result.diagnostics[4].message
    assert f'{sandbox.MAX_ATTEMPTS} pieces of Python code of this launch already failed' in \
        result.diagnostics[-1].message
    assert [n.name for n in result.nodes] == ['l']


def test_the_launch_code_cannot_touch_the_analyser(tmp_path: Path) -> None:
    """It runs in a copy: the parent's environment and modules are as they were."""
    main = tmp_path / 'x.launch.py'
    main.write_text(textwrap.dedent('''\
        import os, sys
        from launch import LaunchDescription
        os.environ['NODL_SANDBOX_PROBE'] = 'set'
        sys.modules['json'] = None
        def generate_launch_description():
            return LaunchDescription([])
        '''))
    result = load_launch(main, {})
    assert result.diagnostics == [] and 'NODL_SANDBOX_PROBE' not in os.environ
    import json

    assert json.dumps(1) == '1'


def test_processes_the_launch_code_starts_are_stopped_with_it(tmp_path: Path) -> None:
    pid_file = tmp_path / 'pid'
    main = tmp_path / 'x.launch.py'
    main.write_text(textwrap.dedent(f'''\
        import subprocess
        from launch import LaunchDescription
        def generate_launch_description():
            child = subprocess.Popen(['sleep', '60'])
            open({str(pid_file)!r}, 'w').write(str(child.pid))
            while True:
                pass
        '''))
    result = load_launch(main, {}, limits=LaunchLimits(timeout=1.0))
    assert [c for c, *_ in _found(result)] == ['NODL528']
    pid = int(pid_file.read_text())
    try:
        state = Path(f'/proc/{pid}/stat').read_text().split(')')[-1].split()[0]
    except FileNotFoundError:
        state = 'gone'
    assert state in ('gone', 'Z')  # killed (a zombie until its new parent reaps it)


def test_what_the_child_writes_over_the_pipe_cannot_run_code_here(tmp_path: Path) -> None:
    """A launch file that forges a result on every pipe it holds: only the launch model's
    classes are unpickled, so the forged os._exit never runs in the parent."""
    import stat

    ours = set()  # the pipes this process holds already (pytest's): the forger leaves them alone
    for fd in range(3, 256):
        try:
            info = os.fstat(fd)
        except OSError:
            continue
        if stat.S_ISFIFO(info.st_mode):
            ours.add(info.st_ino)
    main = tmp_path / 'x.launch.py'
    main.write_text(f'OURS = {sorted(ours)!r}\n' + textwrap.dedent('''\
        import os, pickle, stat
        class Forged:
            def __reduce__(self):
                return (os._exit, (9,))
        def generate_launch_description():
            data = pickle.dumps((Forged(), []))
            frame = b'R' + len(data).to_bytes(8, 'big') + data
            for fd in range(3, 256):
                try:
                    info = os.fstat(fd)
                    if stat.S_ISFIFO(info.st_mode) and info.st_ino not in OURS:
                        os.write(fd, frame)
                except OSError:
                    pass
            os._exit(0)
        '''))
    result = load_launch(main, {}, limits=TIGHT)
    assert _found(result) == [('NODL527', 'x.launch.py', 1, 1)]
    assert 'wrote over the channel' in result.diagnostics[0].message


def test_a_result_larger_than_the_bound_is_not_read(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(sandbox, 'MAX_RESULT_BYTES', 64)
    result = load_launch(SANDBOX / 'good.launch.py', {}, limits=TIGHT)
    assert _found(result) == [('NODL529', 'good.launch.py', 1, 1)]
    assert "'" + str(SANDBOX / 'good.launch.py') + "' is not run: the evaluation of this launch gave a result " \
        'larger than 0 MiB; it is not read; the nodes it would start are missing' in result.diagnostics[0].message


def test_no_fork_without_python_code(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    forks: list[int] = []
    real_fork = os.fork

    def counting_fork() -> int:
        forks.append(1)
        return real_fork()

    monkeypatch.setattr(os, 'fork', counting_fork)
    monkeypatch.setenv('NODL_COMMAND_MARKER', str(tmp_path / 'ran'))
    result = load_launch(SANDBOX / 'plain.launch.xml', {})
    assert [n.name for n in result.nodes] == ['talker'] and forks == []
    load_launch(SANDBOX / 'good.launch.py', {})
    assert forks == [1]
    load_launch(SANDBOX / 'eval.launch.xml', {})
    assert forks == [1, 1]


def test_command_is_never_run_not_even_in_the_child(tmp_path: Path) -> None:
    marker = tmp_path / 'ran'
    main = tmp_path / 'x.launch.xml'
    main.write_text(f'<launch>\n  <node pkg="demo" exec="talker" name="$(eval \'chr(116)\')">\n'
                    f'    <param name="x" value="$(command \'touch {marker}\')"/>\n  </node>\n</launch>\n')
    result = load_launch(main, {})
    assert [n.name for n in result.nodes] == ['t'] and 'NODL513' in [c for c, *_ in _found(result)]
    assert not marker.exists()
    result = load_launch(main, {}, limits=LaunchLimits(execute=False))
    assert [c for c, *_ in _found(result)] == ['NODL526'] and not marker.exists()


def test_eval_runs_in_the_child() -> None:
    result = load_launch(SANDBOX / 'eval.launch.xml', {})
    assert result.diagnostics == []
    assert [n.name for n in result.nodes] == ['talker', 'listener_2']
    assert result.nodes[0].parameters[0].values == {'rate': 10}


def test_an_eval_that_ends_the_child_is_an_error_at_its_entry_and_the_rest_is_read() -> None:
    result = load_launch(SANDBOX / 'eval_exits.launch.xml', {}, limits=TIGHT)
    assert _found(result) == [('NODL527', 'eval_exits.launch.xml', 3, 3)]
    assert 'exit status 3' in result.diagnostics[0].message
    assert [n.name for n in result.nodes] == ['talker']


def test_no_exec_runs_no_python_launch_file(tmp_path: Path) -> None:
    marker = tmp_path / 'ran'
    main = tmp_path / 'x.launch.py'
    main.write_text(f'open({str(marker)!r}, "w").close()\ndef generate_launch_description():\n    pass\n')
    result = load_launch(main, {}, limits=LaunchLimits(execute=False))
    assert _found(result) == [('NODL525', 'x.launch.py', 1, 1)] and not marker.exists()
    assert '--no-exec is set' in result.diagnostics[0].message
    mixed = load_launch(SANDBOX / 'mixed.launch.xml', {}, limits=LaunchLimits(execute=False))
    assert _found(mixed) == [('NODL525', 'mixed.launch.xml', 4, 3), ('NODL525', 'mixed.launch.xml', 5, 3)]
    assert [n.name for n in mixed.nodes] == ['listener']


def test_no_exec_leaves_eval_values_unknown_and_the_nodes_analysed() -> None:
    result = load_launch(SANDBOX / 'eval.launch.xml', {}, limits=LaunchLimits(execute=False))
    found = [(d.code, d.severity, d.line) for d in result.diagnostics]
    assert found == [('NODL526', Severity.WARNING, 4), ('NODL526', Severity.WARNING, 6)]
    assert 'its value is unknown here' in result.diagnostics[0].message
    assert [n.name for n in result.nodes] == ['talker']  # the listener's name is unknown
    from nodl.launch.params import RuntimeValue

    assert isinstance(result.nodes[0].parameters[0].values['rate'], RuntimeValue)  # set, unchecked


def test_the_child_starts_with_what_it_inherits_frozen_and_the_parent_as_it_was(tmp_path: Path) -> None:
    """The objects the child inherits are out of the collector's generations (its collections
    neither walk them nor copy their pages); the parent's are back at once."""
    import gc

    main = tmp_path / 'x.launch.py'
    main.write_text(textwrap.dedent('''\
        import gc
        from launch import LaunchDescription
        from launch_ros.actions import Node
        def generate_launch_description():
            name = 'frozen' if gc.get_freeze_count() > 0 else 'walked'
            return LaunchDescription([Node(package='p', executable='e', name=name)])
        '''))
    assert gc.get_freeze_count() == 0
    result = load_launch(main, {})
    assert [node.name for node in result.nodes] == ['frozen']
    assert gc.get_freeze_count() == 0
