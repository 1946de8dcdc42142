#!/usr/bin/python3
"""Error of the RADIOSITY integrator against the number of rays, on the Cornell box.

Renders test_scenes/validation/cornell_radiosity.blend with Photon at a series of radiosity ray
budgets (same seed, patches and camera samples), and measures each image's relative RMSE
against
  - the stored Cycles reference (cornell_radiosity.exr = cornell_gi.exr): the total error,
    which levels off at the discretisation error (patch size, Gouraud smoothing);
  - the render with the largest budget: the solver's noise alone, which should fall as
    1 / sqrt(rays).
Prints a Markdown table (rays, solve time, rays/s, errors) and draws both curves on log-log
axes into a PNG (numpy + OpenImageIO; no matplotlib needed).

    /usr/bin/python3 tests/bench/radiosity_convergence.py --addon-dir build/stage \\
        [--blender blender] [--out docs/radiosity_convergence.png] [--budgets 250 500 ...]
"""

import argparse
import math
import os
import re
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

from loglog_plot import plot

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "test_scenes" / "validation" / "cornell_radiosity.blend"
STATS = re.compile(r"radiosity: ([\d,]+) patches .*?, ([\d,]+) rays in ([\d.]+) s "
                   r"\(([\d.]+) M rays/s\)")


def read_rgb(path):
    return oiio.ImageBuf(str(path)).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)


def rel_rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)) / np.mean(b))


def render(blender, addon_dir, kilo_rays, out):
    expr = f"import bpy; bpy.context.scene.photon.radiosity_rays = {kilo_rays}"
    cmd = [blender, "-b", "--factory-startup", "--addons", "photon", str(SCENE), "-E", "PHOTON",
           "--python-expr", expr, "-o", f"{out}_####", "-F", "OPEN_EXR", "-x", "1", "-f", "1"]
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    match = STATS.search(proc.stdout)
    if not match:
        raise SystemExit(f"no radiosity statistics in Blender's output:\n{proc.stdout}")
    patches, rays, seconds, mrays = match.groups()
    return {"kilo_rays": kilo_rays, "rays": int(rays.replace(",", "")),
            "patches": int(patches.replace(",", "")), "seconds": float(seconds),
            "mrays_per_s": float(mrays), "image": read_rgb(f"{out}_0001.exr")}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--addon-dir", required=True, help="folder holding addons/photon")
    parser.add_argument("--out", default=str(ROOT / "docs" / "radiosity_convergence.png"))
    parser.add_argument("--budgets", type=int, nargs="+",
                        default=[250, 500, 1000, 2000, 4000, 8000, 16000, 32000, 64000],
                        help="radiosity rays in thousands; the largest is the noise reference")
    args = parser.parse_args()
    cycles = read_rgb(SCENE.with_suffix(".exr"))
    budgets = sorted(args.budgets)
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in budgets:
            runs.append(render(args.blender, Path(args.addon_dir).resolve(), k,
                               Path(tmp) / f"r{k}"))
            r = runs[-1]
            print(f"rendered {r['rays']:,} rays in {r['seconds']:.2f} s", flush=True)
    best = runs[-1]["image"]
    print(f"\n{runs[0]['patches']:,} patches; error of the image (relative RMSE, mean difference)")
    print("| rays | solve s | M rays/s | rel. RMSE vs Cycles | mean diff vs Cycles | "
          f"rel. RMSE vs {runs[-1]['rays'] / 1e6:.0f}M-ray run |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    vs_cycles, vs_best = [], []
    for r in runs:
        e_c = rel_rmse(r["image"], cycles)
        mean_diff = float(np.mean(r["image"]) / np.mean(cycles) - 1.0)
        e_b = rel_rmse(r["image"], best) if r is not runs[-1] else float("nan")
        vs_cycles.append((r["rays"], e_c))
        if r is not runs[-1]:
            vs_best.append((r["rays"], e_b))
        print(f"| {r['rays']:,} | {r['seconds']:.2f} | {r['mrays_per_s']:.2f} | {e_c:.4f} | "
              f"{mean_diff:+.4f} | {'-' if math.isnan(e_b) else f'{e_b:.4f}'} |")
    # 1/sqrt(N) through the first noise point, for comparison.
    n0, e0 = vs_best[0]
    slope = [(n, e0 * math.sqrt(n0 / n)) for n, _ in vs_cycles]
    plot(args.out,
         [("vs Cycles reference (4096 spp)", (0.85, 0.2, 0.15), vs_cycles),
          (f"vs {runs[-1]['rays'] / 1e6:.0f}M-ray radiosity", (0.15, 0.35, 0.8), vs_best),
          ("1 / sqrt(rays)", (0.4, 0.4, 0.4), slope)],
         "radiosity rays", "relative RMSE",
         f"RADIOSITY, Cornell box, {runs[0]['patches']:,} patches: error vs rays")
    print(f"\nwrote {args.out}")


if __name__ == "__main__":
    main()
