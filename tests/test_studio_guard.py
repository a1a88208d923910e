"""What a request to nodl studio may do (nodl.studio.guard, and the app that applies it): the
token, the Host, the folders it reads and writes under (links and ``..`` cannot lead out),
and the launch files' Python code, which runs only when asked and never with --no-exec."""

from __future__ import annotations

import os
from pathlib import Path

from starlette.testclient import TestClient

from conftest import FIXTURES
from nodl.studio.app import create_app
from nodl.studio.guard import FolderGuard, allowed_host, new_token, same_token
from nodl.studio.session import Session
from nodl.targets.resolve import gather_definitions

DEFINITIONS = FIXTURES / 'studio' / 'example_definitions'
LAUNCH = '<launch>\n  <node pkg="rover_tools" exec="teleop" name="teleop"/>\n</launch>\n'


def test_tokens_are_random_and_compared_whole() -> None:
    first, second = new_token(), new_token()
    assert first != second and len(first) >= 32
    assert same_token(first, first)
    assert not same_token(first[:-1], first) and not same_token('', first)
    assert not same_token(None, first)


def test_only_the_loopback_server_is_answered() -> None:
    assert allowed_host('127.0.0.1:8080', 8080) and allowed_host('localhost:8080', 8080)
    assert not allowed_host('127.0.0.1:8081', 8080)
    assert not allowed_host('evil.example:8080', 8080)  # a rebound name
    assert not allowed_host(None, 8080) and not allowed_host('127.0.0.1', 8080)


def test_folders_are_compared_by_their_real_paths(tmp_path: Path) -> None:
    root = tmp_path / 'work'
    (root / 'sub').mkdir(parents=True)
    outside = tmp_path / 'outside'
    outside.mkdir()
    (root / 'link').symlink_to(outside)
    guard = FolderGuard([root])
    assert guard.inside(root / 'sub' / 'new.launch.xml')  # need not exist
    assert guard.inside(root)
    assert not guard.inside(root / '..' / 'outside' / 'x')
    assert not guard.inside(root / 'link' / 'x')  # a link that leads out
    assert not guard.inside(tmp_path / 'work-other' / 'x')  # a prefix is not a parent
    problem = guard.check(root / 'link' / 'x', 'the export')
    assert problem is not None and problem.code == 'NODL990'
    assert problem.message.startswith('the export is outside the folders')


def client_for(tmp_path: Path, *, execute: bool = True) -> tuple[TestClient, str]:
    launch = tmp_path / 'system.launch.xml'
    launch.write_text(LAUNCH)
    session = Session(str(launch), definitions=gather_definitions([str(DEFINITIONS)],
                                                                  use_config=False),
                      roots=[str(DEFINITIONS)], execute=execute)
    token = new_token()
    return TestClient(create_app(session, token, 7777), base_url='http://127.0.0.1:7777'), token


def test_every_request_needs_the_token_and_the_host(tmp_path: Path) -> None:
    client, token = client_for(tmp_path)
    assert client.get('/').status_code == 403
    assert client.get('/static/studio.js').status_code == 403
    assert client.post('/api/state').status_code == 403
    assert client.post('/api/state', headers={'x-nodl-token': token[:-2]}).status_code == 403
    page = client.get(f'/?token={token}')
    assert page.status_code == 200 and f'content="{token}"' in page.text
    assert page.headers['cache-control'] == 'no-store'
    assert page.headers['referrer-policy'] == 'no-referrer'
    assert "script-src 'self'" in page.headers['content-security-policy']
    assert client.get(f'/static/studio.js?token={token}').status_code == 200
    assert client.post('/api/state', headers={'x-nodl-token': token}).status_code == 200
    other_host = TestClient(client.app, base_url='http://attacker.example:7777')
    refused = other_host.post('/api/state', headers={'x-nodl-token': token})
    assert refused.status_code == 403 and 'loopback' in refused.text


def test_files_outside_the_folders_are_refused(tmp_path: Path) -> None:
    client, token = client_for(tmp_path)
    headers = {'x-nodl-token': token}
    assert client.post('/api/save', headers=headers, json={}).json()['ok']
    for output in ('../outside.svg', '/etc/nodl.svg', 'link/x.svg'):
        (tmp_path / 'link').unlink(missing_ok=True)
        (tmp_path / 'link').symlink_to('/tmp')
        answer = client.post('/api/export', headers=headers, json={'what': 'graph', 'output': output})
        assert answer.status_code == 403, output
        assert answer.json()['diagnostics'][0]['code'] == 'NODL990'
    assert not os.path.exists(tmp_path.parent / 'outside.svg')


def test_launch_code_runs_only_when_asked_and_never_with_no_exec(tmp_path: Path) -> None:
    (tmp_path / 'code.launch.py').write_text(
        'from launch import LaunchDescription\n'
        'from launch_ros.actions import Node\n'
        'open(__file__ + ".ran", "w").close()\n\n\n'
        'def generate_launch_description():\n'
        "    return LaunchDescription([Node(package='rover_tools', executable='teleop')])\n")
    ran = tmp_path / 'code.launch.py.ran'
    (tmp_path / 'system.launch.xml').write_text(
        '<launch>\n  <include file="$(dirname)/code.launch.py"/>\n</launch>\n')
    for execute in (False, True):
        session = Session(str(tmp_path / 'system.launch.xml'), execute=execute,
                          definitions=gather_definitions([str(DEFINITIONS)], use_config=False))
        token = new_token()
        client = TestClient(create_app(session, token, 7777), base_url='http://127.0.0.1:7777')
        headers = {'x-nodl-token': token}
        state = client.post('/api/state', headers=headers).json()['state']
        assert not ran.exists()  # opening and analysing never runs it
        assert state['code']['needed'] and state['code']['allowed'] is execute
        answer = client.post('/api/run-code', headers=headers, json={})
        if not execute:
            assert answer.status_code == 403
            assert answer.json()['diagnostics'][0]['code'] == 'NODL994'
            assert not ran.exists()
        else:
            assert answer.status_code == 200 and ran.exists()
            nodes = [n['fqn'] for n in answer.json()['state']['nodes']]
            assert nodes == ['/teleop']
