"""Garbage collection paused during a batch (nodl.system.gc_tuning), and the
analysis's own promise that makes the pause safe: it forms no reference cycles."""

from __future__ import annotations

import gc
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest

from nodl.analysis import analyse_launch
from nodl.system.gc_tuning import batch_collection

PREFIX = [str(Path(__file__).parent / 'fixtures' / 'analysis' / 'prefix')]


@pytest.fixture(autouse=True)
def collector_enabled() -> Iterator[None]:
    was = gc.isenabled()
    gc.enable()
    yield
    if not was:
        gc.disable()


def test_a_batch_pauses_collection_and_resumes_it() -> None:
    with batch_collection():
        assert not gc.isenabled()
        with batch_collection():
            assert not gc.isenabled()
        assert not gc.isenabled()  # the outer block still runs
    assert gc.isenabled()


def test_collection_resumes_when_the_batch_raises() -> None:
    with pytest.raises(RuntimeError), batch_collection():
        raise RuntimeError('boom')
    assert gc.isenabled()


def test_a_collector_the_program_disabled_stays_disabled() -> None:
    gc.disable()
    with batch_collection():
        assert not gc.isenabled()
    assert not gc.isenabled()


def test_what_the_batch_leaves_alive_goes_to_the_oldest_generation() -> None:
    with batch_collection():
        kept = [[index] for index in range(100)]
    assert gc.get_count()[0] < 100  # no young generation full of the batch's objects
    oldest = {id(o) for o in gc.get_objects(generation=2)}
    assert id(kept) in oldest and all(id(item) in oldest for item in kept)


def test_objects_the_program_froze_stay_frozen() -> None:
    marker = [[0]]  # frozen below: in no generation the collector walks
    gc.freeze()
    try:
        assert gc.get_freeze_count() > 0
        with batch_collection():
            kept = [[index] for index in range(100)]
        tracked = {id(o) for o in gc.get_objects()}
        assert id(marker) not in tracked  # still frozen: the batch did not unfreeze
        assert id(kept) in tracked  # the batch's objects are walked as usual
        assert gc.isenabled()
    finally:
        gc.unfreeze()


def test_concurrent_batches_resume_once_the_last_one_ends() -> None:
    inside, release = threading.Event(), threading.Event()

    def other() -> None:
        with batch_collection():
            inside.set()
            release.wait(timeout=30)

    thread = threading.Thread(target=other)
    with batch_collection():
        thread.start()
        assert inside.wait(timeout=30)
    assert not gc.isenabled()  # the other thread's batch still runs
    release.set()
    thread.join(timeout=30)
    assert not thread.is_alive() and gc.isenabled()


def _cyclic_garbage_of_an_analysis(tmp_path: Path, nodes: int) -> int:
    launch = tmp_path / f'n{nodes}.launch.xml'
    launch.write_text('<launch>\n' + ''.join(
        f'  <node pkg="nav" exec="planner" name="p{i}"><param name="speed" value="{i}"/></node>\n'
        f'  <node pkg="sensors" exec="imu_filter" name="imu{i}" namespace="/r{i}"/>\n'
        for i in range(nodes)) + '</launch>\n')
    gc.collect()
    gc.disable()
    try:
        analysis = analyse_launch(launch, prefixes=PREFIX)
        assert len(analysis.nodes) == 2 * nodes
        del analysis
        return gc.collect()  # what reference counting could not free: cycles
    finally:
        gc.enable()


def test_an_analysis_forms_no_reference_cycles_per_node(tmp_path: Path) -> None:
    # The pause is safe because an analysis is freed by reference counting: only a fixed
    # handful of objects per run (the shared base layer) may need the collector, however
    # many nodes are launched.
    few = _cyclic_garbage_of_an_analysis(tmp_path, 5)
    many = _cyclic_garbage_of_an_analysis(tmp_path, 50)
    assert many == few and few < 500
