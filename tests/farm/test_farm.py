"""tools/farm.py on a single-node Slurm cluster that the tests start (and stop, even on failure):
frames and split frames rendered through Slurm must equal Blender's own `-a` output bit for bit,
every pass included, whether the bands share the frame's preparation or each prepares itself;
a band killed or re-queued mid-render is rendered again, and a failed band re-queues only itself;
a stale shared preparation, or a folder in its place, is refused and the band renders
correctly anyway; bad input is refused before anything is queued. Hostile conditions: an output
folder whose name holds spaces, quotes, $ and %; a disk that fills while a frame is written (no
damaged frame under its name, and the failure reaches `status` and `submit --wait`); job ids
that name no submission; an sbatch that does not answer (the submission is withdrawn); more
frames than the cluster takes (refused before queuing).

    /usr/bin/python3 -m pytest -q tests/farm/test_farm.py --photon-stage=build/stage \
        --blender=/usr/bin/blender --photon-out=build/test_out
"""

import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from small_disk import fill, mount_tmpfs, unmount

REPO = Path(__file__).resolve().parents[2]
FARM = REPO / "tools" / "farm.py"
sys.path.insert(0, str(REPO / "tools"))
from farm_lib import cluster as farm_cluster  # noqa: E402

SCENE_SCRIPT = Path(__file__).resolve().parent / "make_farm_scene.py"


class Farm:
    def __init__(self, root, pointer, stage, blender, out):
        self.root, self.pointer, self.stage, self.blender, self.out = root, pointer, stage, \
            blender, out
        self.env = dict(os.environ, SLURM_CONF=str(root / "slurm.conf"),
                        PHOTON_FARM_POINTER=str(pointer))

    def command(self, args, blender=None):
        cmd = [sys.executable, str(FARM), *map(str, args)]
        if args and args[0] == "submit":
            cmd += ["--blender", str(blender or self.blender), "--addon-dir", str(self.stage)]
        return cmd

    def run(self, *args, timeout=240, blender=None, env=None):
        cmd = self.command(args, blender)
        proc = subprocess.run(cmd, env=env or self.env, capture_output=True, text=True,
                              timeout=timeout, stdin=subprocess.DEVNULL)
        proc.log = f"$ {' '.join(cmd)}\n{proc.stdout}\n{proc.stderr}"
        return proc

    def start(self, *args):
        """farm.py running in the background, its output unbuffered (read it line by line)."""
        return subprocess.Popen(self.command(args), env=dict(self.env, PYTHONUNBUFFERED="1"),
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                stdin=subprocess.DEVNULL)

    def slurm(self, *args):
        return subprocess.run(list(args), env=self.env, capture_output=True, text=True,
                              timeout=30, stdin=subprocess.DEVNULL)

    def queue(self):
        return [line for line in self.slurm("squeue", "-h", "-r", "-o", "%i %T %r")
                .stdout.splitlines() if line.strip()]


@pytest.fixture(scope="module")
def farm(request, tmp_path_factory):
    missing = farm_cluster.tools_missing()
    if missing:
        pytest.skip(f"Slurm is not installed here (missing {', '.join(missing)}; "
                    f"apt-get install slurm-wlm munge)")
    if os.geteuid() != 0:
        pytest.skip("the local Slurm cluster runs its daemons as root; not root here")
    base = tmp_path_factory.mktemp("farm")
    stage = Path(request.config.getoption("--photon-stage"))
    if not (stage / "addons" / "photon" / "__init__.py").exists():
        pytest.fail(f"no staged add-on in {stage}: build first (cmake --build build)")
    root = base / "cluster"
    farm = Farm(root, base / "cluster.json", stage, request.config.getoption("--blender"),
                base)
    started = farm.run("local-cluster", "start", "--dir", root, timeout=120)
    pids = []
    try:
        assert started.returncode == 0, started.log
        pids = [farm_cluster._read_pid(root / name) for name in
                ("slurmctld.pid", "slurmd.pid", "munge/munged.pid")]
        assert all(pids), pids
        yield farm
    finally:
        stopped = farm.run("local-cluster", "stop", timeout=120)
        assert stopped.returncode == 0, stopped.log
        assert not root.exists(), "local-cluster stop left its folder"
        assert not any(farm_cluster._alive(pid) for pid in pids), "daemons still running"


@pytest.fixture(scope="module")
def scene(farm):
    """The animation .blend and its frames rendered by `blender -b -a` (the reference)."""
    blend = farm.out / "anim.blend"
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(farm.stage),
               PYTHONPATH=str(REPO / "test_scenes"))
    base = [farm.blender, "-b", "--factory-startup", "--addons", "photon"]
    subprocess.run([*base, "--python", str(SCENE_SCRIPT), "--", str(blend),
                    "OPEN_EXR_MULTILAYER"], env=env, check=True, capture_output=True,
                   timeout=120, stdin=subprocess.DEVNULL)
    ref = farm.out / "reference"
    proc = subprocess.run([*base, str(blend), "-E", "PHOTON", "-o", str(ref / "farm_"), "-a"],
                          env=env, capture_output=True, text=True, timeout=180,
                          stdin=subprocess.DEVNULL)
    assert proc.returncode == 0 and "Photon: rendered frame" in proc.stdout, proc.stdout
    return blend, ref


def read_exr(path):
    """[(channel names, channel types, pixels as raw 32-bit patterns)] per subimage."""
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(str(path))
    assert inp is not None, f"cannot open {path}: {oiio.geterror()}"
    images, index = [], 0
    while inp.seek_subimage(index, 0):
        spec = inp.spec()
        pixels = np.ascontiguousarray(inp.read_image(oiio.FLOAT), dtype=np.float32)
        images.append((list(spec.channelnames),
                       [str(t) for t in spec.channelformats] or [str(spec.format)],
                       pixels.view(np.uint32)))
        index += 1
    inp.close()
    return images


def assert_same_image(a, b):
    ia, ib = read_exr(a), read_exr(b)
    assert len(ia) == len(ib)
    for (names_a, types_a, pix_a), (names_b, types_b, pix_b) in zip(ia, ib):
        assert names_a == names_b
        assert types_a == types_b
        assert pix_a.shape == pix_b.shape
        different = int(np.count_nonzero(pix_a != pix_b))
        assert different == 0, f"{b}: {different} channel values differ from {a}"
    # The passes are really there: Photon's light passes and the data passes.
    assert any("Photon Direct" in n for n in ia[0][0]) and any("Depth" in n for n in ia[0][0])


def job_id(proc):
    match = re.search(r"render job (\d+)", proc.stdout)
    assert match, proc.log
    return match.group(1)


def test_animation_matches_blender_animation_render(farm, scene):
    blend, ref = scene
    out = farm.out / "anim"
    proc = farm.run("submit", blend, "--out", out, "--wait")
    assert proc.returncode == 0, proc.log
    assert "stitch job" not in proc.stdout
    for frame in (1, 2, 3):
        assert_same_image(ref / f"farm_{frame:04d}.exr", out / f"farm_{frame:04d}.exr")
    status = farm.run("status", job_id(proc))
    assert status.returncode == 0, status.log
    assert "frames done: 3/3" in status.stdout, status.log


def job_dir(out):
    return next((out / ".farm").iterdir())


def logs_text(out, pattern):
    return {p.name: p.read_text() for p in sorted((job_dir(out) / "logs").glob(pattern))}


@pytest.mark.parametrize("shared", [True, False], ids=["shared_prepare", "no_shared_prepare"])
def test_split_frame_matches_unsplit_render(farm, scene, shared):
    blend, ref = scene
    out = farm.out / f"split_{'shared' if shared else 'own'}"
    args = ["submit", blend, "--out", out, "--frames", "2", "--split", "4", "--wait"]
    if not shared:
        args.append("--no-shared-prepare")
    proc = farm.run(*args)
    assert proc.returncode == 0, proc.log
    assert "stitch job" in proc.stdout
    assert ("prepare job" in proc.stdout) == shared, proc.log
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == \
        ["farm_0002.exr"]
    assert_same_image(ref / "farm_0002.exr", out / "farm_0002.exr")
    bands = logs_text(out, "render_*.log")
    assert len(bands) == 4, bands.keys()
    if shared:
        (prepared,) = logs_text(out, "prepare_*.log").values()
        assert "Photon: prepared state saved" in prepared and "farm: wrote" in prepared, prepared
        for name, log in bands.items():
            assert "Photon: prepared state loaded" in log, (name, log)
            assert "used the frame's shared preparation" in log, (name, log)
            # A band traced no photons of its own.
            assert "Tracing photons" not in log, (name, log)
        # Removed once the frame was stitched.
        assert not any((job_dir(out) / "state").iterdir())
    else:
        assert not logs_text(out, "prepare_*.log")
        for name, log in bands.items():
            assert "prepared state" not in log, (name, log)


def test_stale_shared_preparation_is_refused_and_bands_render_correctly(farm, scene):
    """The frame's state file is swapped for frame 1's (another camera and objects) between
    the prepare task and the bands: every band refuses it, prepares itself, and the stitched
    frame is still bit-identical."""
    blend, ref = scene
    stale = farm.out / "frame1.photonstate"
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(farm.stage),
               PHOTON_PREPARED_SAVE=str(stale), PHOTON_PREPARE_ONLY="1")
    made = subprocess.run([farm.blender, "-b", "--factory-startup", str(blend), "--addons",
                           "photon", "-E", "PHOTON", "-o", str(farm.out / "stale_tmp" / "x_"),
                           "-f", "1"], env=env, capture_output=True, text=True, timeout=120,
                          stdin=subprocess.DEVNULL)
    assert made.returncode == 0 and stale.is_file(), made.stdout + made.stderr

    out = farm.out / "stale"
    proc = farm.run("submit", blend, "--out", out, "--frames", "2", "--split", "2")
    assert proc.returncode == 0 and "prepare job" in proc.stdout, proc.log
    render = job_id(proc)
    # The bands wait for the prepare task (afterok); held, they wait for the swap too.
    assert farm.slurm("scontrol", "hold", render).returncode == 0
    done = job_dir(out) / "done" / "prepare_0"
    deadline = time.monotonic() + 90
    while not done.exists() and time.monotonic() < deadline:
        time.sleep(0.2)
    assert done.exists(), f"prepare task did not finish: {farm.queue()}"
    state = job_dir(out) / "state" / "frame_2.photonstate"
    assert state.is_file()
    shutil.copyfile(stale, state)
    assert farm.slurm("scontrol", "release", render).returncode == 0
    deadline = time.monotonic() + 120
    while farm.queue() and time.monotonic() < deadline:
        time.sleep(0.5)
    assert not farm.queue(), farm.queue()
    assert_same_image(ref / "farm_0002.exr", out / "farm_0002.exr")
    bands = logs_text(out, "render_*.log")
    assert len(bands) == 2
    for name, log in bands.items():
        assert "Photon: warning: prepared state refused" in log, (name, log)
        assert "another scene or other render settings" in log, (name, log)
        assert "prepared itself" in log, (name, log)


def drain_queue(farm, timeout=150):
    """Waits for the queue to empty. Slurm holds a re-queued task for a while (BeginTime);
    released here so that the tests stay short, but only a couple of seconds after the
    re-queue: Slurm revokes the task's credentials when it re-queues it, and kills a start in
    the same second ("Killing non-startable batch job: Job credential revoked"), which fails
    the task and cancels the jobs that depend on it."""
    deadline = time.monotonic() + timeout
    held = {}
    while farm.queue() and time.monotonic() < deadline:
        for line in farm.queue():
            task, state, reason = line.split(None, 2)
            if state == "PENDING" and reason == "BeginTime":
                since = held.setdefault(task, time.monotonic())
                if time.monotonic() - since >= 2.0:
                    farm.slurm("scontrol", "update", f"JobId={task}", "StartTime=now")
                    del held[task]
        time.sleep(0.5)
    assert not farm.queue(), farm.queue()


def wait_for(path, timeout=90):
    deadline = time.monotonic() + timeout
    while not path.exists() and time.monotonic() < deadline:
        time.sleep(0.2)
    return path.exists()


def _blender_pid(job, task):
    """The Blender process Slurm runs for array task `task` of `job`, or None."""
    wanted = {f"SLURM_ARRAY_JOB_ID={job}".encode(), f"SLURM_ARRAY_TASK_ID={task}".encode()}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            cmdline = (entry / "cmdline").read_bytes().split(b"\0")
            environ = set((entry / "environ").read_bytes().split(b"\0"))
        except OSError:
            continue
        if cmdline and cmdline[0].endswith(b"blender") and wanted <= environ:
            return int(entry.name)
    return None


def test_requeued_and_killed_bands_render_again(farm, scene):
    """Band 1 is re-queued by Slurm (scontrol requeue, as pre-emption does) and band 2's
    Blender is killed by a signal (the task re-queues itself), both mid-render: the stitched
    frame is still bit-identical and nothing half-written is left."""
    blend, ref = scene
    out = farm.out / "fault"
    proc = farm.run("submit", blend, "--out", out, "--frames", "2", "--split", "4")
    assert proc.returncode == 0, proc.log
    job = job_id(proc)
    deadline = time.monotonic() + 90
    requeued = killed = False
    while not (requeued and killed) and time.monotonic() < deadline:
        if not requeued and _blender_pid(job, 0):
            farm.slurm("scontrol", "requeue", f"{job}_0")
            requeued = True
        if not killed:
            pid = _blender_pid(job, 1)
            if pid:
                os.kill(pid, signal.SIGKILL)
                killed = True
        time.sleep(0.05)
    assert requeued and killed, f"bands never ran: {farm.queue()}"
    drain_queue(farm)
    status = farm.run("status", job)
    assert re.search(rf"{job}_0\s+COMPLETED \(restarts [1-9]", status.stdout), status.log
    assert re.search(rf"{job}_1\s+COMPLETED \(restarts [1-9]", status.stdout), status.log
    assert "frames done: 1/1" in status.stdout, status.log
    logs = job_dir(out) / "logs"
    killed_log = (logs / f"render_{job}_1.log").read_text()
    assert "farm: re-queuing" in killed_log and "attempt 2" in killed_log, killed_log
    requeued_log = (logs / f"render_{job}_0.log").read_text()
    assert "attempt 2" in requeued_log
    # The second attempts loaded the frame's shared preparation too.
    for log in (killed_log, requeued_log):
        second = log[log.index("attempt 2"):]
        assert "used the frame's shared preparation" in second, log
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == \
        ["farm_0002.exr"]
    assert_same_image(ref / "farm_0002.exr", out / "farm_0002.exr")


@pytest.mark.parametrize("case", ["missing_blend", "unwritable_out", "split_zero",
                                  "split_with_border"])
def test_bad_input_is_refused_before_queuing(farm, scene, case):
    blend, _ = scene
    out = farm.out / f"bad_{case}"
    args = ["submit", blend, "--out", out]
    expected = ""
    if case == "missing_blend":
        args[1] = farm.out / "no_such.blend"
        expected = "no such .blend file"
    elif case == "unwritable_out":
        blocker = farm.out / "a_file"
        blocker.write_text("not a folder")
        args[3] = out = blocker / "frames"
        expected = "is not writable"
    elif case == "split_zero":
        args += ["--split", "0"]
        expected = "--split must be 1 or more"
    else:
        bordered = farm.out / "bordered.blend"
        subprocess.run([farm.blender, "-b", "--factory-startup", str(blend), "--python-expr",
                        "import bpy; bpy.context.scene.render.use_border = True; "
                        f"bpy.ops.wm.save_as_mainfile(filepath={str(bordered)!r})"],
                       check=True, capture_output=True, timeout=120, stdin=subprocess.DEVNULL)
        args[1] = bordered
        args += ["--split", "2"]
        expected = "the file has a render border"
    before = farm.slurm("scontrol", "show", "config").returncode
    proc = farm.run(*args)
    assert proc.returncode == 2, proc.log
    assert expected in proc.stderr, proc.log
    assert "Traceback" not in proc.stderr, proc.log
    assert before == 0 and not farm.queue()
    assert "render job" not in proc.stdout
    if case != "unwritable_out":
        assert not (out / ".farm").exists()
    shutil.rmtree(out, ignore_errors=True)


def test_band_borders_select_exact_rows():
    """Blender stores the border as float32 and truncates border * height to rows; every band's
    border must land on its rows for any frame height, in float32 and double arithmetic."""
    from farm_lib import blend_info
    for height in range(1, 2200):
        for split in (2, 3, 4, 7, 16):
            if split > height:
                continue
            rows = blend_info.band_rows(height, split)
            assert rows[0][0] == 0 and rows[-1][1] == height
            for (y0, y1), (n0, _) in zip(rows, rows[1:] + [(height, None)]):
                assert y1 == n0 and y1 > y0
                lo, hi = blend_info.band_border(height, y0, y1)
                lo32, hi32 = np.float32(lo), np.float32(hi)
                for product_lo, product_hi in ((lo32 * np.float32(height),
                                                hi32 * np.float32(height)),
                                               (float(lo32) * height, float(hi32) * height)):
                    assert (int(product_lo), int(product_hi)) == (height - y1, height - y0), \
                        (height, split, y0, y1)


@pytest.mark.parametrize("split", [1, 2])
def test_failed_render_makes_wait_fail(farm, split):
    """A frame Photon refuses (a camera with a NaN location: Blender exits 1 and writes
    nothing) fails its task; with no retries left `submit --wait` exits 1, the stitch job is
    dropped, and no frame file appears."""
    blend = farm.out / "nan_camera.blend"
    if not blend.exists():
        env = dict(os.environ, BLENDER_USER_SCRIPTS=str(farm.stage),
                   PYTHONPATH=os.pathsep.join([str(REPO / "test_scenes"),
                                               str(REPO / "tests" / "blender" / "scripts")]))
        subprocess.run([farm.blender, "-b", "--factory-startup", "--addons", "photon",
                        "--python", str(REPO / "tests" / "blender" / "scripts" /
                                        "make_bad_scene.py"),
                        "--", str(farm.out / "nan_camera.json"), "nan_camera", str(blend)],
                       env=env, check=True, capture_output=True, timeout=120,
                       stdin=subprocess.DEVNULL)
    out = farm.out / f"failing_{split}"
    proc = farm.run("submit", blend, "--out", out, "--split", split, "--retries", "0",
                    "--wait")
    assert proc.returncode == 1, proc.log
    assert "not rendered" in proc.stderr, proc.log
    assert not farm.queue()
    assert [p.name for p in out.iterdir()] == [".farm"]
    # With --split 2 the frame's prepare task fails (and its bands never run).
    task_logs = "".join(logs_text(out, "*.log").values())
    assert "non-finite transform" in task_logs and "farm: error" in task_logs, task_logs


def test_shared_preparation_plan():
    """Which split submissions share a preparation, and the note when they do not."""
    from farm_lib import jobs
    info = {"integrator": "PHOTON_MAP", "view_layers": 1}
    assert jobs.shared_prepare_plan(info, 1) == (False, "")
    assert jobs.shared_prepare_plan(info, 4) == (True, "")
    shared, note = jobs.shared_prepare_plan(info, 4, wanted=False)
    assert not shared and "--no-shared-prepare" in note
    for integrator in ("RAY_TRACE", "RADIOSITY", "SPPM", "VCM", None):
        shared, note = jobs.shared_prepare_plan(dict(info, integrator=integrator), 4)
        assert not shared and "only PHOTON_MAP" in note, integrator
    shared, note = jobs.shared_prepare_plan(dict(info, view_layers=2), 4)
    assert not shared and "2 view layers" in note


def test_output_folder_with_spaces_quotes_and_percent(farm, scene):
    """Every path in the jobs' shell commands is quoted, and '%' in the log folder is not taken
    for one of Slurm's file-name patterns: a split frame renders into this folder as anywhere."""
    blend, ref = scene
    out = farm.out / "it's a \"farm\" $HOME `x` 50% dir"
    proc = farm.run("submit", blend, "--out", out, "--frames", "2", "--split", "2", "--wait")
    assert proc.returncode == 0, proc.log
    assert_same_image(ref / "farm_0002.exr", out / "farm_0002.exr")
    assert len(logs_text(out, "*.log")) == 4  # prepare, 2 bands, stitch
    status = farm.run("status", job_id(proc))
    assert status.returncode == 0 and "frames done: 1/1" in status.stdout, status.log


@pytest.mark.parametrize("split", [1, 2])
def test_full_disk_fails_the_frame_and_the_submission(farm, scene, split):
    """The output folder's disk fills while frame 3 is written: Blender's EXR write fails ("No
    space left on device") but Blender says "Saved" and exits 0; with --split, the stitch's
    write fails. No damaged file may appear under the frame's name, and the failure must reach
    the task, `status` and `submit --wait`, with the reason."""
    blend, _ = scene
    out = farm.out / f"full_disk_{split}"
    # Room for the prepared state; the farm's manifest and logs fit in what is left, a frame
    # (about 31 KB) does not.
    mount_tmpfs(out, "16m")
    waiting = None
    try:
        if split == 1:
            fill(out, leave=24 * 1024)
        waiting = farm.start("submit", blend, "--out", out, "--frames", "3", "--split", split,
                             "--retries", "0", "--wait")
        submitted = ""
        for line in waiting.stdout:
            submitted += line
            if line.startswith("logs:"):
                break
        render = re.search(r"render job (\d+)", submitted)
        assert render, submitted + waiting.stderr.read()
        render = render.group(1)
        if split > 1:
            # The stitch waits for the bands; held, it waits for the disk to fill too.
            stitch = re.search(r"stitch job (\d+)", submitted).group(1)
            assert farm.slurm("scontrol", "hold", stitch).returncode == 0
            done = job_dir(out) / "done"
            assert wait_for(done / "task_0") and wait_for(done / "task_1"), farm.queue()
            deadline = time.monotonic() + 30
            while any(line.startswith(f"{render}_") for line in farm.queue()):
                assert time.monotonic() < deadline, farm.queue()
                time.sleep(0.2)
            fill(out, leave=24 * 1024)
            assert farm.slurm("scontrol", "release", stitch).returncode == 0
        stdout, stderr = waiting.communicate(timeout=240)
        log = submitted + stdout + stderr
        assert waiting.returncode == 1, log
        assert "frame(s) [3] not rendered" in stderr, log
        assert "Traceback" not in log, log
        task_logs = "".join(logs_text(out, "*.log").values())
        assert "Traceback" not in task_logs, task_logs
        if split == 1:
            # The task's reason, with Blender's own, reaches `submit --wait`.
            assert re.search(r"farm: error: render_\d+_0\.log: frame 3 .* is damaged or "
                             r"incomplete.*No space left on device", stderr), log + task_logs
        else:
            assert re.search(r"farm: error: stitch_\d+\.log: frame 3: ", stderr), \
                log + task_logs
        # Nothing damaged under a frame's name, no temporary file left.
        assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == \
            ["filler"]
        assert not [p for p in out.rglob("*") if ".partial-" in p.name or
                    p.parent.name.startswith("task_")]
        status = farm.run("status", render)
        assert status.returncode == 1, status.log
        assert "FAILED" in status.stdout and "frames done: 0/1" in status.stdout, status.log
        assert "error: " in status.stdout, status.log
    finally:
        if waiting and waiting.poll() is None:
            waiting.kill()
            waiting.wait()
        unmount(out)


# Blender for the farm, except that the first attempt of the array task that runs under the
# array's own job id fails once the frame's other bands are done (Slurm gives the array's id to
# one of its tasks: re-queuing that id re-queues every task of the array, finished ones too).
FAIL_ONCE = """#!/bin/sh
if [ -z "$PHOTON_PREPARE_ONLY" ] && [ -n "$SLURM_ARRAY_JOB_ID" ] && \\
   [ "$SLURM_JOB_ID" = "$SLURM_ARRAY_JOB_ID" ] && [ "${{SLURM_RESTART_COUNT:-0}}" = 0 ]; then
  n=0
  while [ "$(ls done | grep -c '^task_')" -lt {others} ] && [ $n -lt 600 ]; do
    sleep 0.2
    n=$((n + 1))
  done
  echo "fake Blender: this attempt fails"
  exit 1
fi
exec {blender} "$@"
"""


def test_failed_band_requeues_only_itself(farm, scene):
    """A band fails after the frame's other bands finished: it re-queues itself alone, and no
    finished band renders again."""
    blend, ref = scene
    wrapper = farm.out / "fail_once_blender"
    wrapper.write_text(FAIL_ONCE.format(others=1, blender=shlex.quote(shutil.which(
        farm.blender))))
    wrapper.chmod(0o755)
    out = farm.out / "requeue_one"
    proc = farm.run("submit", blend, "--out", out, "--frames", "2", "--split", "2",
                    "--no-shared-prepare", blender=wrapper)
    assert proc.returncode == 0, proc.log
    job = job_id(proc)
    drain_queue(farm)
    logs = {int(name.rsplit("_", 1)[1][:-4]): log
            for name, log in logs_text(out, f"render_{job}_*.log").items()}
    assert sorted(logs) == [0, 1], logs.keys()
    failed = [band for band, log in logs.items() if "fake Blender: this attempt fails" in log]
    assert len(failed) == 1, logs
    for band, log in logs.items():
        attempts = log.count(", attempt ")
        renders = len(re.findall(r"^Photon: rendered frame", log, re.M))
        if band in failed:
            assert attempts == 2 and renders == 1, log
            assert f"farm: re-queuing {job}_{band} " in log, log
        else:
            assert attempts == 1 and renders == 1, (band, log)
    status = farm.run("status", job)
    assert status.returncode == 0, status.log
    for band in range(2):
        restarted = re.search(rf"{job}_{band}\s+COMPLETED \(restarts 1\)", status.stdout)
        assert bool(restarted) == (band in failed), status.log
    assert_same_image(ref / "farm_0002.exr", out / "farm_0002.exr")


def test_status_and_cancel_refuse_what_names_no_submission(farm, scene):
    """`status 0` / `cancel 0` once reached another submission (`scontrol show job 0` lists
    every job). Anything but the job id of a farm submission is refused, and nothing is
    cancelled; a submission's job id cancels all of its jobs."""
    blend, _ = scene
    other = farm.slurm("sbatch", "--parsable", "--hold", "-o", "/dev/null", "--wrap",
                       "sleep 300").stdout.strip()
    assert other.isdigit(), other
    out = farm.out / "cancelled"
    try:
        # Finished submissions of the earlier tests are in the controller too.
        for bad, message in (("0", "is not a job id"), ("abc", "is not a job id"),
                             ("-1", "is not a job id"), (f"{other}_0", "is not a job id"),
                             (f"{other},{other}", "is not a job id"),
                             ("987654321", "Slurm knows no job 987654321"),
                             (other, f"job {other} is not a farm submission")):
            for command in ("status", "cancel"):
                proc = farm.run(command, bad)
                assert proc.returncode == 2, proc.log
                assert message in proc.stderr and "Traceback" not in proc.stderr, proc.log
                assert "cancelled" not in proc.stdout, proc.log
        state = farm.slurm("squeue", "-h", "-j", other, "-o", "%T").stdout.strip()
        assert state == "PENDING", state

        proc = farm.run("submit", blend, "--out", out, "--frames", "1", "--split", "2")
        assert proc.returncode == 0, proc.log
        ids = re.findall(r"(?:prepare|render|stitch) job (\d+)", proc.stdout)
        assert len(ids) == 3, proc.log
        cancelled = farm.run("cancel", job_id(proc))
        assert cancelled.returncode == 0, cancelled.log
        assert f"cancelled job(s) {', '.join(ids)}" in cancelled.stdout, cancelled.log
        deadline = time.monotonic() + 30
        for job in ids:
            # A running task is COMPLETING for a moment while Slurm stops it.
            while True:
                states = set(farm.slurm("squeue", "-h", "-t", "all", "-j", job, "-o",
                                        "%T").stdout.split())
                if states != {"COMPLETING"} or time.monotonic() > deadline:
                    break
                time.sleep(0.2)
            assert states == {"CANCELLED"}, (job, states)
    finally:
        farm.slurm("scancel", other)


SLOW_SBATCH = """#!/bin/sh
# The first sbatch answers; every later one queues its job and then hangs, as an overloaded
# controller can: the submission cannot learn that job's id. Every job is held, so that none
# runs (and finishes) before the submission is withdrawn.
n=$(cat {count} 2>/dev/null || echo 0)
echo $((n + 1)) > {count}
{sbatch} --hold "$@" || exit $?
if [ "$n" -ge 1 ]; then exec sleep 60; fi
"""


def test_sbatch_timeout_withdraws_the_submission(farm, scene):
    """An sbatch that does not answer within --sbatch-timeout: a clear error, no traceback, and
    nothing half-made: the queued jobs (the hanging sbatch's too) are cancelled and the folders
    the submission made are removed."""
    blend, _ = scene
    bin_dir = farm.out / "slow_sbatch"
    bin_dir.mkdir()
    count = bin_dir / "count"
    sbatch = bin_dir / "sbatch"
    sbatch.write_text(SLOW_SBATCH.format(count=shlex.quote(str(count)),
                                         sbatch=shlex.quote(shutil.which("sbatch"))))
    sbatch.chmod(0o755)
    out = farm.out / "slow" / "frames"
    env = dict(farm.env, PATH=f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    started = time.monotonic()
    proc = farm.run("submit", blend, "--out", out, "--frames", "2", "--split", "2",
                    "--sbatch-timeout", "3", env=env)
    assert proc.returncode == 2, proc.log
    assert "sbatch did not answer within 3 s" in proc.stderr, proc.log
    assert "withdrawn" in proc.stderr and "Traceback" not in proc.stderr, proc.log
    assert time.monotonic() - started < 90, proc.log
    assert count.read_text().strip() == "2"  # the prepare job, then the hanging render job
    assert not (farm.out / "slow").exists()
    # Both jobs were queued, and both are cancelled.
    jobs = [line.split("|") for line in farm.slurm(
        "squeue", "-h", "-t", "all", "-O", "JobID:|,State:|,WorkDir:").stdout.splitlines()]
    mine = [(job, state) for job, state, folder in jobs if folder.startswith(f"{out}/")]
    assert len(mine) == 2 and {state for _, state in mine} == {"CANCELLED"}, jobs
    assert not farm.queue()


def test_more_frames_than_the_cluster_takes_are_refused(farm, scene):
    """A 20,000-frame range is more array tasks than the cluster's MaxJobCount (Slurm's default
    10000, as on the test cluster): sbatch would sleep and retry until it timed out. It is
    refused at once, with the reason, and nothing is queued or left behind."""
    blend, _ = scene
    config = farm.slurm("scontrol", "show", "config").stdout
    max_jobs = int(re.search(r"^MaxJobCount\s*=\s*(\d+)", config, re.M).group(1))
    assert max_jobs < 20000, config
    out = farm.out / "huge" / "frames"
    before = farm.slurm("squeue", "-h", "-r", "-t", "all", "-o", "%i").stdout.split()
    started = time.monotonic()
    proc = farm.run("submit", blend, "--out", out, "--frames", "1-20000", timeout=120)
    assert proc.returncode == 2, proc.log
    assert (f"farm: error: the submission is 20000 Slurm jobs (each array task counts), more "
            f"than the cluster's MaxJobCount {max_jobs} allows: submit the frames in parts "
            f"(--frames A-B)") in proc.stderr, proc.log
    assert "Traceback" not in proc.stderr, proc.log
    assert time.monotonic() - started < 30, proc.log
    assert not (farm.out / "huge").exists()
    assert farm.slurm("squeue", "-h", "-r", "-t", "all", "-o", "%i").stdout.split() == before


@pytest.mark.parametrize("kind", ["directory"])
def test_state_file_replaced_by_a_non_file(farm, scene, kind):
    """The frame's prepared state becomes a folder (the stitch once died on it with a
    traceback) between the prepare task and the bands: the bands refuse it and prepare
    themselves, the stitch leaves it alone, and the frame is still bit-identical. (FIFOs,
    devices, empty and garbage files: test_farm_files.py, without Slurm.)"""
    blend, ref = scene
    out = farm.out / f"odd_state_{kind}"
    proc = farm.run("submit", blend, "--out", out, "--frames", "2", "--split", "2")
    assert proc.returncode == 0 and "prepare job" in proc.stdout, proc.log
    render = job_id(proc)
    assert farm.slurm("scontrol", "hold", render).returncode == 0
    assert wait_for(job_dir(out) / "done" / "prepare_0"), farm.queue()
    state = job_dir(out) / "state" / "frame_2.photonstate"
    state.unlink()
    if kind == "directory":
        state.mkdir()
        (state / "something").write_text("not the farm's")
    else:
        os.mkfifo(state)
    assert farm.slurm("scontrol", "release", render).returncode == 0
    drain_queue(farm)
    assert_same_image(ref / "farm_0002.exr", out / "farm_0002.exr")
    what = "a directory" if kind == "directory" else "a FIFO"
    for name, log in logs_text(out, "render_*.log").items():
        assert f"is {what}, not a regular file" in log and "prepared itself" in log, (name, log)
    (stitched,) = logs_text(out, "stitch_*.log").values()
    assert f"is {what}, not a file; left in place" in stitched, stitched
    assert "Traceback" not in "".join(logs_text(out, "*.log").values())
    assert state.is_dir() if kind == "directory" else state.is_fifo()
    status = farm.run("status", render)
    assert status.returncode == 0 and "frames done: 1/1" in status.stdout, status.log
