"""A farm submission: the checks made before anything is queued, the manifest every task reads,
and the bodies of the two kinds of Slurm job (render task, stitch).

Layout under the output folder: OUT/.farm/job-<time>-<pid>/ holds manifest.json, logs/ (one
Slurm log per task), bands/ (finished band renders), tmp/ (renders in progress) and done/ (a
marker per finished task and per stitched frame). Every file a task makes is written under a
temporary name and renamed when complete, so a killed or re-queued task never leaves a
half-written frame or band behind.
"""

import json
import os
import re
import shutil
import subprocess
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


def make_manifest(blend, out_dir, info, split, addon_dir, blender, retries):
    job_dir = out_dir / ".farm" / f"job-{time.strftime('%Y%m%d-%H%M%S')}-{os.getpid()}"
    for sub in ("logs", "bands", "tmp", "done"):
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
        "job_dir": str(job_dir),
    }
    (job_dir / "manifest.json").write_text(json.dumps(manifest, indent=1))
    return manifest


def _wrap(manifest, command):
    return f"exec {manifest['python']} {FARM_PY} {command} {manifest['job_dir']}/manifest.json"


def submit(manifest, partition=None, name="photon"):
    """Queues the render array (and the stitch job for split frames); returns their ids."""
    job_dir = manifest["job_dir"]
    # Append: a re-queued task's log keeps every attempt.
    common = ["--requeue", "--open-mode=append", "--chdir", job_dir,
              f"--export=ALL,BLENDER_USER_SCRIPTS={manifest['addon_dir']}"]
    if partition:
        common += ["-p", partition]
    count = len(manifest["frames"]) * manifest["split"]
    render_id = slurm.sbatch([*common, "-J", f"{name}-render", "-a", f"0-{count - 1}",
                              "-o", f"{job_dir}/logs/render_%A_%a.log",
                              "--wrap", _wrap(manifest, "_task")])
    manifest["render_job"] = render_id
    stitch_id = None
    if manifest["split"] > 1:
        stitch_id = slurm.sbatch([*common, "-J", f"{name}-stitch",
                                  f"--dependency=afterok:{render_id}",
                                  "--kill-on-invalid-dep=yes",
                                  "-o", f"{job_dir}/logs/stitch_%j.log",
                                  "--wrap", _wrap(manifest, "_stitch")])
    manifest["stitch_job"] = stitch_id
    Path(job_dir, "manifest.json").write_text(json.dumps(manifest, indent=1))
    return render_id, stitch_id


def missing_frames(manifest):
    """Frames whose finished marker is not there yet."""
    done = Path(manifest["job_dir"]) / "done"
    if manifest["split"] > 1:
        return [f for f in manifest["frames"] if not (done / f"frame_{f}").exists()]
    return [f for i, f in enumerate(manifest["frames"]) if not (done / f"task_{i}").exists()]


def wait(manifest, poll=1.0):
    ids = [i for i in (manifest.get("render_job"), manifest.get("stitch_job")) if i]
    while slurm.queued(ids):
        time.sleep(poll)
    return missing_frames(manifest)


# ---- Inside Slurm ----

def band_path(manifest, frame, band):
    ext = {"PNG": ".png", "TIFF": ".tif", "BMP": ".bmp", "TARGA_RAW": ".tga", "HDR": ".hdr"}
    suffix = ext.get(manifest["band_format"], ".exr")
    return Path(manifest["job_dir"]) / "bands" / f"frame_{frame}_band_{band}{suffix}"


def _band_expr(manifest, band):
    y0, y1 = manifest["rows"][band]
    lo, hi = blend_info.band_border(manifest["height"], y0, y1)
    expr = ("import bpy; r = bpy.context.scene.render; r.use_border = True; "
            "r.use_crop_to_border = False; r.border_min_x, r.border_max_x = 0.0, 1.0; "
            f"r.border_min_y, r.border_max_y = {lo!r}, {hi!r}")
    if manifest["band_format"] != manifest["file_format"]:
        expr += (f"; r.image_settings.file_format = {manifest['band_format']!r}"
                 "; r.image_settings.color_depth = '8'")
    return expr


def _render(cmd, env):
    """Runs Blender, passing its output to the Slurm log; True when Photon rendered."""
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            stdin=subprocess.DEVNULL, text=True, errors="replace")
    rendered = False
    for line in proc.stdout:
        sys.stdout.write(line)
        rendered = rendered or line.startswith("Photon: rendered frame")
    sys.stdout.flush()
    return proc.wait() == 0 and rendered


def run_task(manifest_path):
    manifest = json.loads(Path(manifest_path).read_text())
    index = int(os.environ["SLURM_ARRAY_TASK_ID"])
    split = manifest["split"]
    frame = manifest["frames"][index // split]
    band = index % split
    job_dir = Path(manifest["job_dir"])
    tmp = job_dir / "tmp" / f"task_{index}"
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    cmd = [manifest["blender"], "-b", "--factory-startup", manifest["blend"],
           "--addons", "photon", "-E", "PHOTON"]
    if split > 1:
        cmd += ["--python-expr", _band_expr(manifest, band)]
    cmd += ["-o", str(tmp / "out_"), "-f", str(frame)]
    env = dict(os.environ, BLENDER_USER_SCRIPTS=manifest["addon_dir"])
    print(f"farm: frame {frame}" + (f" band {band + 1}/{split}" if split > 1 else "") +
          f", attempt {int(os.environ.get('SLURM_RESTART_COUNT', '0')) + 1}", flush=True)
    outputs = []
    if _render(cmd, env):
        outputs = [p for p in tmp.iterdir() if p.is_file()]
    if len(outputs) == 1:
        dest = band_path(manifest, frame, band) if split > 1 else \
            Path(manifest["paths"][index])
        dest.parent.mkdir(parents=True, exist_ok=True)
        os.replace(outputs[0], dest)
        shutil.rmtree(tmp, ignore_errors=True)
        (job_dir / "done" / f"task_{index}").write_text(str(dest))
        print(f"farm: wrote {dest}", flush=True)
        return 0
    print(f"farm: error: Blender did not render frame {frame} (outputs: "
          f"{[p.name for p in outputs]})", flush=True)
    return _requeue_or_fail(manifest)


def _requeue_or_fail(manifest):
    restarts = int(os.environ.get("SLURM_RESTART_COUNT", "0"))
    job_id = os.environ.get("SLURM_JOB_ID")
    if job_id and restarts < manifest["retries"]:
        print(f"farm: re-queuing (restart {restarts + 1} of {manifest['retries']})", flush=True)
        proc = slurm.requeue(job_id)
        if proc.returncode == 0:
            # Slurm ends this run and starts the task again.
            time.sleep(60)
        print(f"farm: re-queue failed: {proc.stderr.strip()}", flush=True)
    return 1


def run_stitch(manifest_path):
    manifest = json.loads(Path(manifest_path).read_text())
    job_dir = Path(manifest["job_dir"])
    failed = 0
    for frame, path in zip(manifest["frames"], manifest["paths"]):
        bands = [band_path(manifest, frame, b) for b in range(manifest["split"])]
        missing = [str(b) for b in bands if not b.exists()]
        if missing:
            print(f"farm: error: frame {frame} misses bands {missing}", flush=True)
            failed += 1
            continue
        try:
            stitch.stitch(bands, manifest["rows"], path, manifest["file_format"],
                          manifest["quality"])
        except stitch.StitchError as exc:
            print(f"farm: error: frame {frame}: {exc}", flush=True)
            failed += 1
            continue
        (job_dir / "done" / f"frame_{frame}").write_text(str(path))
        print(f"farm: stitched frame {frame} -> {path}", flush=True)
    if failed:
        return _requeue_or_fail(manifest)
    return 0
