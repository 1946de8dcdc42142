"""The bodies of the farm's Slurm jobs, run by `farm.py _prepare|_task|_stitch MANIFEST`:

- prepare (one array task per frame of a split submission sharing its preparation): Blender
  renders the frame with PHOTON_PREPARED_SAVE and PHOTON_PREPARE_ONLY (the add-on's
  prepared_state.py), so Photon traces the photon maps and builds the caches once and saves
  them; the file is renamed into OUT/.farm/job-*/state/ only when Blender succeeded;
- render task: one frame, or one band of a frame through the render border, loading the
  frame's state file (PHOTON_PREPARED_LOAD) when the submission shares it. A state file that
  is missing, damaged or made for other settings is refused by Photon with a warning and the
  band prepares itself, with the same pixels;
- stitch: assembles each frame from its bands.

Every file is written under a temporary name and renamed when complete; a failed task
re-queues itself while it has retries left.
"""

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from . import blend_info, slurm, stitch

# Lines of the add-on's output a task looks for.
RENDERED = "Photon: rendered frame"
PREPARED = "Photon: prepared (no pixels"
STATE_SAVED = "Photon: prepared state saved"
STATE_LOADED = "Photon: prepared state loaded"
STATE_REFUSED = "Photon: warning: prepared state refused"


def band_path(manifest, frame, band):
    ext = {"PNG": ".png", "TIFF": ".tif", "BMP": ".bmp", "TARGA_RAW": ".tga", "HDR": ".hdr"}
    suffix = ext.get(manifest["band_format"], ".exr")
    return Path(manifest["job_dir"]) / "bands" / f"frame_{frame}_band_{band}{suffix}"


def state_path(manifest, frame):
    """The frame's shared preparation (written by its prepare task)."""
    return Path(manifest["job_dir"]) / "state" / f"frame_{frame}.photonstate"


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


def _render(cmd, env, success_line):
    """Runs Blender, passing its output to the Slurm log. Returns (whether it exited 0 and
    printed `success_line`, the set of STATE_* markers it printed)."""
    started = time.monotonic()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            stdin=subprocess.DEVNULL, text=True, errors="replace")
    succeeded = False
    markers = set()
    for line in proc.stdout:
        sys.stdout.write(line)
        succeeded = succeeded or line.startswith(success_line)
        markers.update(m for m in (STATE_SAVED, STATE_LOADED, STATE_REFUSED)
                       if line.startswith(m))
    code = proc.wait()
    print(f"farm: Blender ran {time.monotonic() - started:.2f} s (exit {code})", flush=True)
    return code == 0 and succeeded, markers


def _blender_cmd(manifest, frame, out_prefix, expr=None):
    cmd = [manifest["blender"], "-b", "--factory-startup", manifest["blend"],
           "--addons", "photon", "-E", "PHOTON"]
    if expr:
        cmd += ["--python-expr", expr]
    return cmd + ["-o", str(out_prefix), "-f", str(frame)]


def _attempt():
    return int(os.environ.get("SLURM_RESTART_COUNT", "0")) + 1


def _fresh_dir(path):
    shutil.rmtree(path, ignore_errors=True)
    path.mkdir(parents=True)
    return path


def run_prepare(manifest_path):
    manifest = json.loads(Path(manifest_path).read_text())
    index = int(os.environ["SLURM_ARRAY_TASK_ID"])
    frame = manifest["frames"][index]
    job_dir = Path(manifest["job_dir"])
    tmp = _fresh_dir(job_dir / "tmp" / f"prepare_{index}")
    saved = tmp / "state.photonstate"
    env = dict(os.environ, BLENDER_USER_SCRIPTS=manifest["addon_dir"],
               PHOTON_PREPARED_SAVE=str(saved), PHOTON_PREPARE_ONLY="1")
    env.pop("PHOTON_PREPARED_LOAD", None)
    print(f"farm: frame {frame} shared preparation, attempt {_attempt()}", flush=True)
    ok, markers = _render(_blender_cmd(manifest, frame, tmp / "out_"), env, PREPARED)
    if ok and STATE_SAVED in markers and saved.is_file():
        dest = state_path(manifest, frame)
        dest.parent.mkdir(parents=True, exist_ok=True)
        os.replace(saved, dest)
        shutil.rmtree(tmp, ignore_errors=True)
        (job_dir / "done" / f"prepare_{index}").write_text(str(dest))
        print(f"farm: wrote {dest} ({dest.stat().st_size / 1e6:.1f} MB)", flush=True)
        return 0
    print(f"farm: error: Blender did not prepare frame {frame}", flush=True)
    return _requeue_or_fail(manifest)


def run_task(manifest_path, frame_index=None):
    """One render task: array task i of the single render array (frame i // split, band
    i % split), or, with `frame_index`, band i of that frame's own array."""
    manifest = json.loads(Path(manifest_path).read_text())
    index = int(os.environ["SLURM_ARRAY_TASK_ID"])
    split = manifest["split"]
    if frame_index is None:
        frame_index, band = divmod(index, split)
    else:
        band = index
    frame = manifest["frames"][frame_index]
    task = frame_index * split + band
    job_dir = Path(manifest["job_dir"])
    tmp = _fresh_dir(job_dir / "tmp" / f"task_{task}")
    env = dict(os.environ, BLENDER_USER_SCRIPTS=manifest["addon_dir"])
    for name in ("PHOTON_PREPARED_SAVE", "PHOTON_PREPARED_LOAD", "PHOTON_PREPARE_ONLY"):
        env.pop(name, None)
    if manifest.get("shared_prepare"):
        env["PHOTON_PREPARED_LOAD"] = str(state_path(manifest, frame))
    expr = _band_expr(manifest, band) if split > 1 else None
    print(f"farm: frame {frame}" + (f" band {band + 1}/{split}" if split > 1 else "") +
          f", attempt {_attempt()}", flush=True)
    outputs = []
    ok, markers = _render(_blender_cmd(manifest, frame, tmp / "out_", expr), env, RENDERED)
    if ok:
        outputs = [p for p in tmp.iterdir() if p.is_file()]
    if manifest.get("shared_prepare"):
        print("farm: " + ("used the frame's shared preparation" if STATE_LOADED in markers else
                          "prepared itself (the shared preparation was not used)"), flush=True)
    if len(outputs) == 1:
        dest = band_path(manifest, frame, band) if split > 1 else \
            Path(manifest["paths"][frame_index])
        dest.parent.mkdir(parents=True, exist_ok=True)
        os.replace(outputs[0], dest)
        shutil.rmtree(tmp, ignore_errors=True)
        (job_dir / "done" / f"task_{task}").write_text(str(dest))
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
        started = time.monotonic()
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
        print(f"farm: stitched frame {frame} -> {path} in {time.monotonic() - started:.2f} s",
              flush=True)
        # Its bands are done: the frame's shared preparation (often the job's largest file) goes.
        state_path(manifest, frame).unlink(missing_ok=True)
    if failed:
        return _requeue_or_fail(manifest)
    return 0
