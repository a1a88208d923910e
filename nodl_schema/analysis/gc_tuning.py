"""Python's cyclic garbage collector, tuned while a large batch is built.

An analysis of a launched system allocates millions of small objects (parsed
documents, models, entities, instances) that all live until the analysis
ends.  With the default thresholds the collector runs every 700 allocations
and keeps scanning that growing heap for cycles that are not there: a third
of the time of a 1,000-node analysis.  :func:`batch_collection` raises the
first threshold for the duration of the batch (the collector still runs,
about seventy times less often) and restores it afterwards.
"""

from __future__ import annotations

import gc
import threading
from contextlib import contextmanager
from typing import Iterator

__all__ = ['batch_collection', 'BATCH_THRESHOLD']

#: The first-generation threshold during a batch (allocations between collections).
BATCH_THRESHOLD = 50_000

_lock = threading.Lock()
_depth = 0
_saved: tuple[int, ...] = ()


@contextmanager
def batch_collection() -> Iterator[None]:
    """Collect less often inside the block; nested and concurrent blocks restore the
    thresholds once, when the last one ends.  A disabled collector (threshold 0, or
    ``gc.disable()``) and higher thresholds set by the program are left as they are."""
    global _depth, _saved
    with _lock:
        if _depth == 0:
            _saved = gc.get_threshold()
            if 0 < _saved[0] < BATCH_THRESHOLD:
                gc.set_threshold(BATCH_THRESHOLD, *_saved[1:])
        _depth += 1
    try:
        yield
    finally:
        with _lock:
            _depth -= 1
            if _depth == 0:
                gc.set_threshold(*_saved)
