"""``nodl system``: run as a real process, as users run it."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from composer_helpers import DEFINITIONS, copy_launch
from conftest import REPO
from nodl.cli.main import main


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, NO_COLOR='1')
    env.pop('AMENT_PREFIX_PATH', None)
    return subprocess.run([sys.executable, '-m', 'nodl', 'system', *args,
                           '--definitions', str(DEFINITIONS)],
                          cwd=REPO, env=env, text=True, capture_output=True, timeout=120, check=False)


def test_build_a_system_from_an_empty_file(tmp_path: Path) -> None:
    path = str(tmp_path / 'robot.launch.yaml')
    steps = [('new', path), ('add', path, 'demo_pkg', 'talker', '--name', 'talker'),
             ('add', path, 'demo_pkg', 'listener', '--name', 'listener', '--namespace', 'ui'),
             ('connect', path, 'talker:chatter', '/ui/listener:messages'),
             ('set', path, 'talker', 'rate', '2.0')]
    said = []
    for step in steps:
        done = nodl(*step)
        assert done.returncode == 0, (step, done.stdout, done.stderr)
        said.append(done.stdout)
    assert said[3] == ('joined talker:chatter and /ui/listener:messages (remapping rule '
                       f'messages:=/chatter on /ui/listener); {path} saved\n')
    text = Path(path).read_text(encoding='utf-8')
    assert text == (
        'launch:\n'
        '  - node:\n'
        '      pkg: demo_pkg\n'
        '      exec: talker\n'
        '      name: talker\n'
        '      param:\n'
        '        - {name: rate, value: 2.0}\n'
        '  - group:\n'
        '      children:\n'
        '        - push-ros-namespace: {namespace: ui}\n'
        '        - node:\n'
        '            pkg: demo_pkg\n'
        '            exec: listener\n'
        '            name: listener\n'
        '            remap:\n'
        '              - {from: messages, to: /chatter}\n')
    shown = nodl('show', path, '--format', 'json')
    assert shown.returncode == 0, shown.stderr
    data = json.loads(shown.stdout)
    assert [n['fqn'] for n in data['nodes']] == ['/talker', '/ui/listener']
    assert any(c['from']['final_name'] == '/chatter' and c['to']['node'] == data['nodes'][1]['id']
               for c in data['connections'])


def test_refusals_change_nothing_and_say_why(tmp_path: Path) -> None:
    path = str(copy_launch(tmp_path) / 'demo.launch.xml')
    before = Path(path).read_text(encoding='utf-8')
    done = nodl('set', path, 'talker', 'rate', '1000.0')
    assert done.returncode == 1
    assert 'error: rate = 1000.0 is refused' in done.stdout and '[NODL977]' in done.stdout
    missing = nodl('set', path, 'nobody', 'rate', '1.0')
    assert missing.returncode == 2 and '[NODL970]' in missing.stdout
    assert nodl('new', path).returncode == 2
    assert Path(path).read_text(encoding='utf-8') == before
    sarif = nodl('connect', path, 'talker:chatter', 'counter:count', '--format', 'sarif')
    assert sarif.returncode == 1
    assert json.loads(sarif.stdout)['runs'][0]['results'][0]['ruleId'] == 'NODL973'


def test_dry_run_prints_and_writes_nothing(tmp_path: Path) -> None:
    path = str(copy_launch(tmp_path) / 'demo.launch.py')
    before = Path(path).read_text(encoding='utf-8')
    done = nodl('add', path, 'demo_pkg', 'listener', '--name', 'extra', '--dry-run')
    assert done.returncode == 0, done.stderr
    assert "        Node(\n            package='demo_pkg',\n            executable='listener',\n" \
           "            name='extra',\n        ),\n    ])\n" in done.stdout
    assert Path(path).read_text(encoding='utf-8') == before


def test_rename_and_remap(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = str(copy_launch(tmp_path) / 'rules.launch.xml')
    renamed = nodl('rename', path, 'talker', '--namespace', '/robot')
    assert renamed.returncode == 0, renamed.stderr
    assert renamed.stdout == f'renamed /talker to /robot/talker; {path} saved\n'
    assert '<node pkg="demo_pkg" exec="talker" name="talker" namespace="/robot"/>' in \
        Path(path).read_text(encoding='utf-8')
    before = Path(path).read_text(encoding='utf-8')
    refused = nodl('remap', path, 'listener', 'messages:=/robot/chatter', 'nonsense')
    assert refused.returncode == 1
    assert "rule 2 'nonsense' is not FROM:=TO" in refused.stdout and '[NODL988]' in refused.stdout
    assert Path(path).read_text(encoding='utf-8') == before
    remapped = nodl('remap', path, 'listener', 'messages:=/robot/chatter', '--format', 'json')
    assert remapped.returncode == 0, remapped.stderr
    data = json.loads(remapped.stdout)
    assert data['saved'] and data['remaps'] == [{'node': 'n1', 'from': 'messages',
                                                 'to': '/robot/chatter'}]
    assert len(data['removed']) == 2
    assert '<remap from="$(var topic)" to="messages"/>\n' \
           '    <remap from="messages" to="/robot/chatter"/>\n' in Path(path).read_text(encoding='utf-8')
    # what is so already is not written again, and not said to be saved (in process)
    mtime = os.stat(path).st_mtime_ns
    assert main(['system', 'rename', path, 'talker', '--namespace', '/robot', '--definitions',
                 str(DEFINITIONS)]) == 0
    assert capsys.readouterr().out == \
        f'/robot/talker: the name and namespace are unchanged; {path} unchanged\n'
    assert os.stat(path).st_mtime_ns == mtime
    # rename without --name or --namespace is a usage error (in process: no file is read)
    assert main(['system', 'rename', path, 'talker']) == 2
    assert 'give --name, --namespace or both' in capsys.readouterr().err
