#!/usr/bin/python3
"""Many lights: Photon's light tree on a room lit by 1,000 small coloured point and spot lights.

Builds the room of tests/blender/scripts/many_lights.py with 10 and with 1,000 lights (same total
power), then prints
  1. Photon's render time with 1,000 lights against 10 lights at the same sample count (goal:
     at most 2x), rendered back to back;
  2. Photon and Cycles at equal render time on the 1,000-light room (Cycles' sample count
     calibrated from a short run, as in equal_time_vs_cycles.py): relative RMSE of each against
     a converged Cycles reference rendered here (direct light only: Photon's RAY_TRACE
     integrator, Cycles with 0 bounces).
The machine may be shared: times are measured back to back and only their ratios mean much.

    tests/bench/many_lights.py --addon-dir build/stage [--blender blender] [--samples 16]
        [--reference-samples 1024] [--size 160x120] [--no-cycles]
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

HERE = Path(__file__).resolve().parent
SCRIPTS = HERE.parent / "blender" / "scripts"
SCENES = HERE.parent.parent / "test_scenes"


def read_rgb(path):
    return oiio.ImageBuf(str(path)).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)


def make_blend(blender, addon_dir, n_lights, width, height, samples, path):
    expr = ("import sys, bpy; sys.path[:0] = [%r, %r]; import many_lights; "
            "s, _ = many_lights.build_room(%d, %d, %d, %d); s.photon.integrator = 'RAY_TRACE'; "
            "bpy.ops.wm.save_as_mainfile(filepath=%r)"
            % (str(SCRIPTS), str(SCENES), n_lights, width, height, samples, str(path)))
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    subprocess.run([blender, "-b", "--factory-startup", "--addons", "photon", "--python-expr", expr],
                   env=env, capture_output=True, text=True, check=True)


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
    return Path(f"{out}_0001.exr"), render_time


def rel_rmse(image, reference):
    return float(np.sqrt(np.mean((image - reference) ** 2)) / reference.mean())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--addon-dir", required=True, type=Path)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--samples", type=int, default=16, help="Photon samples per pixel")
    parser.add_argument("--reference-samples", type=int, default=1024)
    parser.add_argument("--size", default="160x120")
    parser.add_argument("--no-cycles", action="store_true", help="only the 1,000 vs 10 timing")
    args = parser.parse_args()
    width, height = map(int, args.size.split("x"))
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        blends = {}
        for n in (10, 1000):
            blends[n] = tmp / f"room_{n}.blend"
            make_blend(args.blender, args.addon_dir, n, width, height, args.samples, blends[n])
        # 1. 1,000 vs 10 lights, back to back (twice, alternating, best of each).
        times = {10: [], 1000: []}
        for _ in range(2):
            for n in (10, 1000):
                exr, t = render(args.blender, args.addon_dir, blends[n], "PHOTON", tmp / f"p{n}")
                times[n].append(t)
        photon_exr = exr
        t10, t1000 = min(times[10]), min(times[1000])
        print(f"Photon, {args.samples} spp, {width}x{height}: 10 lights {t10:.2f} s, "
              f"1000 lights {t1000:.2f} s, ratio {t1000 / t10:.2f} (goal <= 2)")
        if args.no_cycles:
            return 0
        # 2. Equal time against Cycles on the 1,000-light room.
        ref_exr, t_ref = render(args.blender, args.addon_dir, blends[1000], "CYCLES", tmp / "ref",
                                f"import bpy; s = bpy.context.scene; "
                                f"s.cycles.samples = {args.reference_samples}; s.cycles.seed = 7")
        reference = read_rgb(ref_exr)
        calibrate = 16
        _, t_cal = render(args.blender, args.addon_dir, blends[1000], "CYCLES", tmp / "cal",
                          f"import bpy; bpy.context.scene.cycles.samples = {calibrate}")
        spp = max(1, int(round(calibrate * t1000 / max(t_cal, 1e-3))))
        cycles_exr, t_cycles = render(
            args.blender, args.addon_dir, blends[1000], "CYCLES", tmp / "cycles",
            f"import bpy; s = bpy.context.scene; s.cycles.samples = {spp}; s.cycles.seed = 99")
        photon = read_rgb(photon_exr)
        cycles = read_rgb(cycles_exr)
        print(f"Cycles reference: {args.reference_samples} spp, {t_ref:.1f} s")
        print(f"1000 lights, equal time: Photon {t1000:.2f} s relative RMSE "
              f"{rel_rmse(photon, reference):.4f} mean {photon.mean() / reference.mean() - 1:+.4f}"
              f" | Cycles {spp} spp {t_cycles:.2f} s relative RMSE "
              f"{rel_rmse(cycles, reference):.4f} mean {cycles.mean() / reference.mean() - 1:+.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
