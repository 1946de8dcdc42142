"""What the farm needs to know about a .blend before queuing anything: frame range, frame size,
output format, the path Blender itself would write each frame to, and Photon's integrator and
the number of view layers (whether the bands of a frame can share one preparation). Read by
one short background Blender run with the Photon add-on enabled (it registers scene.photon;
without it the integrator is None)."""

import json
import os
import subprocess

MARKER = "PHOTON_FARM_INFO "

# Runs inside Blender: argv after "--" is (output prefix, first frame or "", last frame or "").
_SCRIPT = r"""
import json, os, sys
import bpy
args = sys.argv[sys.argv.index("--") + 1:]
prefix, first, last = args
scene = bpy.context.scene
r = scene.render
fmt = r.image_settings
start = int(first) if first else scene.frame_start
end = int(last) if last else scene.frame_end
step = max(scene.frame_step, 1)
# The file's own name part (Blender's "//render/frame_" -> "frame_"), under the farm's folder.
name = os.path.basename(r.filepath.replace("\\", "/")) if r.filepath else ""
r.filepath = os.path.join(prefix, name)
frames = list(range(start, end + 1, step))
info = {
    "frames": frames,
    "paths": [bpy.path.abspath(r.frame_path(frame=f)) for f in frames],
    "width": r.resolution_x * r.resolution_percentage // 100,
    "height": r.resolution_y * r.resolution_percentage // 100,
    "file_format": fmt.file_format,
    "color_depth": fmt.color_depth,
    "color_mode": fmt.color_mode,
    "quality": fmt.quality,
    "is_movie": bool(r.is_movie_format),
    "use_multiview": bool(r.use_multiview),
    "use_border": bool(r.use_border),
    "scene_frames": [scene.frame_start, scene.frame_end],
    "integrator": getattr(getattr(scene, "photon", None), "integrator", None),
    "view_layers": sum(1 for layer in scene.view_layers if layer.use),
}
print("PHOTON_FARM_INFO " + json.dumps(info), flush=True)
"""


class BlendError(RuntimeError):
    pass


def read(blender, blend, out_dir, first=None, last=None, timeout=120, addon_dir=None):
    """The .blend's render settings as a dict (see _SCRIPT), frame paths under out_dir.
    `addon_dir` holds addons/photon (BLENDER_USER_SCRIPTS)."""
    cmd = [blender, "-b", "--factory-startup", str(blend)]
    env = dict(os.environ)
    if addon_dir is not None:
        cmd += ["--addons", "photon"]
        env["BLENDER_USER_SCRIPTS"] = str(addon_dir)
    cmd += ["--python-expr", _SCRIPT, "--", str(out_dir), "" if first is None else str(first),
            "" if last is None else str(last)]
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                              stdin=subprocess.DEVNULL, env=env)
    except FileNotFoundError:
        raise BlendError(f"Blender executable not found: {blender}") from None
    except subprocess.TimeoutExpired:
        raise BlendError(f"Blender did not read {blend} within {timeout} s") from None
    for line in proc.stdout.splitlines():
        if line.startswith(MARKER):
            return json.loads(line[len(MARKER):])
    tail = "\n".join((proc.stdout + proc.stderr).strip().splitlines()[-8:])
    raise BlendError(f"Blender could not read {blend} (exit {proc.returncode}):\n{tail}")


def band_rows(height, split):
    """Row ranges [(y0, y1), ...], top row first, of `split` horizontal bands of a frame."""
    return [(height * k // split, height * (k + 1) // split) for k in range(split)]


def band_border(height, y0, y1):
    """Blender's border (min_y, max_y) selecting rows [y0, y1) counted from the top.

    Blender truncates border * height to whole rows measured from the bottom; aiming half a
    row above each boundary makes the truncation land on it whatever float32 rounding does.
    RNA clamps the top edge's value to 1.0.
    """
    bottom, top = height - y1, height - y0
    return (bottom + 0.5) / height, min((top + 0.5) / height, 1.0)


