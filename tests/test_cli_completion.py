"""Shell completion of `nodl` through argcomplete's protocol, in a real process."""

from __future__ import annotations

import os
import subprocess
import sys

from conftest import REPO


def complete(line: str) -> list[str]:
    """What a shell would get for ``line`` (argcomplete answers on file descriptor 8)."""
    read, write = os.pipe()
    saved = os.dup(8) if _is_open(8) else None
    os.dup2(write, 8)
    os.close(write)
    try:
        env = dict(os.environ, _ARGCOMPLETE='1', _ARGCOMPLETE_IFS='\n',
                   _ARGCOMPLETE_SUPPRESS_SPACE='1', COMP_LINE=line, COMP_POINT=str(len(line)),
                   COMP_TYPE='9')
        result = subprocess.run([sys.executable, '-m', 'nodl'], cwd=REPO, env=env,
                                pass_fds=(8,), capture_output=True, text=True, timeout=60)
    finally:
        os.close(8)
        if saved is not None:
            os.dup2(saved, 8)
            os.close(saved)
    with os.fdopen(read, 'rb') as stream:
        words = stream.read().decode()
    assert result.returncode == 0, result.stderr
    return words.split('\n') if words else []


def _is_open(fd: int) -> bool:
    try:
        os.fstat(fd)
    except OSError:
        return False
    return True


def test_verbs_options_choices_and_paths_complete() -> None:
    assert {'validate', 'check', 'describe', 'show', 'schema'} <= set(complete('nodl '))
    assert complete('nodl valid') == ['validate']
    assert '--format' in complete('nodl validate --fo')
    assert set(complete('nodl validate --format ')) == {'text', 'json', 'sarif', 'junit'}
    assert complete('nodl validate exampl') == ['examples/']


def test_show_offers_registered_packages() -> None:
    env_prefix = os.environ.get('AMENT_PREFIX_PATH', '')
    from nodl.registry.registrations import list_registrations

    packages = {r.package for r in list_registrations()}
    words = complete('nodl show ')
    assert packages <= set(words), (env_prefix, words)
    assert 'examples/' in words


def test_the_entry_module_carries_the_argcomplete_marker() -> None:
    import nodl.cli.main as main

    with open(main.__file__, encoding='utf-8') as f:
        assert 'PYTHON_ARGCOMPLETE_OK' in f.read(1024)


def test_completion_in_a_real_bash_on_a_terminal(tmp_path) -> None:
    """What a user gets: bash on a pseudo-terminal, the hook from register-python-argcomplete."""
    import pty
    import select
    import shutil
    import time

    register = shutil.which('register-python-argcomplete',
                            path=os.path.dirname(sys.executable) + os.pathsep + os.environ['PATH'])
    assert register, 'argcomplete is a test dependency'
    wrapper = tmp_path / 'nodl'  # the source tree's nodl, under the name the hook is for
    wrapper.write_text(f'#!/bin/sh\nexec {sys.executable} -m nodl "$@"\n')
    wrapper.chmod(0o755)
    env = dict(os.environ, PATH=f'{tmp_path}{os.pathsep}{os.environ["PATH"]}', PYTHONPATH=str(REPO),
               PS1='$ ', TERM='dumb', HOME=str(tmp_path), INPUTRC='/dev/null')
    pid, fd = pty.fork()
    if pid == 0:  # pragma: no cover - the child
        os.chdir(REPO)
        os.execvpe('bash', ['bash', '--norc', '--noprofile', '-i'], env)

    def exchange(text: str, until: str, timeout: float = 30) -> str:
        os.write(fd, text.encode())
        seen = ''
        deadline = time.monotonic() + timeout
        while until not in seen and time.monotonic() < deadline:
            ready, _, _ = select.select([fd], [], [], 0.2)
            if ready:
                try:
                    seen += os.read(fd, 65536).decode(errors='replace')
                except OSError:
                    break
        return seen

    try:
        exchange(f'eval "$({register} nodl)"; echo hooked\n', 'hooked\r\n$ ')
        assert 'nodl validate ' in exchange('nodl valid\t', 'validate ')
        listed = exchange('\x15nodl validate --format \t\t', 'sarif')
        assert all(word in listed for word in ('json', 'sarif', 'text'))
        os.write(fd, b'\x15exit\n')
    finally:
        for _ in range(50):
            done, _ = os.waitpid(pid, os.WNOHANG)
            if done:
                break
            time.sleep(0.1)
        else:
            os.kill(pid, 9)
            os.waitpid(pid, 0)
        os.close(fd)
