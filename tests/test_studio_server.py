"""``nodl studio`` as a user starts it (nodl.studio.server, nodl/cli/verbs/studio.py): a real
process that prints its address, listens on 127.0.0.1 only, answers nothing without the
token, and stops cleanly on SIGTERM; what it says when it cannot start."""

from __future__ import annotations

import argparse
import os
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl.cli.verbs.studio import StudioVerb

DEFINITIONS = FIXTURES / 'studio' / 'example_definitions'


def listening_addresses(port: int) -> list[str]:
    """The local addresses of the TCP sockets listening on ``port`` (from /proc/net/tcp*)."""
    found = []
    for table in ('/proc/net/tcp', '/proc/net/tcp6'):
        with open(table, encoding='ascii') as stream:
            for line in list(stream)[1:]:
                fields = line.split()
                address, port_hex = fields[1].rsplit(':', 1)
                if int(port_hex, 16) == port and fields[3] == '0A':  # LISTEN
                    found.append(address)
    return found


def fetch(url: str) -> int:
    try:
        with urllib.request.urlopen(url, timeout=10) as response:
            return int(response.status)
    except urllib.error.HTTPError as exc:
        return exc.code


def test_the_studio_serves_loopback_only_and_stops_on_sigterm(tmp_path: Path) -> None:
    launch = tmp_path / 'system.launch.xml'
    launch.write_text('<launch>\n  <node pkg="rover_tools" exec="teleop" name="teleop"/>\n</launch>\n')
    process = subprocess.Popen([sys.executable, '-m', 'nodl', 'studio', str(launch), '--no-browser',
                                '--definitions', str(DEFINITIONS)], cwd=REPO,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert process.stdout is not None
        lines = [process.stdout.readline() for _ in range(3)]
        address = next(line.split('open ', 1)[1].strip() for line in lines if 'open http' in line)
        assert address.startswith('http://127.0.0.1:') and '/?token=' in address
        port = int(address.split(':')[2].split('/')[0])
        assert listening_addresses(port) == ['0100007F']  # 127.0.0.1, and nothing else
        base = address.split('/?token=')[0]
        assert fetch(f'{base}/') == 403
        assert fetch(f'{base}/?token=wrong') == 403
        assert fetch(address) == 200
        process.send_signal(signal.SIGTERM)
        out, err = process.communicate(timeout=15)
        assert process.returncode == 0, err
        assert 'nodl studio: stopped' in out
        assert 'Traceback' not in err
    finally:
        if process.poll() is None:
            process.kill()
            process.wait(10)


def run_verb(*argv: str) -> int:
    verb = StudioVerb()
    parser = argparse.ArgumentParser()
    verb.add_arguments(parser)
    return verb.main(parser.parse_args(list(argv)))


def test_missing_browser_libraries_are_said_with_what_to_run(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    from nodl.studio import vendor

    monkeypatch.setattr(vendor, 'vendor_folder', lambda: tmp_path / 'nothing')
    assert run_verb(str(tmp_path / 'x.launch.xml'), '--no-browser') == 2
    err = capsys.readouterr().err
    assert "the studio's browser libraries are not installed (cytoscape.min.js" in err
    assert 'make install' in err and 'npm ci --prefix nodl/studio/web' in err and '[NODL991]' in err


def test_a_port_taken_or_a_wrong_name_is_a_usage_error(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with socket.socket() as taken:
        taken.bind(('127.0.0.1', 0))
        taken.listen(1)
        port = taken.getsockname()[1]
        assert run_verb(str(tmp_path / 'x.launch.xml'), '--no-browser', '--port', str(port)) == 2
    assert f'cannot listen on 127.0.0.1:{port}' in capsys.readouterr().err
    assert run_verb(str(tmp_path / 'x.txt'), '--no-browser') == 2
    assert 'a launch file name ends in .launch.xml' in capsys.readouterr().err
    assert run_verb(str(tmp_path / 'no' / 'x.launch.xml'), '--no-browser') == 2
    assert 'its folder does not exist' in capsys.readouterr().err
    assert not os.listdir(tmp_path)  # nothing written


def test_serving_in_a_thread_starts_and_stops(tmp_path: Path) -> None:
    from nodl.studio.server import StudioServer, bind

    async def app(scope, receive, send):  # type: ignore[no-untyped-def]
        if scope['type'] == 'http':
            await send({'type': 'http.response.start', 'status': 204, 'headers': []})
            await send({'type': 'http.response.body', 'body': b''})

    server = StudioServer(app, bind(0))
    started = time.monotonic()
    server.start()
    try:
        assert server.host == '127.0.0.1'
        assert fetch(f'http://127.0.0.1:{server.port}/') == 204
    finally:
        server.stop()
    assert time.monotonic() - started < 5
