#!/usr/bin/python3
"""Photon against Cycles at equal wall time on a validation scene.

Renders NAME.blend with Photon (its stored settings), then with Cycles at the sample count that
takes the same render time (calibrated from a short Cycles run), and prints each image's
relative RMSE and mean difference against the stored Cycles reference NAME.exr.

    tests/bench/equal_time_vs_cycles.py test_scenes/validation/cornell_gi.blend \
        --addon-dir build/stage [--blender blender] [--photon-expr "..."]
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio


def read_rgb(path):
    return oiio.ImageBuf(str(path)).get_pixels(oiio.FLOAT)[..., :3]


def render(blender, addon_dir, blend, engine, out, expr=""):
    cmd = [blender, "-b", "--factory-startup", "--addons", "photon", str(blend), "-E", engine]
    if expr:
        cmd += ["--python-expr", expr]
    cmd += ["-o", f"{out}_####", "-F", "OPEN_EXR", "-x", "1", "-t", "0", "-f", "1"]
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    wall = time.perf_counter() - t0
    # Blender's own render time (excludes start-up): the last "Time: mm:ss.xx" on stdout.
    times = re.findall(r"Time: (\d+):(\d+\.\d+)", proc.stdout)
    render_time = int(times[-1][0]) * 60 + float(times[-1][1]) if times else wall
    return Path(f"{out}_0001.exr"), render_time, proc.stdout


def errors(image, reference):
    rel_rmse = float(np.sqrt(np.mean((image - reference) ** 2)) / reference.mean())
    return rel_rmse, float(image.mean() / reference.mean() - 1.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("blend", type=Path)
    parser.add_argument("--addon-dir", required=True, type=Path)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--photon-expr", default="", help="Python run before the Photon render")
    args = parser.parse_args()
    reference = read_rgb(args.blend.with_suffix(".exr"))
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        photon_exr, photon_time, log = render(args.blender, args.addon_dir, args.blend, "PHOTON",
                                              tmp / "photon", args.photon_expr)
        photon_rmse, photon_mean = errors(read_rgb(photon_exr), reference)
        calibrate = 32
        _, t_cal, _ = render(args.blender, args.addon_dir, args.blend, "CYCLES", tmp / "cal",
                             f"import bpy; bpy.context.scene.cycles.samples = {calibrate}")
        spp = max(1, int(round(calibrate * photon_time / max(t_cal, 1e-3))))
        cycles_exr, cycles_time, _ = render(
            args.blender, args.addon_dir, args.blend, "CYCLES", tmp / "cycles",
            f"import bpy; s = bpy.context.scene; s.cycles.samples = {spp}; s.cycles.seed = 99")
        cycles_rmse, cycles_mean = errors(read_rgb(cycles_exr), reference)
    print(f"{args.blend.stem}: Photon {photon_time:.2f} s, relative RMSE {photon_rmse:.4f}, "
          f"mean {photon_mean:+.4f} | Cycles {spp} spp {cycles_time:.2f} s, relative RMSE "
          f"{cycles_rmse:.4f}, mean {cycles_mean:+.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
