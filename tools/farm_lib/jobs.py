"""A farm submission: the checks made before anything is queued, the manifest every task reads,
and the Slurm jobs (tasks.py holds their bodies).

Layout under the output folder: OUT/.farm/job-<time>-<pid>/ holds manifest.json, logs/ (one
Slurm log per task), state/ (each split frame's shared preparation, removed once the frame is
stitched), bands/ (finished band renders), tmp/ (renders in progress) and done/ (a marker per
finished task and per stitched frame). Every file a task makes is written under a temporary
name and renamed when complete, so a killed or re-queued task never leaves a half-written
frame, band or state file behind.

Jobs: without --split one render array, a task per frame. With --split N and a shared
preparation (the default for the PHOTON_MAP integrator), a prepare array (a task per frame),
then per frame a render array of N band tasks that waits for that frame's prepare task
(afterok), then a stitch job after every render array; without sharing, one render array of
frames x N band tasks and the stitch job.
"""

import json
import os
import re
import shutil
import sys
import time
from pathlib import Path

from . import blend_info, slurm, stitch

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
    if not blend.is_file():
        raise SubmitError(f"no such .blend file: {blend}")
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
        try:
            import OpenImageIO  # noqa: F401
        except ImportError:
            raise SubmitError(f"stitching needs OpenImageIO's Python module in {sys.executable} "
                              f"(apt-get install python3-openimageio)") from None


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
    for sub in ("logs", "bands", "tmp", "done", "state"):
        (job_dir / sub).mkdir(parents=True, exist_ok=True)
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
        "height": info["height"],
        "file_format": file_format,
        "band_format": stitch.BAND_FORMAT.get(file_format, file_format),
        "quality": info["quality"],
        "retries": retries,
        "shared_prepare": bool(shared_prepare and split > 1),
        "job_dir": str(job_dir),
    }
    (job_dir / "manifest.json").write_text(json.dumps(manifest, indent=1))
    return manifest


def _wrap(manifest, command, *args):
    extra = "".join(f" {a}" for a in args)
    return (f"exec {manifest['python']} {FARM_PY} {command} {manifest['job_dir']}/manifest.json"
            f"{extra}")


def job_ids(manifest):
    """Every Slurm job of the submission, in submission order."""
    ids = [manifest.get("prepare_job"), *manifest.get("render_jobs", []),
           manifest.get("stitch_job")]
    return [i for i in ids if i]


def submit(manifest, partition=None, name="photon"):
    """Queues the submission's jobs (see the module's doc); returns (prepare job or None,
    render jobs, stitch job or None)."""
    job_dir = manifest["job_dir"]
    # Append: a re-queued task's log keeps every attempt.
    common = ["--requeue", "--open-mode=append", "--chdir", job_dir,
              f"--export=ALL,BLENDER_USER_SCRIPTS={manifest['addon_dir']}"]
    if partition:
        common += ["-p", partition]
    frames, split = len(manifest["frames"]), manifest["split"]
    prepare_id = None
    render_ids = []
    render = [*common, "-J", f"{name}-render", "-o", f"{job_dir}/logs/render_%A_%a.log"]
    if manifest["shared_prepare"]:
        prepare_id = slurm.sbatch([*common, "-J", f"{name}-prepare", "-a", f"0-{frames - 1}",
                                   "-o", f"{job_dir}/logs/prepare_%A_%a.log",
                                   "--wrap", _wrap(manifest, "_prepare")])
        # Each frame's bands wait for that frame's preparation only.
        for k in range(frames):
            render_ids.append(slurm.sbatch([
                *render, "-a", f"0-{split - 1}", f"--dependency=afterok:{prepare_id}_{k}",
                "--kill-on-invalid-dep=yes", "--wrap", _wrap(manifest, "_task", "--frame-index",
                                                             k)]))
    else:
        render_ids.append(slurm.sbatch([*render, "-a", f"0-{frames * split - 1}",
                                        "--wrap", _wrap(manifest, "_task")]))
    manifest["prepare_job"] = prepare_id
    manifest["render_jobs"] = render_ids
    manifest["render_job"] = render_ids[0]
    stitch_id = None
    if split > 1:
        stitch_id = slurm.sbatch([*common, "-J", f"{name}-stitch",
                                  "--dependency=afterok:" + ":".join(render_ids),
                                  "--kill-on-invalid-dep=yes",
                                  "-o", f"{job_dir}/logs/stitch_%j.log",
                                  "--wrap", _wrap(manifest, "_stitch")])
    manifest["stitch_job"] = stitch_id
    Path(job_dir, "manifest.json").write_text(json.dumps(manifest, indent=1))
    return prepare_id, render_ids, stitch_id


def missing_frames(manifest):
    """Frames whose finished marker is not there yet."""
    done = Path(manifest["job_dir"]) / "done"
    if manifest["split"] > 1:
        return [f for f in manifest["frames"] if not (done / f"frame_{f}").exists()]
    return [f for i, f in enumerate(manifest["frames"]) if not (done / f"task_{i}").exists()]


def wait(manifest, poll=1.0):
    ids = job_ids(manifest)
    while slurm.queued(ids):
        time.sleep(poll)
    return missing_frames(manifest)
