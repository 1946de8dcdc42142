"""tools/farm.py on a single-node Slurm cluster that the tests start (and stop, even on failure):
frames and split frames rendered through Slurm must equal Blender's own `-a` output bit for bit,
every pass included, whether the bands share the frame's preparation or each prepares itself;
a band killed or re-queued mid-render is rendered again; a stale shared preparation is refused
and the band renders correctly anyway; bad input is refused before anything is queued.

    /usr/bin/python3 -m pytest -q tests/farm/test_farm.py --photon-stage=build/stage \
        --blender=/usr/bin/blender --photon-out=build/test_out
"""

import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

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

    def run(self, *args, timeout=240):
        cmd = [sys.executable, str(FARM), *map(str, args)]
        if args and args[0] == "submit":
            cmd += ["--blender", self.blender, "--addon-dir", str(self.stage)]
        proc = subprocess.run(cmd, env=self.env, capture_output=True, text=True,
                              timeout=timeout, stdin=subprocess.DEVNULL)
        proc.log = f"$ {' '.join(cmd)}\n{proc.stdout}\n{proc.stderr}"
        return proc

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
    # Slurm holds a re-queued job for a while (BeginTime); release it so the test stays short.
    deadline = time.monotonic() + 150
    while farm.queue() and time.monotonic() < deadline:
        for line in farm.queue():
            task, state, reason = line.split(None, 2)
            if state == "PENDING" and reason == "BeginTime":
                farm.slurm("scontrol", "update", f"JobId={task}", "StartTime=now")
        time.sleep(0.5)
    assert not farm.queue(), farm.queue()
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
