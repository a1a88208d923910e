"""`nodl list`: run as a real process, as users run it."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from conftest import FIXTURES, REPO

INDEX = FIXTURES / 'index'
FIRST = str(INDEX / 'first')
SECOND = str(INDEX / 'second')
BOTH = os.pathsep.join([FIRST, SECOND])


def nodl(*args: str, prefixes: str | None = BOTH) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    if prefixes is None:
        env.pop('AMENT_PREFIX_PATH', None)
    else:
        env['AMENT_PREFIX_PATH'] = prefixes
    return subprocess.run([sys.executable, '-m', 'nodl', 'list', *args], cwd=REPO,
                          env=env, text=True, capture_output=True, timeout=60)


def rows(stdout: str) -> list[tuple[str, ...]]:
    """package, kind, name, file (the origin column, tested on its own, left out)."""
    return [tuple(line.split()[:3] + line.split()[4:]) for line in stdout.splitlines()]


def test_lists_every_registration_sorted() -> None:
    result = nodl()
    assert result.returncode == 0, result.stderr
    assert result.stderr == ''
    share = lambda prefix, pkg, f: os.path.join(prefix, 'share', pkg, 'nodl', f)  # noqa: E731
    entry = lambda prefix, t, n: os.path.join(prefix, 'share', 'ament_index',  # noqa: E731
                                              'resource_index', t, n)
    assert rows(result.stdout) == [
        ('alpha', 'interface', 'chatter', share(FIRST, 'alpha', 'chatter.nodl.yaml')),
        ('alpha', 'node', 'inline', entry(FIRST, 'nodl_nodes', 'alpha__inline')),
        ('alpha', 'node', 'listener', share(SECOND, 'alpha', 'listener.nodl.yaml')),
        ('alpha', 'node', 'talker', share(FIRST, 'alpha', 'talker.nodl.yaml')),
        ('beta', 'node', 'node', share(SECOND, 'beta', 'node.nodl.yaml')),
        ('beta', 'interface', 'status', share(SECOND, 'beta', 'status.nodl.yaml')),
        ('delta', 'node', 'dangling', entry(FIRST, 'nodl_nodes', 'delta__dangling')),
    ]


def test_columns_are_aligned() -> None:
    lines = nodl().stdout.splitlines()
    assert lines[0].startswith('alpha' + ' ' * (25 - len('alpha')) + 'interface')
    assert len({line.index('/') for line in lines}) == 1  # the file column starts at one place


def test_one_package() -> None:
    result = nodl('beta')
    assert result.returncode == 0
    assert [r[:3] for r in rows(result.stdout)] == [('beta', 'node', 'node'),
                                                    ('beta', 'interface', 'status')]


def test_first_prefix_wins() -> None:
    swapped = os.pathsep.join([SECOND, FIRST])
    talker = [r for r in rows(nodl('alpha', prefixes=swapped).stdout) if r[2] == 'talker']
    assert talker == [('alpha', 'node', 'talker',
                       os.path.join(SECOND, 'share', 'alpha', 'nodl', 'talker.nodl.yaml'))]


def test_json_format() -> None:
    result = nodl('--format', 'json')
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert [(d['package'], d['name'], d['kind']) for d in data] == [
        ('alpha', 'chatter', 'interface'), ('alpha', 'inline', 'node'),
        ('alpha', 'listener', 'node'), ('alpha', 'talker', 'node'), ('beta', 'node', 'node'),
        ('beta', 'status', 'interface'), ('delta', 'dangling', 'node')]
    assert set(data[0]) == {'package', 'name', 'kind', 'file', 'origin', 'folder', 'provenance'}
    assert {(d['origin'], d['folder'], d['provenance']) for d in data} == {('index', None, None)}
    assert json.loads(nodl('zeta', '--format', 'json').stdout) == []


def test_nothing_registered_says_so_on_stderr_and_exits_0() -> None:
    result = nodl(prefixes=None)
    assert (result.returncode, result.stdout) == (0, '')
    assert result.stderr == 'no NoDL definitions registered (AMENT_PREFIX_PATH: empty)\n'
    result = nodl('zeta')
    assert (result.returncode, result.stdout) == (0, '')
    assert result.stderr == (f"no NoDL definitions registered for package 'zeta' "
                             f'(AMENT_PREFIX_PATH: {BOTH})\n')


def test_bad_arguments_are_usage_errors() -> None:
    assert nodl('--format', 'xml').returncode == 2
    assert nodl('a', 'b').returncode == 2


def test_kind_keeps_one_kind_of_definition() -> None:
    interfaces = nodl('--kind', 'interface')
    assert interfaces.returncode == 0, interfaces.stderr
    assert {(r[0], r[1], r[2]) for r in rows(interfaces.stdout)} == {
        ('alpha', 'interface', 'chatter'), ('beta', 'interface', 'status')}
    nodes = nodl('--kind', 'node', '--format', 'json')
    assert nodes.returncode == 0, nodes.stderr
    kinds = {entry['kind'] for entry in json.loads(nodes.stdout)}
    assert kinds and 'interface' not in kinds and kinds <= {'node', 'legacy node'}


def test_kind_with_nothing_to_list_says_which_kind() -> None:
    result = nodl('--kind', 'interface', 'delta')
    assert result.returncode == 0 and result.stdout == ''
    assert "no interface definitions registered for package 'delta'" in result.stderr


def test_lists_what_the_references_ament_nodl_register_installed() -> None:
    reference = str(INDEX / 'reference')
    result = nodl('ref_robot', prefixes=reference)
    assert result.returncode == 0, result.stderr
    entry = os.path.join(reference, 'share', 'ament_index', 'resource_index', 'nodl', 'ref_robot__')
    assert rows(result.stdout) == [('ref_robot', 'node', name, entry + name)
                                   for name in ('lidar', 'listener', 'sensor_common', 'talker')]
    everything = json.loads(nodl('--format', 'json', prefixes=reference).stdout)
    assert ('custom_pkg', 'custom_exe') in {(r['package'], r['name']) for r in everything}


OVERLAYS = FIXTURES / 'overlays'


def test_definitions_folders_come_first_with_their_origin() -> None:
    defs = str(OVERLAYS / 'defs')
    prefix = str(FIXTURES / 'analysis' / 'prefix')
    result = nodl('--definitions', defs, prefixes=prefix)
    assert result.returncode == 0, result.stderr
    origins = {(line.split()[0], line.split()[2]): line.split()[3] for line in result.stdout.splitlines()}
    assert origins[('nav', 'controller')] == 'overlay(extracted)'   # shadows the index's
    assert origins[('nav', 'planner')] == 'index'
    assert origins[('upstream_drv', 'fusion')] == 'overlay(described)'
    assert origins[('upstream_drv', 'status')] == 'overlay'
    data = json.loads(nodl('nav', '--definitions', defs, '--format', 'json', prefixes=prefix).stdout)
    assert [(d['name'], d['origin'], d['folder'], d['provenance']) for d in data] == [
        ('controller', 'overlay', defs, 'extracted'), ('planner', 'index', None, None)]


def test_a_bad_folder_is_reported_and_exit_1() -> None:
    result = nodl('--definitions', str(OVERLAYS / 'bad'), prefixes=None)
    assert result.returncode == 1
    assert '[NODL243]' in result.stderr and '[NODL242]' in result.stderr
    assert rows(result.stdout) == [('my_pkg', 'node', 'node',
                                    str(OVERLAYS / 'bad' / 'my_pkg' / 'node.nodl.yaml'))]
    assert nodl('--definitions', 'nowhere').returncode == 2
