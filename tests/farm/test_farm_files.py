"""The farm's file handling without Slurm: a render task (`farm.py _task`, run here directly with
the environment Slurm gives it) whose Blender reports success but wrote a truncated image, or
whose done marker cannot be written, fails with a clear message instead of renaming the damage
into place or dying with a traceback; a FIFO where the manifest belongs is refused at once; and
tools/farm_lib/files.py's checked writes keep the old file when the disk is full.

    /usr/bin/python3 -m pytest -q tests/farm/test_farm_files.py
"""

import json
import os
import re
import stat
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from small_disk import fill, mount_tmpfs, unmount

REPO = Path(__file__).resolve().parents[2]
FARM = REPO / "tools" / "farm.py"
sys.path.insert(0, str(REPO / "tools"))

WIDTH, HEIGHT = 48, 40

# Stands in for Blender in a render task: writes the image named by $FAKE_IMAGE (the first
# $FAKE_BYTES bytes of it, when set) where `-o PREFIX -f N` says, and reports success as Blender
# does even when its write failed.
FAKE_BLENDER = r"""#!/bin/sh
while [ $# -gt 0 ]; do
  case "$1" in
    -o) prefix="$2"; shift ;;
    -f) frame="$2"; shift ;;
  esac
  shift
done
out="$prefix$(printf %04d "$frame").exr"
if [ -n "$FAKE_BYTES" ]; then
  head -c "$FAKE_BYTES" "$FAKE_IMAGE" > "$out"
else
  cp "$FAKE_IMAGE" "$out"
fi
echo "fake Blender: PHOTON_PREPARED_LOAD=${PHOTON_PREPARED_LOAD-unset}"
echo "Photon: rendered frame $frame"
echo "Saved: '$out'"
exit 0
"""


def write_exr(path):
    import OpenImageIO as oiio
    pixels = np.linspace(0.0, 1.0, WIDTH * HEIGHT * 4, dtype=np.float32).reshape(HEIGHT, WIDTH, 4)
    out = oiio.ImageOutput.create(str(path))
    assert out.open(str(path), oiio.ImageSpec(WIDTH, HEIGHT, 4, oiio.HALF))
    assert out.write_image(pixels)
    assert out.close()


@pytest.fixture
def task(tmp_path):
    """A one-frame submission's job folder and manifest, rendered by FAKE_BLENDER."""
    job_dir = tmp_path / ".farm" / "job-test"
    for sub in ("logs", "bands", "tmp", "done", "state"):
        (job_dir / sub).mkdir(parents=True)
    blender = tmp_path / "fake_blender"
    blender.write_text(FAKE_BLENDER)
    blender.chmod(0o755)
    image = tmp_path / "image.exr"
    write_exr(image)
    manifest = {"blend": str(tmp_path / "scene.blend"), "blender": str(blender),
                "addon_dir": str(tmp_path), "python": sys.executable, "frames": [3],
                "paths": [str(tmp_path / "frame_0003.exr")], "split": 1,
                "rows": [[0, HEIGHT]], "width": WIDTH, "height": HEIGHT,
                "file_format": "OPEN_EXR", "band_format": "OPEN_EXR", "color_mode": "RGBA",
                "quality": 90, "retries": 0, "shared_prepare": False, "job_dir": str(job_dir)}
    (job_dir / "manifest.json").write_text(json.dumps(manifest))
    return job_dir, image, Path(manifest["paths"][0])


def run_task(job_dir, image, **env):
    # What Slurm sets for array task 0 on its first attempt (no SLURM_JOB_ID: nothing to
    # re-queue).
    env = dict(os.environ, SLURM_ARRAY_TASK_ID="0", SLURM_RESTART_COUNT="0",
               FAKE_IMAGE=str(image), **env)
    for name in ("SLURM_JOB_ID", "SLURM_ARRAY_JOB_ID"):
        env.pop(name, None)
    proc = subprocess.run([sys.executable, str(FARM), "_task", str(job_dir / "manifest.json")],
                          env=env, capture_output=True, text=True, timeout=60,
                          stdin=subprocess.DEVNULL)
    proc.log = proc.stdout + proc.stderr
    return proc


def test_task_places_a_good_frame(task):
    job_dir, image, frame = task
    proc = run_task(job_dir, image)
    assert proc.returncode == 0, proc.log
    assert frame.read_bytes() == image.read_bytes()
    assert (job_dir / "done" / "task_0").read_text() == str(frame)
    assert not any((job_dir / "tmp").iterdir())


def test_truncated_image_fails_the_task(task):
    """Blender ran out of disk while saving, said "Saved" and exited 0: the task must not
    rename the truncated file into place, and must fail with the reason."""
    job_dir, image, frame = task
    proc = run_task(job_dir, image, FAKE_BYTES=str(image.stat().st_size // 2))
    assert proc.returncode == 1, proc.log
    assert "farm: error: frame 3" in proc.stdout and "damaged or incomplete" in proc.stdout, \
        proc.log
    assert "Traceback" not in proc.log, proc.log
    assert not frame.exists()
    assert not (job_dir / "done" / "task_0").exists()
    # The damaged file is gone (on a full disk, it holds the room the log line needs).
    assert not list((job_dir / "tmp").rglob("*.exr"))


def test_done_marker_in_the_way_fails_the_task(task):
    job_dir, image, frame = task
    (job_dir / "done" / "task_0").mkdir()
    proc = run_task(job_dir, image)
    assert proc.returncode == 1, proc.log
    assert "farm: error: done marker" in proc.stdout and "is a directory" in proc.stdout, \
        proc.log
    assert "Traceback" not in proc.log, proc.log


def test_full_disk_for_the_done_marker_fails_the_task(task):
    job_dir, image, frame = task
    done = job_dir / "done"
    mount_tmpfs(done, "16k")
    try:
        fill(done)
        proc = run_task(job_dir, image)
        assert proc.returncode == 1, proc.log
        assert "farm: error: cannot write done marker" in proc.stdout, proc.log
        assert "No space left on device" in proc.stdout, proc.log
        assert "Traceback" not in proc.log, proc.log
        assert [p.name for p in done.iterdir()] == ["filler"]
    finally:
        unmount(done)


def test_manifest_fifo_is_refused_without_blocking(task):
    job_dir, image, _ = task
    manifest = job_dir / "manifest.json"
    manifest.unlink()
    os.mkfifo(manifest)
    proc = run_task(job_dir, image)  # a blocking open would hit run_task's timeout
    assert proc.returncode == 1, proc.log
    assert "is a FIFO, not a regular file" in proc.stdout, proc.log
    assert "Traceback" not in proc.log, proc.log


def test_checked_write_on_a_full_disk_keeps_the_old_file(tmp_path):
    from farm_lib import files
    disk = tmp_path / "disk"
    mount_tmpfs(disk, "16k")
    try:
        marker = disk / "marker"
        files.write_text(marker, "old", "marker")
        fill(disk)
        with pytest.raises(files.FileError, match="cannot write marker .*No space left"):
            files.write_text(marker, "new " * 4096, "marker")
        assert marker.read_text() == "old"
        assert sorted(p.name for p in disk.iterdir()) == ["filler", "marker"]
    finally:
        unmount(disk)


def test_checked_access_refuses_what_is_not_a_regular_file(tmp_path):
    from farm_lib import files
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    folder = tmp_path / "folder"
    folder.mkdir()
    for path, kind in ((fifo, "a FIFO"), (folder, "a directory")):
        with pytest.raises(files.FileError, match=f"is {kind}, not a regular file"):
            files.read_text(path, "manifest")
        with pytest.raises(files.FileError, match=f"exists and is {kind}; refusing"):
            files.write_text(path, "x", "marker")
        with pytest.raises(files.FileError, match=f"is {kind}, not a file; left in place"):
            files.remove(path, "state")
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and folder.is_dir()


def make_odd(path, kind):
    """Puts something other than a good file at `path`."""
    if os.path.lexists(path):
        os.unlink(path)
    if kind == "directory":
        path.mkdir()
        (path / "something").write_text("not the farm's")
    elif kind == "empty":
        path.write_bytes(b"")
    elif kind == "garbage":
        path.write_bytes(b'{"frames": [3], "split": \xff\x00 garbage')
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "device":
        if os.geteuid() != 0:
            pytest.skip("making a device node needs root")
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, 3))  # /dev/null's numbers
    else:
        raise ValueError(kind)


@pytest.mark.parametrize("kind", ["directory", "empty", "garbage", "device", "list"])
@pytest.mark.parametrize("command", ["_task", "_stitch", "_prepare"])
def test_odd_manifest_fails_the_task_with_a_message(task, command, kind):
    """A manifest that is a folder, empty, not JSON, a device, or JSON that is not a farm
    manifest: the task fails at once with a message naming the file, not a traceback."""
    job_dir, image, frame = task
    manifest = job_dir / "manifest.json"
    if kind == "list":
        manifest.write_text("[1, 2, 3]")
    else:
        make_odd(manifest, kind)
    env = dict(os.environ, SLURM_ARRAY_TASK_ID="0", SLURM_RESTART_COUNT="0")
    proc = subprocess.run([sys.executable, str(FARM), command, str(manifest)], env=env,
                          capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)
    log = proc.stdout + proc.stderr
    assert proc.returncode == 1, log
    assert "Traceback" not in log, log
    assert re.search(rf"^farm: error: .*manifest {re.escape(str(manifest))}", proc.stdout,
                     re.M), log
    assert not frame.exists()


@pytest.mark.parametrize("kind", ["directory", "fifo", "device", "good"])
def test_band_refuses_a_state_file_that_is_not_a_file(task, kind):
    """A render task of a submission sharing its preparation hands the frame's state file to
    Blender (PHOTON_PREPARED_LOAD) only when it is a regular file: Photon would block on a FIFO
    or fail on a folder. Otherwise the band prepares itself, and says why."""
    job_dir, image, frame = task
    manifest = json.loads((job_dir / "manifest.json").read_text())
    manifest["shared_prepare"] = True
    (job_dir / "manifest.json").write_text(json.dumps(manifest))
    state = job_dir / "state" / "frame_3.photonstate"
    if kind == "good":
        state.write_bytes(b"PHOTPREP" + bytes(32))
    else:
        make_odd(state, kind)
    proc = run_task(job_dir, image)
    assert proc.returncode == 0, proc.log
    assert "Traceback" not in proc.log, proc.log
    assert frame.read_bytes() == image.read_bytes()
    if kind == "good":
        assert f"fake Blender: PHOTON_PREPARED_LOAD={state}\n" in proc.stdout, proc.log
    else:
        what = {"directory": "a directory", "fifo": "a FIFO",
                "device": "a character device"}[kind]
        assert "fake Blender: PHOTON_PREPARED_LOAD=unset\n" in proc.stdout, proc.log
        assert (f"farm: warning: the frame's shared preparation {state} is {what}, not a "
                f"regular file; refusing it") in proc.stdout, proc.log
        assert "prepared itself (the shared preparation was not used)" in proc.stdout, proc.log
        assert os.path.lexists(state) and not stat.S_ISREG(os.lstat(state).st_mode)


@pytest.fixture
def split_frame(tmp_path):
    """A split submission's job folder whose two bands are rendered and whose shared
    preparation is still there: what the stitch job finds."""
    job_dir = tmp_path / ".farm" / "job-test"
    for sub in ("logs", "bands", "tmp", "done", "state"):
        (job_dir / sub).mkdir(parents=True)
    manifest = {"blend": str(tmp_path / "scene.blend"), "blender": "/bin/false",
                "addon_dir": str(tmp_path), "python": sys.executable, "frames": [3],
                "paths": [str(tmp_path / "frame_0003.exr")], "split": 2,
                "rows": [[0, HEIGHT // 2], [HEIGHT // 2, HEIGHT]], "width": WIDTH,
                "height": HEIGHT, "file_format": "OPEN_EXR", "band_format": "OPEN_EXR",
                "color_mode": "RGBA", "quality": 90, "retries": 0, "shared_prepare": True,
                "job_dir": str(job_dir)}
    (job_dir / "manifest.json").write_text(json.dumps(manifest))
    for band in range(2):
        write_exr(job_dir / "bands" / f"frame_3_band_{band}.exr")
    return job_dir, Path(manifest["paths"][0]), job_dir / "state" / "frame_3.photonstate"


@pytest.mark.parametrize("kind", ["directory", "fifo", "device", "empty", "garbage"])
def test_stitch_survives_an_odd_state_file(split_frame, kind):
    """The frame's shared preparation, which the stitch removes once the frame is stitched, has
    become a folder, a FIFO, a device, an empty or a garbage file: the frame is stitched all the
    same; files are removed, anything else is left in place with a warning."""
    job_dir, frame, state = split_frame
    make_odd(state, kind)
    env = dict(os.environ, SLURM_RESTART_COUNT="0")
    for name in ("SLURM_JOB_ID", "SLURM_ARRAY_JOB_ID", "SLURM_ARRAY_TASK_ID"):
        env.pop(name, None)
    proc = subprocess.run([sys.executable, str(FARM), "_stitch", str(job_dir / "manifest.json")],
                          env=env, capture_output=True, text=True, timeout=60,
                          stdin=subprocess.DEVNULL)
    log = proc.stdout + proc.stderr
    assert proc.returncode == 0, log
    assert "Traceback" not in log, log
    assert "farm: stitched frame 3" in proc.stdout, log
    assert (job_dir / "done" / "frame_3").read_text() == str(frame)
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(str(frame))
    assert inp is not None and (inp.spec().width, inp.spec().height) == (WIDTH, HEIGHT)
    inp.close()
    if kind in ("empty", "garbage"):
        assert not os.path.lexists(state), log
    else:
        what = {"directory": "a directory", "fifo": "a FIFO",
                "device": "a character device"}[kind]
        assert f"farm: warning: the frame's shared preparation {state} is {what}, not a file; " \
               f"left in place" in proc.stdout, log
        assert os.path.lexists(state) and not stat.S_ISREG(os.lstat(state).st_mode)


def test_submissions_larger_than_the_cluster_takes_are_refused(monkeypatch):
    """Slurm's array indices go up to MaxArraySize - 1, and past MaxJobCount (every array task
    counts, and every job the controller holds) sbatch sleeps and retries instead of failing:
    the farm refuses such a submission before queuing anything, whichever layout makes it."""
    from farm_lib import jobs, slurm
    limits = {"MaxArraySize": 1001, "MaxJobCount": 10000}
    held = [0]
    monkeypatch.setattr(slurm, "limits", lambda: dict(limits))
    monkeypatch.setattr(slurm, "job_count", lambda: held[0])

    def check(frames, split, shared):
        jobs.check_capacity(frames, split, shared)

    assert jobs.job_counts(3, 1, False) == (3, 3)
    assert jobs.job_counts(3, 4, False) == (12, 13)  # + the stitch job
    assert jobs.job_counts(3, 4, True) == (4, 16)  # prepare array, an array per frame, stitch
    check(1001, 1, False)  # indices 0-1000
    with pytest.raises(jobs.SubmitError, match=r"^1002 tasks in one job array exceed the "
                                               r"cluster's MaxArraySize 1001: submit the frames "
                                               r"in parts \(--frames A-B\)$"):
        check(1002, 1, False)
    check(500, 2, False)
    with pytest.raises(jobs.SubmitError, match="^1004 tasks .* or in fewer bands$"):
        check(251, 4, False)  # one array of frames x bands
    check(1001, 4, True)  # a prepare array of 1001 frames, arrays of 4 bands
    with pytest.raises(jobs.SubmitError, match="^1002 tasks"):
        check(1002, 4, True)
    with pytest.raises(jobs.SubmitError, match="^1500 tasks"):
        check(2, 1500, True)  # one frame's bands

    limits["MaxArraySize"] = 100001
    check(9999, 1, False)  # slurmctld takes a job while its count stays below MaxJobCount
    with pytest.raises(jobs.SubmitError, match=r"^the submission is 10000 Slurm jobs .* more "
                                               r"than the cluster's MaxJobCount 10000 allows"):
        check(10000, 1, False)
    with pytest.raises(jobs.SubmitError, match="^the submission is 20000 Slurm jobs"):
        check(20000, 1, False)  # the 20,000-frame range that hung in sbatch
    with pytest.raises(jobs.SubmitError, match="^the submission is 10006 Slurm jobs"):
        check(2001, 4, True)  # 2001 + 2001 x 4 + 1 (the stitch)
    held[0] = 9000
    check(999, 1, False)
    with pytest.raises(jobs.SubmitError, match="already holds 9000 of its MaxJobCount 10000"):
        check(1000, 1, False)
    held[0] = None  # squeue did not say: sbatch decides
    check(9999, 1, False)
    limits.clear()  # scontrol did not say: sbatch decides
    check(10 ** 6, 1, False)
