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

Every file is written under a temporary name, checked (images read back with OpenImageIO,
markers read back and compared; files.py) and renamed when complete. A file that does not check
out (Blender exits 0 even when the disk filled while it saved the frame) fails the task, which
re-queues itself while it has retries left; only that task, not its whole array.
"""

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from . import blend_info, files, jobs, slurm, stitch

# Lines of the add-on's output a task looks for.
RENDERED = "Photon: rendered frame"
PREPARED = "Photon: prepared (no pixels"
STATE_SAVED = "Photon: prepared state saved"
STATE_LOADED = "Photon: prepared state loaded"
STATE_REFUSED = "Photon: warning: prepared state refused"
# Blender prints a failed image write and still says "Saved" and exits 0; a task that finds the
# file damaged quotes the reason.
WRITE_ERRORS = ("No space left on device", "Disk quota exceeded", "File too large",
                "Read-only file system", "Input/output error")


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
            f"r.border_min_y, r.border_max_y = {lo!r}, {hi!r}"
            # Bands of one frame need the same samples, or the stitched frame's noise would
            # change at their seams: a Time Limit would stop each band elsewhere, and adaptive
            # sampling judges a pixel with its neighbours, which a band's edge lacks.
            "; p = getattr(bpy.context.scene, 'photon', None)"
            "; p is not None and setattr(p, 'time_limit', 0.0)"
            "; p is not None and setattr(p, 'adaptive_sampling', False)")
    if manifest["band_format"] != manifest["file_format"]:
        expr += (f"; r.image_settings.file_format = {manifest['band_format']!r}"
                 "; r.image_settings.color_depth = '8'")
    return expr


def say(text):
    """Writes a line to the task's log (Slurm's output file) at once, unbuffered. When that disk
    is full the line is lost, not the task: its exit status still tells, and nothing is kept
    back to fail again at exit."""
    try:
        os.write(sys.stdout.fileno(), (text + "\n").encode("utf-8", errors="replace"))
    except OSError:
        pass


def _render(cmd, env, success_line):
    """Runs Blender, passing its output to the Slurm log. Returns (whether it exited 0 and
    printed `success_line`, the set of STATE_* markers it printed, its last line naming one of
    WRITE_ERRORS or "")."""
    started = time.monotonic()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            stdin=subprocess.DEVNULL, text=True, errors="replace")
    succeeded = False
    markers = set()
    write_error = ""
    for line in proc.stdout:
        say(line.rstrip("\n"))
        succeeded = succeeded or line.startswith(success_line)
        markers.update(m for m in (STATE_SAVED, STATE_LOADED, STATE_REFUSED)
                       if line.startswith(m))
        if any(error in line for error in WRITE_ERRORS):
            write_error = line.strip()
    code = proc.wait()
    say(f"farm: Blender ran {time.monotonic() - started:.2f} s (exit {code})")
    return code == 0 and succeeded, markers, write_error


def _blender_cmd(manifest, frame, out_prefix, expr=None):
    cmd = [manifest["blender"], "-b", "--factory-startup", manifest["blend"],
           "--addons", "photon", "-E", "PHOTON"]
    if expr:
        cmd += ["--python-expr", expr]
    return cmd + ["-o", str(out_prefix), "-f", str(frame)]


def _attempt():
    return int(os.environ.get("SLURM_RESTART_COUNT", "0")) + 1


def _min_channels(manifest):
    return files.MIN_CHANNELS.get(manifest["color_mode"], 1)


def _mark_done(manifest, name, dest):
    """The marker done/NAME, holding the path of what the task wrote; jobs.missing_frames and
    `submit --wait` count a frame done only once its marker is there."""
    files.write_text(Path(manifest["job_dir"]) / "done" / name, str(dest), "done marker")


def _give_up(manifest, tmp, message):
    # The failed output goes first: on a full disk, it frees the room for the log line.
    shutil.rmtree(tmp, ignore_errors=True)
    say(f"{jobs.ERROR}{message}")
    return _requeue_or_fail(manifest)


def run_prepare(manifest_path):
    manifest = jobs.load_manifest(manifest_path)
    index = int(os.environ["SLURM_ARRAY_TASK_ID"])
    frame = manifest["frames"][index]
    job_dir = Path(manifest["job_dir"])
    say(f"farm: frame {frame} shared preparation{jobs.ATTEMPT}{_attempt()}")
    tmp = files.fresh_dir(job_dir / "tmp" / f"prepare_{index}")
    saved = tmp / "state.photonstate"
    env = dict(os.environ, BLENDER_USER_SCRIPTS=manifest["addon_dir"],
               PHOTON_PREPARED_SAVE=str(saved), PHOTON_PREPARE_ONLY="1")
    env.pop("PHOTON_PREPARED_LOAD", None)
    ok, markers, write_error = _render(_blender_cmd(manifest, frame, tmp / "out_"), env,
                                       PREPARED)
    if not (ok and STATE_SAVED in markers and files.is_regular(saved)):
        said = f" ({write_error})" if write_error else ""
        return _give_up(manifest, tmp, f"Blender did not prepare frame {frame}{said}")
    dest = state_path(manifest, frame)
    try:
        files.check_state_file(saved)
        files.move(saved, dest, "prepared state")
        _mark_done(manifest, f"prepare_{index}", dest)
    except files.FileError as exc:
        return _give_up(manifest, tmp, f"frame {frame}: {exc}")
    shutil.rmtree(tmp, ignore_errors=True)
    say(f"farm: wrote {dest} ({dest.stat().st_size / 1e6:.1f} MB)")
    return 0


def _shared_state(manifest, frame):
    """The frame's state file for PHOTON_PREPARED_LOAD, or None (with a note) when something
    other than a regular file is in its place: the band then prepares itself."""
    path = state_path(manifest, frame)
    try:
        files.require_regular(path, "the frame's shared preparation")
    except files.FileError as exc:
        say(f"farm: warning: {exc}")
        return None
    return path


def run_task(manifest_path, frame_index=None):
    """One render task: array task i of the single render array (frame i // split, band
    i % split), or, with `frame_index`, band i of that frame's own array."""
    manifest = jobs.load_manifest(manifest_path)
    index = int(os.environ["SLURM_ARRAY_TASK_ID"])
    split = manifest["split"]
    if frame_index is None:
        frame_index, band = divmod(index, split)
    else:
        band = index
    frame = manifest["frames"][frame_index]
    task = frame_index * split + band
    job_dir = Path(manifest["job_dir"])
    say(f"farm: frame {frame}" + (f" band {band + 1}/{split}" if split > 1 else "") +
        f"{jobs.ATTEMPT}{_attempt()}")
    tmp = files.fresh_dir(job_dir / "tmp" / f"task_{task}")
    env = dict(os.environ, BLENDER_USER_SCRIPTS=manifest["addon_dir"])
    for name in ("PHOTON_PREPARED_SAVE", "PHOTON_PREPARED_LOAD", "PHOTON_PREPARE_ONLY"):
        env.pop(name, None)
    state = _shared_state(manifest, frame) if manifest.get("shared_prepare") else None
    if state:
        env["PHOTON_PREPARED_LOAD"] = str(state)
    expr = _band_expr(manifest, band) if split > 1 else None
    outputs = []
    ok, markers, write_error = _render(_blender_cmd(manifest, frame, tmp / "out_", expr), env,
                                       RENDERED)
    if ok:
        outputs = [p for p in tmp.iterdir() if files.is_regular(p)]
    if manifest.get("shared_prepare"):
        say("farm: " + ("used the frame's shared preparation" if STATE_LOADED in markers else
                        "prepared itself (the shared preparation was not used)"))
    if len(outputs) != 1:
        return _give_up(manifest, tmp, f"Blender did not render frame {frame} (outputs: "
                                       f"{[p.name for p in outputs]})")
    if split > 1:
        dest, what = band_path(manifest, frame, band), f"frame {frame} band {band + 1}"
    else:
        dest, what = Path(manifest["paths"][frame_index]), f"frame {frame}"
    try:
        # Blender says "Saved" and exits 0 even when the disk filled while it wrote the file.
        files.place_image(outputs[0], dest, what, manifest["width"], manifest["height"],
                          _min_channels(manifest))
        _mark_done(manifest, f"task_{task}", dest)
    except files.FileError as exc:
        said = f"; Blender: {write_error}" if write_error else ""
        return _give_up(manifest, tmp, f"{exc}{said}")
    shutil.rmtree(tmp, ignore_errors=True)
    say(f"farm: wrote {dest}")
    return 0


def _requeue_target():
    """What `scontrol requeue` must name to re-queue this task alone: an array task by
    ARRAYID_TASK (the array's own id, which one of its tasks also runs under, names the whole
    array), another job by its id."""
    array, task = os.environ.get("SLURM_ARRAY_JOB_ID"), os.environ.get("SLURM_ARRAY_TASK_ID")
    if array and task:
        return f"{array}_{task}"
    return os.environ.get("SLURM_JOB_ID")


def _requeue_or_fail(manifest):
    restarts = int(os.environ.get("SLURM_RESTART_COUNT", "0"))
    target = _requeue_target()
    if target and restarts < manifest["retries"]:
        say(f"farm: re-queuing {target} (restart {restarts + 1} of {manifest['retries']})")
        try:
            proc = slurm.requeue(target)
        except slurm.SlurmError as exc:
            say(f"farm: re-queue failed: {exc}")
            return 1
        if proc.returncode == 0:
            # Slurm ends this run and starts the task again.
            time.sleep(60)
        say(f"farm: re-queue failed: {(proc.stderr or proc.stdout).strip()}")
    return 1


def _remove_state(manifest, frame):
    """Its bands are done: the frame's shared preparation (often the job's largest file) goes.
    Whatever else took its place is left alone; the frame is stitched all the same."""
    try:
        files.remove(state_path(manifest, frame), "the frame's shared preparation")
    except files.FileError as exc:
        say(f"farm: warning: {exc}")


def run_stitch(manifest_path):
    manifest = jobs.load_manifest(manifest_path)
    say(f"farm: stitching {len(manifest['frames'])} frame(s){jobs.ATTEMPT}{_attempt()}")
    failed = 0
    done = Path(manifest["job_dir"]) / "done"
    for frame, path in zip(manifest["frames"], manifest["paths"]):
        if files.is_regular(done / f"frame_{frame}") and files.is_regular(path):
            # Stitched by an earlier attempt of this job, re-queued for another frame.
            continue
        started = time.monotonic()
        bands = [band_path(manifest, frame, b) for b in range(manifest["split"])]
        missing = [str(b) for b in bands if not files.is_regular(b)]
        if missing:
            say(f"{jobs.ERROR}frame {frame} misses bands {missing}")
            failed += 1
            continue
        try:
            stitch.stitch(bands, manifest["rows"], path, manifest["file_format"],
                          manifest["quality"])
            _mark_done(manifest, f"frame_{frame}", path)
        except (stitch.StitchError, files.FileError) as exc:
            say(f"{jobs.ERROR}frame {frame}: {exc}")
            failed += 1
            continue
        say(f"farm: stitched frame {frame} -> {path} in {time.monotonic() - started:.2f} s")
        if manifest.get("shared_prepare"):
            _remove_state(manifest, frame)
    if failed:
        return _requeue_or_fail(manifest)
    return 0
