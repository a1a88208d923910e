"""The test run's own isolation (tests/conftest.py): a ROS domain per parallel worker,
modules handed out costliest first, and no node outliving the process that started it."""

from __future__ import annotations

import json
import os
import selectors
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import conftest
from conftest import DURATIONS, NODES, costliest_first, module_costs

pytest_plugins = ['pytester']


# --- a ROS domain per xdist worker ------------------------------------------------------

def test_each_worker_adds_its_index_to_the_base_domain() -> None:
    assert conftest._worker_domain('57', 'gw0') == '57'
    assert conftest._worker_domain('57', 'gw3') == '60'
    assert conftest._worker_domain('100', 'gw2') == '0'  # stays within 0-101


def test_without_xdist_the_domain_is_the_base() -> None:
    assert conftest._worker_domain('57', None) == '57'
    assert conftest._worker_domain('57', '') == '57'


def test_a_domain_with_a_participant_is_in_use_and_skipped() -> None:
    """A real node in a domain makes the probe say so, and the choice of a run's domains
    steps over it; once the node is gone, the domain is free again."""
    base = conftest._free_domain_base(40, count=2)
    assert not conftest._domain_in_use(base)
    env = dict(os.environ, ROS_DOMAIN_ID=str(base))
    node = subprocess.Popen(
        [sys.executable, '-c', 'import rclpy, sys; rclpy.init(); n = rclpy.create_node("probe_me"); '
                               'print("ready", flush=True); sys.stdin.read()'],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert node.stdout is not None and node.stdout.readline().strip() == 'ready'
        assert conftest._domain_in_use(base)
        assert conftest._free_domain_base(base, count=2) not in (base - 1, base)
    finally:
        node.communicate('', timeout=20)
    assert not conftest._domain_in_use(base)


def test_this_process_uses_its_workers_domain() -> None:
    """In this very run: the domain rclpy sees is the base plus this worker's index."""
    base = int(os.environ['NODL_TEST_ROS_DOMAIN_BASE'])
    worker = os.environ.get('PYTEST_XDIST_WORKER', '')
    index = int(worker[2:]) if worker.startswith('gw') else 0
    assert os.environ['ROS_DOMAIN_ID'] == str((base + index) % 102)
    assert os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] == 'LOCALHOST'


# --- the order in which workers are given the modules -----------------------------------

def test_the_costliest_module_comes_first_and_an_unknown_one_before_all() -> None:
    costs = {'test_quick.py': 0.5, 'test_build.py': 40.0, 'test_live.py': 12.0}
    modules = ['test_quick.py', 'test_live.py', 'test_new.py', 'test_build.py']
    assert costliest_first(modules, costs) == ['test_new.py', 'test_build.py', 'test_live.py',
                                               'test_quick.py']


def test_equal_costs_keep_the_file_order() -> None:
    assert costliest_first(['b.py', 'a.py', 'c.py'], {'a.py': 1, 'b.py': 1, 'c.py': 1}) == [
        'b.py', 'a.py', 'c.py']


def test_the_recorded_durations_are_seconds_per_module() -> None:
    # (a module since removed may stay listed: it only no longer takes part in the order)
    costs = module_costs()
    assert costs, f'{DURATIONS} is missing or empty'
    assert all(name.startswith('test_') and name.endswith('.py') for name in costs)
    assert all(value >= 0 for value in costs.values())
    assert costs == json.loads(DURATIONS.read_text(encoding='utf-8'))  # plain JSON, as recorded


def test_a_worker_collects_the_modules_costliest_first(pytester: pytest.Pytester) -> None:
    """A real xdist run of three modules on one worker: they run in the recorded order."""
    source = Path(conftest.__file__).read_text(encoding='utf-8')
    recorded = "DURATIONS = Path(__file__).parent / 'durations.json'"
    assert recorded in source
    pytester.makeconftest(source.replace(recorded, "DURATIONS = Path(__file__).parent / 'costs.json'"))
    (pytester.path / 'costs.json').write_text(json.dumps({
        'test_a.py': 1.0, 'test_b.py': 30.0, 'test_c.py': 5.0}), encoding='utf-8')
    for name in 'abc':
        pytester.makepyfile(**{f'test_{name}': f'def test_{name}1(): pass\ndef test_{name}2(): pass\n'})
    result = pytester.runpytest_subprocess('-n', '1', '--dist', 'loadfile', '--no-loadscope-reorder',
                                           '-v', '-p', 'no:cacheprovider', timeout=120)
    result.assert_outcomes(passed=6)
    ran = [line.split('::')[1].split()[0] for line in result.outlines if 'PASSED' in line]
    assert ran == ['test_b1', 'test_b2', 'test_c1', 'test_c2', 'test_a1', 'test_a2']


# --- nodes end with the process that started them ---------------------------------------

def _alive(pid: int) -> bool:
    """The process runs (a zombie waiting for its new parent to reap it has ended)."""
    try:
        state = Path(f'/proc/{pid}/stat').read_text().rpartition(')')[2].split()[0]
    except (FileNotFoundError, ProcessLookupError, IndexError):
        return False
    return state not in ('Z', 'X')


def test_a_node_ends_when_the_test_process_is_killed() -> None:
    """A run stopped half-way (SIGKILL: no fixture teardown) leaves no node behind."""
    starter = subprocess.Popen(
        [sys.executable, '-c',
         ('import sys; sys.path.insert(0, sys.argv[1]); from conftest import NodeProcess; '
          "node = NodeProcess('plain_node.py', 'orphan_probe', '/conftest_test'); "
          'print(node.process.pid, flush=True); sys.stdin.read()'),
         str(Path(conftest.__file__).parent)],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, cwd=NODES)
    try:
        assert starter.stdout is not None
        selector = selectors.DefaultSelector()
        selector.register(starter.stdout, selectors.EVENT_READ)
        assert selector.select(timeout=60), 'the node did not start within 60 s'
        node_pid = int(starter.stdout.readline())
        os.kill(node_pid, 0)  # the node runs
        starter.send_signal(signal.SIGKILL)
        starter.wait(timeout=10)
        deadline = time.monotonic() + 15
        while time.monotonic() < deadline and _alive(node_pid):
            time.sleep(0.05)
        if not _alive(node_pid):
            return
        os.kill(node_pid, signal.SIGKILL)
        pytest.fail('the node outlived the process that started it')
    finally:
        if starter.poll() is None:
            starter.kill()
            starter.wait(timeout=10)
        for stream in (starter.stdin, starter.stdout):
            if stream is not None:
                stream.close()
