"""Syncs the open scene with photon's sync_scene twice, with a stand-in for
RenderEngine.test_break: once recording when it is polled (always false), once turning true at
poll CANCEL_AT. Args: RESULT_PATH CANCEL_AT

Returns the instance count, the sync's time, the number of polls, the time to the first poll
and the longest stretch without one after it (between polls, and from the last to the end), and
for the cancelled sync what it raised and how long after the true reading it returned."""

import time

import bpy

import harness


class Recorder:
    """test_break() that notes when it is called; true from call `true_at` on (0: never)."""

    def __init__(self, true_at=0):
        self.times = []
        self.true_at = true_at

    def __call__(self):
        self.times.append(time.perf_counter())
        return 0 < self.true_at <= len(self.times)


def main(cancel_at):
    from photon import report, sync
    from photon.native import native_module
    native = native_module()
    depsgraph = bpy.context.evaluated_depsgraph_get()

    polls = Recorder()
    t0 = time.perf_counter()
    _, stats = sync.sync_scene(native, depsgraph, report.Reporter(), test_break=polls)
    t1 = time.perf_counter()
    stats.release()
    # Up to the first poll Blender builds the instance list in iter(depsgraph.object_instances),
    # which no poll can split: that stretch is reported apart from the sync's own.
    marks = [*polls.times, t1]
    result = {"instances": stats.instances, "seconds": t1 - t0, "polls": len(polls.times),
              "first_poll": polls.times[0] - t0 if polls.times else t1 - t0,
              "longest_gap": max(b - a for a, b in zip(marks, marks[1:]))}

    cancel = Recorder(int(cancel_at))
    try:
        sync.sync_scene(native, depsgraph, report.Reporter(), test_break=cancel)
        result["cancel"] = "not raised"
    except Exception as exc:  # noqa: BLE001 - the test checks what it was
        result["cancel"] = type(exc).__name__
        result["stopped_after"] = time.perf_counter() - cancel.times[-1]
    return result


harness.run(main)
