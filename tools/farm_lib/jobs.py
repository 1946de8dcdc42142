"""A farm submission: the checks made before anything is queued, the manifest every task reads,
and the Slurm jobs (tasks.py holds their bodies).

Layout under the output folder: OUT/.farm/job-<time>-<pid>/ holds manifest.json, logs/ (one
Slurm log per task), state/ (each split frame's shared preparation, removed once the frame is
stitched), bands/ (finished band renders), tmp/ (renders in progress) and done/ (a marker per
finished task and per stitched frame). Every file a task makes is written under a temporary
name, read back and renamed when complete (files.py), so a killed or re-queued task, or a full
disk, never leaves a half-written frame, band, marker or manifest under its final name.

Jobs: without --split one render array, a task per frame. With --split N and a shared
preparation (the default for the PHOTON_MAP integrator), a prepare array (a task per frame),
then per frame a render array of N band tasks that waits for that frame's prepare task
(afterok), then a stitch job after every render array; without sharing, one render array of
frames x N band tasks and the stitch job.

A submission that cannot be queued whole (sbatch fails or does not answer) is withdrawn: the
jobs already queued are cancelled and its job folder is removed.
"""

import importlib
import os
import re
import shlex
import shutil
import sys
import time
from pathlib import Path

from . import blend_info, files, slurm, stitch

FARM_PY = Path(__file__).resolve().parents[1] / "farm.py"


class SubmitError(RuntimeError):
    pass


def parse_frames(text):
    """'A-B' or 'A' -> (A, B)."""
    match = re.fullmatch(r"\s*(\d+)\s*(?:-\s*(\d+)\s*)?", text)
    if not match:
        raise SubmitError(f"--frames must be A-B or A (whole frame numbers), not {text!r}")
    first = int(match.group(1))
    last = int(match.group(2)) if match.group(2) else first
    if last < first:
        raise SubmitError(f"--frames {text}: the last frame is before the first")
    return first, last


def _check_out_dir(out_dir):
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        probe = out_dir / f".farm-write-test-{os.getpid()}"
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as exc:
        raise SubmitError(f"output folder {out_dir} is not writable: {exc.strerror or exc}") \
            from None


def check_arguments(blend, out_dir, split, addon_dir, blender, retries=0):
    """The checks that need no Blender run or Slurm: raise SubmitError with a clear message."""
    if split < 1:
        raise SubmitError(f"--split must be 1 or more, not {split}")
    if retries < 0:
        raise SubmitError(f"--retries must be 0 or more, not {retries}")
    if not os.path.lexists(blend):
        raise SubmitError(f"no such .blend file: {blend}")
    if not files.is_regular(blend):
        raise SubmitError(f"{blend} is not a regular file (Blender would block on a FIFO)")
    if not (addon_dir / "addons" / "photon" / "__init__.py").is_file():
        raise SubmitError(f"no Photon add-on in {addon_dir}/addons/photon (build it: "
                          f"cmake --build build --target photon_addon, or pass --addon-dir)")
    if shutil.which(blender) is None:
        raise SubmitError(f"Blender executable not found: {blender}")
    _check_out_dir(out_dir)


def check_settings(info, split):
    if info["is_movie"]:
        raise SubmitError(f"the file writes a movie ({info['file_format']}); the farm renders "
                          f"frames as separate tasks: choose an image format")
    if not info["frames"]:
        raise SubmitError("no frames to render in the given range")
    try:
        importlib.import_module("OpenImageIO")
    except ImportError:
        raise SubmitError(f"the farm reads back every image it writes with OpenImageIO's Python "
                          f"module, missing in {sys.executable} (apt-get install "
                          f"python3-openimageio)") from None
    if split > 1:
        if info["file_format"] not in stitch.OIIO_FORMATS:
            raise SubmitError(f"--split cannot stitch {info['file_format']} output; use "
                              f"{', '.join(sorted(stitch.OIIO_FORMATS))}")
        if info["use_border"]:
            raise SubmitError("--split renders bands of the whole frame, but the file has a "
                              "render border (Output > Format > Render Region): turn it off")
        if info["use_multiview"]:
            raise SubmitError("--split does not support multi-view (stereo) output")
        if split > info["height"]:
            raise SubmitError(f"--split {split} is more bands than the frame's "
                              f"{info['height']} rows")


def shared_prepare_plan(info, split, wanted=True):
    """(whether the bands of each frame share one preparation, a note for the user or "")."""
    if split <= 1:
        return False, ""
    if not wanted:
        return False, "each band prepares itself (--no-shared-prepare)"
    if info.get("integrator") != "PHOTON_MAP":
        return False, (f"each band prepares itself: the file's integrator is "
                       f"{info.get('integrator') or 'unknown'}, and only PHOTON_MAP shares its "
                       f"preparation")
    if info.get("view_layers", 1) > 1:
        return False, (f"each band prepares itself: the file renders {info['view_layers']} view "
                       f"layers, and a shared preparation holds one")
    return True, ""


def make_manifest(blend, out_dir, info, split, addon_dir, blender, retries,
                  shared_prepare=False):
    job_dir = out_dir / ".farm" / f"job-{time.strftime('%Y%m%d-%H%M%S')}-{os.getpid()}"
    try:
        for sub in ("logs", "bands", "tmp", "done", "state"):
            (job_dir / sub).mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise SubmitError(f"cannot make the job folder {job_dir}: {exc.strerror or exc}") \
            from None
    file_format = info["file_format"]
    manifest = {
        "blend": str(blend.resolve()),
        "blender": shutil.which(blender),
        "addon_dir": str(addon_dir.resolve()),
        "python": sys.executable,
        "frames": info["frames"],
        "paths": info["paths"],
        "split": split,
        "rows": blend_info.band_rows(info["height"], split),
        "width": info["width"],
        "height": info["height"],
        "file_format": file_format,
        "band_format": stitch.BAND_FORMAT.get(file_format, file_format),
        "color_mode": info["color_mode"],
        "quality": info["quality"],
        "retries": retries,
        "shared_prepare": bool(shared_prepare and split > 1),
        "job_dir": str(job_dir),
    }
    save_manifest(manifest)
    return manifest


def save_manifest(manifest):
    files.write_json(Path(manifest["job_dir"]) / "manifest.json", manifest, "manifest")


def load_manifest(path):
    """A manifest.json: raises files.FileError unless it is a regular file holding a farm
    manifest."""
    manifest = files.read_json(path, "manifest")
    if not isinstance(manifest, dict) or not all(k in manifest for k in ("job_dir", "frames",
                                                                         "split")):
        raise files.FileError(f"manifest {path} is not a farm manifest (it lacks job_dir, "
                              f"frames or split)")
    return manifest


def _wrap(manifest, command, *args):
    """The shell command of a job (sbatch --wrap runs it with /bin/sh): every word quoted, so
    folders with spaces, quotes or $ in their names reach farm.py as they are."""
    words = [manifest["python"], str(FARM_PY), command,
             str(Path(manifest["job_dir"]) / "manifest.json"), *map(str, args)]
    return "exec " + " ".join(shlex.quote(w) for w in words)


def _log(manifest, name):
    """sbatch -o for logs/NAME: '%' in the folder doubled, so that only NAME's %A/%a/%j are
    Slurm's replacement symbols."""
    return str(Path(manifest["job_dir"]) / "logs").replace("%", "%%") + "/" + name


def job_ids(manifest):
    """Every Slurm job of the submission, in submission order."""
    ids = [manifest.get("prepare_job"), *manifest.get("render_jobs", []),
           manifest.get("stitch_job")]
    return [i for i in ids if i]


def job_counts(frames, split, shared_prepare):
    """(tasks of the submission's largest job array, every job and array task it queues)."""
    arrays = [frames, *[split] * frames] if shared_prepare else [frames * split]
    return max(arrays), sum(arrays) + (1 if split > 1 else 0)


def check_capacity(frames, split, shared_prepare):
    """Refuses, before anything is queued, a submission the cluster cannot take: an array larger
    than MaxArraySize (array indices go up to MaxArraySize - 1), or more jobs than fit under
    MaxJobCount, where every array task counts and so does every job the controller still
    holds. (Past MaxJobCount, sbatch does not fail: it sleeps and retries.)"""
    largest, total = job_counts(frames, split, shared_prepare)
    hint = "submit the frames in parts (--frames A-B)" + (" or in fewer bands" if split > 1
                                                          else "")
    limit = slurm.limits()
    max_array = limit.get("MaxArraySize")
    if max_array is not None and largest > max_array:
        raise SubmitError(f"{largest} tasks in one job array exceed the cluster's "
                          f"MaxArraySize {max_array}: {hint}")
    max_jobs = limit.get("MaxJobCount")
    if max_jobs is None:
        return
    if total >= max_jobs:
        raise SubmitError(f"the submission is {total} Slurm jobs (each array task counts), "
                          f"more than the cluster's MaxJobCount {max_jobs} allows: {hint}")
    held = slurm.job_count()
    if held is not None and held + total >= max_jobs:
        raise SubmitError(f"the submission is {total} Slurm jobs (each array task counts), but "
                          f"the controller already holds {held} of its MaxJobCount {max_jobs} "
                          f"(finished jobs count until MinJobAge): submit later, or {hint}")


def submit(manifest, partition=None, name="photon", timeout=60):
    """Queues the submission's jobs (see the module's doc); returns (prepare job or None,
    render jobs, stitch job or None). Each job id goes into the manifest as soon as it is
    queued, so that withdraw() finds every job of a submission that failed half-way. `timeout`
    is how long one sbatch may take."""
    job_dir = manifest["job_dir"]
    # Append: a re-queued task's log keeps every attempt. (BLENDER_USER_SCRIPTS is set by the
    # task itself: --export splits at commas, which a folder name may hold.)
    common = ["--requeue", "--open-mode=append", "--chdir", job_dir, "--export=ALL"]
    if partition:
        common += ["-p", partition]
    frames, split = len(manifest["frames"]), manifest["split"]
    manifest.update(prepare_job=None, render_jobs=[], render_job=None, stitch_job=None)
    render = [*common, "-J", f"{name}-render", "-o", _log(manifest, "render_%A_%a.log")]
    if manifest["shared_prepare"]:
        manifest["prepare_job"] = slurm.sbatch([
            *common, "-J", f"{name}-prepare", "-a", f"0-{frames - 1}",
            "-o", _log(manifest, "prepare_%A_%a.log"), "--wrap", _wrap(manifest, "_prepare")],
            timeout)
        # Each frame's bands wait for that frame's preparation only.
        for k in range(frames):
            manifest["render_jobs"].append(slurm.sbatch([
                *render, "-a", f"0-{split - 1}",
                f"--dependency=afterok:{manifest['prepare_job']}_{k}",
                "--kill-on-invalid-dep=yes",
                "--wrap", _wrap(manifest, "_task", "--frame-index", k)], timeout))
    else:
        manifest["render_jobs"].append(slurm.sbatch([
            *render, "-a", f"0-{frames * split - 1}", "--wrap", _wrap(manifest, "_task")],
            timeout))
    manifest["render_job"] = manifest["render_jobs"][0]
    if split > 1:
        manifest["stitch_job"] = slurm.sbatch([
            *common, "-J", f"{name}-stitch",
            "--dependency=afterok:" + ":".join(manifest["render_jobs"]),
            "--kill-on-invalid-dep=yes", "-o", _log(manifest, "stitch_%j.log"),
            "--wrap", _wrap(manifest, "_stitch")], timeout)
    save_manifest(manifest)
    return manifest["prepare_job"], manifest["render_jobs"], manifest["stitch_job"]


def withdraw(manifest, settle=30.0):
    """Undoes a submission that failed half-way: cancels its queued jobs (those whose ids it
    recorded, and any other whose working folder is its job folder: an sbatch that timed out
    may still have queued its job), waits for them to leave the queue, then removes the job
    folder. Returns what is left behind (a sentence), or ""."""
    job_dir = Path(manifest["job_dir"])
    ids = job_ids(manifest)
    try:
        ids = sorted(set(ids) | set(slurm.jobs_in(job_dir)), key=int)
        if ids:
            slurm.run(["scancel", *ids], check=False)
            deadline = time.monotonic() + settle
            while slurm.queued(ids) and time.monotonic() < deadline:
                time.sleep(0.5)
            if slurm.queued(ids):
                raise slurm.SlurmError(f"job(s) did not stop within {settle:.0f} s")
    except slurm.SlurmError as exc:
        return (f"could not withdraw the submission ({exc}): cancel job(s) "
                f"{', '.join(ids) or '(none recorded)'} with scancel, and remove {job_dir}")
    shutil.rmtree(job_dir, ignore_errors=True)
    if job_dir.exists():
        return f"could not remove {job_dir}"
    try:
        job_dir.parent.rmdir()  # OUT/.farm, unless other submissions use it
    except OSError:
        pass
    return ""


def missing_frames(manifest):
    """Frames whose finished marker is not there yet."""
    done = Path(manifest["job_dir"]) / "done"
    if manifest["split"] > 1:
        return [f for f in manifest["frames"] if not files.is_regular(done / f"frame_{f}")]
    return [f for i, f in enumerate(manifest["frames"])
            if not files.is_regular(done / f"task_{i}")]


# Every attempt of a task starts its log with a line holding this (tasks.py).
ATTEMPT = ", attempt "
ERROR = "farm: error: "


def errors(manifest):
    """'LOG: message' for each task log whose last attempt printed an error."""
    found = []
    for log in sorted((Path(manifest["job_dir"]) / "logs").glob("*.log")):
        try:
            lines = files.read_text(log, "log").splitlines()
        except files.FileError as exc:
            found.append(str(exc))
            continue
        starts = [i for i, line in enumerate(lines) if line.startswith("farm: ") and
                  ATTEMPT in line]
        last = lines[starts[-1]:] if starts else lines
        messages = [line[len(ERROR):] for line in last if line.startswith(ERROR)]
        if messages:
            found.append(f"{log.name}: {messages[-1]}")
    return found


def wait(manifest, poll=1.0):
    ids = job_ids(manifest)
    while slurm.queued(ids):
        time.sleep(poll)
    return missing_frames(manifest)
