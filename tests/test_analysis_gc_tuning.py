"""The collector's thresholds during a batch (nodl_schema.analysis.gc_tuning)."""

from __future__ import annotations

import gc
import threading
from typing import Iterator

import pytest

from nodl_schema.analysis.gc_tuning import BATCH_THRESHOLD, batch_collection


@pytest.fixture(autouse=True)
def default_thresholds() -> Iterator[None]:
    saved = gc.get_threshold()
    gc.set_threshold(700, 10, 10)
    yield
    gc.set_threshold(*saved)


def test_a_batch_collects_less_often_and_restores_the_thresholds() -> None:
    with batch_collection():
        assert gc.get_threshold() == (BATCH_THRESHOLD, 10, 10)
        with batch_collection():
            assert gc.get_threshold() == (BATCH_THRESHOLD, 10, 10)
        assert gc.get_threshold() == (BATCH_THRESHOLD, 10, 10)  # the outer block still runs
    assert gc.get_threshold() == (700, 10, 10)


def test_thresholds_are_restored_when_the_batch_raises() -> None:
    with pytest.raises(RuntimeError):
        with batch_collection():
            raise RuntimeError('boom')
    assert gc.get_threshold() == (700, 10, 10)


@pytest.mark.parametrize('threshold', [(0, 10, 10), (BATCH_THRESHOLD * 2, 5, 5)])
def test_a_disabled_collector_or_higher_thresholds_are_left_alone(threshold: tuple[int, int, int]) -> None:
    gc.set_threshold(*threshold)
    with batch_collection():
        assert gc.get_threshold() == threshold
    assert gc.get_threshold() == threshold


def test_concurrent_batches_restore_once_the_last_one_ends() -> None:
    inside, release = threading.Event(), threading.Event()

    def other() -> None:
        with batch_collection():
            inside.set()
            release.wait(timeout=30)

    thread = threading.Thread(target=other)
    with batch_collection():
        thread.start()
        assert inside.wait(timeout=30)
    assert gc.get_threshold() == (BATCH_THRESHOLD, 10, 10)  # the other thread's batch still runs
    release.set()
    thread.join(timeout=30)
    assert not thread.is_alive() and gc.get_threshold() == (700, 10, 10)
