"""Python's cyclic garbage collector, paused while a large batch is built.

An analysis of a launched system (or a policy of one) allocates hundreds of
thousands of small objects (parsed documents, models, entities, instances)
that all live until the batch ends, and none of which form reference cycles
(they are freed by reference counting as soon as they are let go; tests keep
it so).  With the collector running, every object that survives is walked
by a young-generation collection and again by a middle-generation one, to
find cycles that are not there: a seventh of a 1,000-node analysis.

:func:`batch_collection` therefore pauses automatic collection for the batch.
When the last batch ends, the objects the batch left alive go straight to the
oldest generation (``gc.freeze()`` then ``gc.unfreeze()``: a move, not a
walk), where only the rare full collections look at them, and collection
resumes.  The move applies to every object alive at that moment, so other
young objects of the program are promoted too (cyclic garbage among them is
freed by the next full collection instead of a young one).  A program that
keeps objects frozen itself (``gc.freeze()`` before forking) is left alone:
its frozen objects stay frozen, the batch's objects are walked as usual.  A
collector the program has disabled stays disabled.
"""

from __future__ import annotations

import gc
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ['batch_collection']

_lock = threading.Lock()
_depth = 0
_paused = False


@contextmanager
def batch_collection() -> Iterator[None]:
    """Pause automatic garbage collection inside the block (see the module docstring);
    nested and concurrent blocks resume it once, when the last one ends."""
    global _depth, _paused
    with _lock:
        if _depth == 0 and gc.isenabled():
            gc.disable()
            _paused = True
        _depth += 1
    try:
        yield
    finally:
        with _lock:
            _depth -= 1
            if _depth == 0 and _paused:
                _paused = False
                if gc.get_freeze_count() == 0:
                    gc.freeze()
                    gc.unfreeze()
                gc.enable()
