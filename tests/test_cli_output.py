"""The command line's output layer (nodl.cli.output and the runner): guarded writes,
exit statuses, streaming, progress, colour, Ctrl-C; real processes, real pipes and terminals."""

from __future__ import annotations

import os
import pty
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl.cli.output import colour_enabled, colourize

SCAN = FIXTURES / 'scan'
CMD = [sys.executable, '-m', 'nodl']


def nodl(*args: str, env: dict[str, str] | None = None, **kwargs) -> subprocess.CompletedProcess[str]:
    result = subprocess.run([*CMD, *args], cwd=REPO, text=True, capture_output=True, timeout=60,
                            env=env, **kwargs)
    assert 'Traceback' not in result.stderr, result.stderr
    return result


def run_on_terminal(args: list[str], env: dict[str, str] | None = None, stdout_tty: bool = True,
                    timeout: float = 60) -> tuple[int, str, str]:
    """Run with a pseudo-terminal as stdout (or stderr): returns (status, terminal text, other)."""
    master, slave = pty.openpty()
    other = subprocess.PIPE
    process = subprocess.Popen([*CMD, *args], cwd=REPO, env=env,
                               stdout=slave if stdout_tty else other,
                               stderr=other if stdout_tty else slave)
    os.close(slave)
    chunks = []
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            data = os.read(master, 65536)
        except OSError:  # EIO: the process closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    out, err = process.communicate(timeout=max(1.0, deadline - time.monotonic()))
    rest = out if out is not None else err
    return process.returncode, b''.join(chunks).decode(), rest.decode()


# -- write failures ---------------------------------------------------------------------------

@pytest.mark.parametrize('args', [['schema'], ['validate', str(SCAN / 'valid.nodl.yaml')],
                                  ['list', '--format', 'json']])
def test_a_full_standard_output_is_one_io_line_and_exit_2(args: list[str]) -> None:
    with open('/dev/full', 'w') as full:
        result = subprocess.run([*CMD, *args], cwd=REPO, text=True, stdout=full,
                                stderr=subprocess.PIPE, timeout=60)
    assert result.returncode == 2, result.stderr
    assert result.stderr.strip().splitlines() == [
        'nodl: error: cannot write standard output: No space left on device'], result.stderr


def test_an_unwritable_output_file_is_one_io_line_and_exit_2() -> None:
    result = nodl('schema', '-o', '/dev/full')
    assert result.returncode == 2
    assert result.stderr == ('/dev/full: error: cannot write the file: no space left on the device '
                             '[NODL030]\n')  # a device: written in place, nothing to keep
    assert 'internal error' not in result.stderr


def test_describe_all_into_a_file_is_refused_at_once(tmp_path: Path) -> None:
    target = tmp_path / 'a_file'
    target.write_text('')
    start = time.monotonic()
    result = nodl('describe', '--all', '-o', str(target), '--timeout', '30')
    assert result.returncode == 2
    assert 'not a directory' in result.stderr and 'internal error' not in result.stderr
    assert time.monotonic() - start < 20  # no discovery was started


def test_a_closed_pipe_ends_quietly_with_141(tmp_path: Path) -> None:
    for i in range(50):
        shutil.copy(SCAN / 'valid.nodl.yaml', tmp_path / f'f{i}.nodl.yaml')
    process = subprocess.Popen([*CMD, 'validate', str(tmp_path)], cwd=REPO,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert process.stdout is not None and process.stderr is not None
    process.stdout.close()  # the reader goes away, as `| head` does
    err = process.stderr.read().decode()
    assert process.wait(timeout=60) == 141
    assert err == ''
    process.stderr.close()


def _registered_verbs() -> list[str]:
    """Every verb pyproject.toml registers (new verbs are covered without editing this test)."""
    try:
        import tomllib
    except ImportError:  # Python 3.10
        import tomli as tomllib  # type: ignore[no-redef]
    with open(REPO / 'pyproject.toml', 'rb') as f:
        return sorted(tomllib.load(f)['project']['entry-points']['nodl.verbs'])


def test_every_verb_documents_its_exit_statuses() -> None:
    verbs = _registered_verbs()
    assert {'validate', 'deps', 'export'} <= set(verbs)
    for verb in verbs:  # deps sets an epilog of its own: the statuses still close its --help
        text = nodl(verb, '--help').stdout
        assert 'exit status:' in text, verb
        for status in ('0 ', '2 ', '3 ', '130 ', '141 '):
            assert f'\n  {status}' in text, (verb, status)


# -- streaming, unreadable paths --------------------------------------------------------------

def test_unreadable_paths_are_counted_and_in_the_json(tmp_path: Path) -> None:
    missing = str(tmp_path / 'missing.nodl.yaml')
    result = nodl('validate', str(SCAN / 'valid.nodl.yaml'), missing)
    assert result.returncode == 2
    assert result.stdout.rstrip().endswith('1 file, 0 errors, 0 warnings, 1 unreadable path')
    result = nodl('validate', '--format', 'json', missing)
    import json

    entries = json.loads(result.stdout)
    assert [(e['file'], e['severity'], e['code']) for e in entries] == [(missing, 'error', 'NODL020')]
    assert '1 unreadable path' in result.stderr


def _drop_read_permission_override() -> None:
    """As root, permission bits do not stop reading; drop the capabilities that bypass them."""
    if os.geteuid() == 0:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        for capability in (1, 2):  # CAP_DAC_OVERRIDE, CAP_DAC_READ_SEARCH
            if libc.prctl(24, capability, 0, 0, 0) != 0:  # PR_CAPBSET_DROP
                raise OSError(ctypes.get_errno(), 'prctl(PR_CAPBSET_DROP)')


def test_an_unreadable_subdirectory_is_reported_and_exits_2(tmp_path: Path) -> None:
    shutil.copy(SCAN / 'valid.nodl.yaml', tmp_path / 'a.nodl.yaml')
    locked = tmp_path / 'locked'
    locked.mkdir()
    shutil.copy(SCAN / 'valid.nodl.yaml', locked / 'b.nodl.yaml')
    locked.chmod(0)
    try:
        result = subprocess.run([*CMD, 'validate', str(tmp_path)], cwd=REPO, text=True,
                                capture_output=True, timeout=60,
                                preexec_fn=_drop_read_permission_override)
    finally:
        locked.chmod(0o755)
    assert result.returncode == 2, result.stdout + result.stderr
    assert f'{locked}: error: cannot read this directory: Permission denied' in result.stderr
    assert result.stdout.rstrip().endswith('1 file, 0 errors, 0 warnings, 1 unreadable path')


def test_a_pipe_in_a_scanned_directory_does_not_hang(tmp_path: Path) -> None:
    shutil.copy(SCAN / 'valid.nodl.yaml', tmp_path / 'a.nodl.yaml')
    os.mkfifo(tmp_path / 'b.nodl.yaml')
    result = nodl('validate', str(tmp_path))  # times out (fails) if the pipe is opened
    assert result.returncode == 0, result.stderr
    assert 'b.nodl.yaml: note: skipped: is a named pipe' in result.stderr


def test_a_pipe_given_explicitly_says_it_waits_and_ctrl_c_keeps_what_was_printed(tmp_path: Path) -> None:
    pipe = tmp_path / 'p.nodl.yaml'
    os.mkfifo(pipe)
    process = subprocess.Popen([*CMD, 'validate', str(SCAN / 'valid.nodl.yaml'), str(pipe)],
                               cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert process.stderr is not None
        line = process.stderr.readline()  # printed before the read blocks
        assert 'is a named pipe: waiting for a program to write to it' in line
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate(timeout=10)
    assert process.returncode == 130
    assert 'valid.nodl.yaml: valid interface definition' in out  # streamed, and kept
    assert 'interrupted' in err and 'Traceback' not in err


def test_a_pipe_with_a_writer_is_read(tmp_path: Path) -> None:
    pipe = tmp_path / 'p.yaml'
    os.mkfifo(pipe)

    def write() -> None:
        with open(pipe, 'w') as f:
            f.write((SCAN / 'valid.nodl.yaml').read_text())

    writer = threading.Thread(target=write)
    writer.start()
    try:
        result = nodl('validate', str(pipe))
    finally:
        writer.join(timeout=30)
    assert result.returncode == 0, result.stderr
    assert 'valid interface definition' in result.stdout


def test_progress_line_on_a_terminal_is_erased_before_output(tmp_path: Path) -> None:
    for i in range(20):
        shutil.copy(SCAN / 'invalid.nodl.yaml', tmp_path / f'f{i:02}.nodl.yaml')
    pipe = tmp_path / 'first.yaml'
    os.mkfifo(pipe)

    def write_late() -> None:  # the run lasts long enough for the progress line
        time.sleep(1.0)
        with open(pipe, 'w') as f:
            f.write((SCAN / 'valid.nodl.yaml').read_text())

    writer = threading.Thread(target=write_late)
    writer.start()
    try:
        status, terminal, out = run_on_terminal(['validate', str(pipe), str(tmp_path)],
                                                stdout_tty=False)
    finally:
        writer.join(timeout=30)
    assert status == 1
    assert 'files checked' in terminal
    assert terminal.rstrip('\r\n').endswith('\r\033[K')  # erased at the end
    assert out.count(': error: ') == 20  # stdout (a pipe) holds no progress text
    assert 'files checked' not in out


def test_no_progress_line_when_stderr_is_not_a_terminal(tmp_path: Path) -> None:
    result = nodl('validate', str(SCAN))
    assert 'files checked' not in result.stderr


# -- colour -----------------------------------------------------------------------------------

RED = '\033[1;31m'


def test_severity_words_are_coloured_on_a_terminal() -> None:
    env = {k: v for k, v in os.environ.items() if k != 'NO_COLOR'}
    status, terminal, _ = run_on_terminal(['validate', str(SCAN / 'invalid.nodl.yaml')], env=env)
    assert status == 1
    assert f': {RED}error\033[0m: unknown key' in terminal


def test_no_color_and_color_never_turn_it_off_and_always_forces_it() -> None:
    env = dict(os.environ, NO_COLOR='1')
    _, terminal, _ = run_on_terminal(['validate', str(SCAN / 'invalid.nodl.yaml')], env=env)
    assert '\033[' not in terminal and ': error: unknown key' in terminal
    _, terminal, _ = run_on_terminal(['validate', '--color', 'never', str(SCAN / 'invalid.nodl.yaml')])
    assert '\033[' not in terminal
    piped = nodl('validate', '--color', 'always', str(SCAN / 'invalid.nodl.yaml'), env=env)
    assert RED in piped.stdout
    assert '\033[' not in nodl('validate', str(SCAN / 'invalid.nodl.yaml')).stdout


def test_colour_rules() -> None:
    class Tty:
        def isatty(self) -> bool:
            return True

    assert colour_enabled('auto', Tty(), {}) is True
    assert colour_enabled('auto', Tty(), {'NO_COLOR': 'x'}) is False
    assert colour_enabled('auto', Tty(), {'NO_COLOR': ''}) is True  # no-color.org: non-empty
    assert colour_enabled('always', object(), {'NO_COLOR': 'x'}) is True
    assert colourize('f:1:2: warning: w\nplain\n') == 'f:1:2: \033[1;35mwarning\033[0m: w\nplain\n'


def test_a_guarded_stream_shows_control_and_bidi_characters_never_obeys_them() -> None:
    import io

    from nodl.cli.output import GuardedStream

    raw = io.StringIO()
    stream = GuardedStream(raw, 'stdout', colour=True)
    stream.write('x.yaml:1:2: error: name \x1b[2J\u202eevil\x00\tend\n')
    assert raw.getvalue() == ('x.yaml:1:2: \033[1;31merror\033[0m: name \\x1b[2J\\u202eevil\\x00\tend\n')
