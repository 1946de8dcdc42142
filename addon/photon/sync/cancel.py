"""Esc during a sync: RenderEngine.test_break() (Esc, or Ctrl-C in background mode) is polled
while the depsgraph is read, and a true reading stops the sync with SyncCancelled.

A scene of a million geometry-node instances takes most of a minute to sync, tens of
microseconds per instance in Python, so the sync polls every POLL_EVERY instances and after each
slow step (a mesh, a run of hair strands, a chunk of instances placed): a cancel stops it within
a few tens of milliseconds, plus drain()'s ~0.2 s per million instances not yet read. A poll
costs ~0.1 us (RenderEngine.test_break) every ~25 ms, and reading the instances through
instances() ~20 ns each, against ~25 us each for the sync: under 0.2% in all."""

import collections
import itertools
import time

# Instances read between two polls: 1000 x ~25 us = ~25 ms of sync.
POLL_EVERY = 1000
_END = object()  # next()'s default: the iteration is over


class SyncCancelled(Exception):
    """The sync stopped because test_break() became true; `at` is when (perf_counter)."""

    def __init__(self):
        super().__init__("sync cancelled")
        self.at = time.perf_counter()


class SyncPoll:
    """Calling it raises SyncCancelled once `test_break()` is true (never without test_break:
    previews, bakes and the viewport sync to the end). instances() reads
    depsgraph.object_instances polling as it goes; drain() must follow a sync that stopped."""

    def __init__(self, test_break=None):
        self._test_break = test_break
        self._iterator = None  # the object_instances iteration under way

    def __call__(self):
        if self._test_break is not None and self._test_break():
            raise SyncCancelled()

    def instances(self, depsgraph):
        """depsgraph.object_instances, polled before every POLL_EVERY items."""
        iterator = self._iterator = iter(depsgraph.object_instances)
        while True:
            self()
            first = next(iterator, _END)
            if first is _END:
                break
            yield first
            # The run after the first item straight from C: 16 ns an item where counting
            # items in Python cost 50 (a sync spends ~25 us on each).
            yield from itertools.islice(iterator, POLL_EVERY - 1)
        self._iterator = None

    def drain(self):
        """Runs an iteration left halfway to its end. Blender 3.4 frees an object's list of
        instances only when iteration passes its end (DEG_iterator_objects_end does not), and
        builds the next object's list as it reaches the object: a sync stopped halfway leaked
        44 MB for 200k geometry-node instances. Without a Python loop this costs ~0.2 s for a
        million instances left."""
        iterator, self._iterator = self._iterator, None
        if iterator is not None:
            try:
                collections.deque(iterator, maxlen=0)
            except Exception:  # noqa: BLE001 - the error that stopped the sync is the one to tell
                pass
