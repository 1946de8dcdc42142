"""Scene discovery (.blend + optional sidecar .json) and headless Blender renders with a
wall-clock timeout."""

import json
import os
import re
import signal
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

from .blender_version import version_folder

# Printed by the add-on once per finished frame: proves Photon (not a fallback engine) rendered.
PHOTON_LINE = re.compile(r"^Photon: rendered frame (-?\d+) ", re.MULTILINE)
DEFAULT_TIMEOUT = 120.0
DEFAULT_REFERENCE_TIMEOUT = 3600.0  # Cycles references at thousands of samples are slow
# "regions": named pixel rectangles [x0, y0, x1, y1] or discs [cx, cy, r] (y down) that tests
# read (not used here).
SIDECAR_KEYS = {"thresholds", "frames", "timeout", "reference_engine", "reference_samples",
                "reference_timeout", "description", "regions"}


@dataclass
class Scene:
    """One .blend of the suite and its sidecar settings."""
    name: str
    blend: Path
    sidecar: dict = field(default_factory=dict)
    sidecar_error: str = ""
    # Blender (major, minor) whose references are used: its blender-X.Y/ subfolder unless 3.4.
    version: tuple = None

    @property
    def frames(self):
        return [int(f) for f in self.sidecar.get("frames", [1])]

    @property
    def reference_engine(self):
        return str(self.sidecar.get("reference_engine", "PHOTON")).upper()

    @property
    def is_validation(self):
        return self.reference_engine != "PHOTON"

    @property
    def description(self):
        return self.sidecar.get("description", "")

    def reference_path(self, frame):
        """NAME.exr for single-frame scenes, NAME_####.exr per frame for animations, beside the
        .blend for Blender 3.4's references and in blender-X.Y/ for Blender X.Y's."""
        folder = version_folder(self.blend.parent, self.version)
        if len(self.frames) == 1:
            return folder / f"{self.name}.exr"
        return folder / f"{self.name}_{frame:04d}.exr"

    def timeout(self, default, update=False):
        if update and self.is_validation:
            return float(self.sidecar.get("reference_timeout", max(default,
                                                                   DEFAULT_REFERENCE_TIMEOUT)))
        return float(self.sidecar.get("timeout", default))


def load_sidecar(blend):
    """Reads NAME.json next to NAME.blend; returns (dict, error message)."""
    path = blend.with_suffix(".json")
    if not path.exists():
        return {}, ""
    try:
        data = json.loads(path.read_text())
        if not isinstance(data, dict):
            raise ValueError("top level is not an object")
        unknown = set(data) - SIDECAR_KEYS
        if unknown:
            raise ValueError(f"unknown keys {sorted(unknown)}")
        frames = data.get("frames", [1])
        if not frames or not all(isinstance(f, int) for f in frames):
            raise ValueError("\"frames\" must be a non-empty list of integers")
        return data, ""
    except (OSError, ValueError) as exc:
        return {}, f"bad sidecar {path.name}: {exc}"


def find_scenes(folders, only=None, version=None):
    """Every NAME.blend in the folders (sorted by name), restricted to `only` names if given;
    `version` picks the Blender whose references are compared with."""
    scenes = []
    for folder in folders:
        for blend in sorted(Path(folder).glob("*.blend")):
            if only and blend.stem not in only:
                continue
            sidecar, error = load_sidecar(blend)
            scenes.append(Scene(blend.stem, blend, sidecar, error, version))
    return scenes


def frame_args(frames):
    """Blender's frame arguments: -f N, or -f A,B,C for several frames."""
    return ["-f", ",".join(str(f) for f in frames)]


def engine_expr(engine, samples=None):
    """--python-expr text that pins the engine settings for a reference render."""
    lines = ["import bpy", "s = bpy.context.scene"]
    if engine == "CYCLES":
        lines += ["s.cycles.device = 'CPU'", "s.cycles.use_denoising = False",
                  "s.cycles.use_adaptive_sampling = False"]
        if samples:
            lines.append(f"s.cycles.samples = {int(samples)}")
    lines.append("print('regress: engine', s.render.engine, 'samples',"
                 " getattr(getattr(s, s.render.engine.lower(), None), 'samples', None),"
                 " flush=True)")
    return "; ".join(lines)


def blender_command(blender, scene, out_prefix, engine="PHOTON", samples=None, threads=None):
    """The command line that renders `scene`'s frames to OUT_PREFIX####.exr."""
    cmd = [str(blender), "-b", "--factory-startup", "--addons", "photon", str(scene.blend),
           "-E", engine]
    if threads:
        cmd += ["-t", str(threads)]
    if engine != "PHOTON":
        cmd += ["--python-expr", engine_expr(engine, samples)]
    cmd += ["-o", f"{out_prefix}####", "-F", "OPEN_EXR", "-x", "1", *frame_args(scene.frames)]
    return cmd


def run_command(cmd, env, timeout, log_path):
    """Runs cmd in its own process group; kills the whole group after `timeout` seconds.

    Returns (returncode or None on timeout, combined output, seconds)."""
    start = time.monotonic()
    proc = subprocess.Popen(cmd, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, start_new_session=True)
    try:
        output, _ = proc.communicate(timeout=timeout)
        returncode = proc.returncode
    except subprocess.TimeoutExpired:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        output, _ = proc.communicate()
        returncode = None
    seconds = time.monotonic() - start
    text = output.decode("utf-8", "replace")
    Path(log_path).write_text(f"$ {' '.join(cmd)}\n{text}")
    return returncode, text, seconds


def describe_exit(returncode):
    if returncode < 0:
        try:
            return f"Blender killed by signal {signal.Signals(-returncode).name}"
        except ValueError:
            return f"Blender killed by signal {-returncode}"
    return f"Blender exited with status {returncode}"


def render_scene(scene, blender, addon_dir, out_dir, timeout, update=False, threads=None):
    """Renders every frame of `scene` into OUT/renders. Returns a dict with "error" ("" when all
    went well), "outputs" {frame: path}, "seconds" and "log"."""
    renders = Path(out_dir) / "renders"
    logs = Path(out_dir) / "logs"
    renders.mkdir(parents=True, exist_ok=True)
    logs.mkdir(parents=True, exist_ok=True)
    engine = scene.reference_engine if update else "PHOTON"
    samples = scene.sidecar.get("reference_samples") if update else None
    prefix = renders / f"{scene.name}_"
    outputs = {f: Path(f"{prefix}{f:04d}.exr") for f in scene.frames}
    for path in outputs.values():  # never mistake a stale file for this run's output
        if path.exists():
            path.unlink()
    log_path = logs / f"{scene.name}.log"
    result = {"outputs": {}, "seconds": 0.0, "log": str(log_path), "error": "", "engine": engine}
    cmd = blender_command(blender, scene, prefix, engine, samples, threads)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    limit = scene.timeout(timeout, update)
    try:
        returncode, output, seconds = run_command(cmd, env, limit, log_path)
    except OSError as exc:
        result["error"] = f"cannot start Blender: {exc}"
        return result
    result["seconds"] = seconds
    if returncode is None:
        result["error"] = f"timeout: no result after {limit:g} s (process group killed)"
    elif returncode != 0:
        result["error"] = describe_exit(returncode) + last_error_line(output)
    elif engine == "PHOTON":
        rendered = {int(f) for f in PHOTON_LINE.findall(output)}
        missing = [f for f in scene.frames if f not in rendered]
        if missing:
            result["error"] = (f"Photon did not render frame(s) {missing} (no 'Photon: rendered "
                               f"frame' line: add-on missing or another engine ran)"
                               + last_error_line(output))
    elif f"regress: engine {engine}" not in output:
        result["error"] = f"{engine} did not run" + last_error_line(output)
    if not result["error"]:
        missing = [str(p.name) for p in outputs.values() if not p.exists() or
                   p.stat().st_size == 0]
        if missing:
            result["error"] = f"no output file {', '.join(missing)}" + last_error_line(output)
    result["outputs"] = {f: p for f, p in outputs.items() if p.exists()}
    return result


def last_error_line(output):
    """': <the last line mentioning an error>' from Blender's output, or ''."""
    for line in reversed(output.splitlines()):
        low = line.lower()
        if "error" in low or "traceback" in low or "segmentation" in low:
            return f": {line.strip()[:300]}"
    return ""
