#!/usr/bin/python3
"""Photon against Cycles at equal wall time on scenes other people made.

FOLDER holds NAME.blend files and refs/NAME.exr, a converged Cycles reference of each, with
refs/NAME.txt saying at which resolution percentage it was rendered ("... pct 16"); the scenes'
licences are not the project's, so they stay outside the repository (SOURCES.md in the folder says
where each came from). Each scene is rendered at that percentage with Photon (its defaults, or the
file's scene.photon, plus --photon-expr), then with Cycles given Photon's render time as its Time
Limit (the file's own Cycles settings, adaptive sampling on at its default threshold, no denoising;
the limit is Photon's time less what Cycles spends besides sampling, measured with one sample).
Prints per scene the image means against the reference and the relative RMSE of both renders; the
reference's own noise is not taken out, so small errors are floors rather than values.

    tests/bench/third_party_vs_cycles.py FOLDER --addon-dir build/stage [--scenes bmw27 mic]
        [--photon-expr "bpy.context.scene.photon.adaptive_sampling = True"] [--keep DIR]
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio


def read_rgb(path):
    return oiio.ImageBuf(str(path)).get_pixels(oiio.FLOAT)[..., :3]


def render(blender, addon_dir, blend, engine, out, expr):
    cmd = [blender, "-b", "--factory-startup", "--addons", "photon", str(blend), "-E", engine,
           "--python-expr", expr, "-o", f"{out}_####", "-F", "OPEN_EXR", "-x", "1", "-f", "1"]
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    exr = Path(f"{out}_0001.exr")
    if proc.returncode != 0 or not exr.exists():
        sys.exit(f"{engine} render of {blend} failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}")
    # Blender's own render time (excludes start-up and file loading): the last "Time: mm:ss.xx".
    times = re.findall(r"Time: (\d+):(\d+\.\d+)", proc.stdout)
    seconds = int(times[-1][0]) * 60 + float(times[-1][1]) if times else wall
    return exr, seconds, proc.stdout


def errors(image, reference):
    rel_rmse = float(np.sqrt(np.mean((image - reference) ** 2)) / reference.mean())
    return float(image.mean() / reference.mean()), rel_rmse


def common_expr(pct):
    return ("import bpy; s = bpy.context.scene; "
            f"s.render.resolution_percentage = {pct}; s.render.use_border = False; ")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=Path)
    parser.add_argument("--addon-dir", required=True, type=Path)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--scenes", nargs="*", help="names (default: every refs/NAME.exr)")
    parser.add_argument("--photon-expr", default="", help="Python run before the Photon render")
    parser.add_argument("--keep", type=Path, help="copy the renders here")
    args = parser.parse_args()
    names = args.scenes or sorted(p.stem for p in (args.folder / "refs").glob("*.exr"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for name in names:
            blend = args.folder / f"{name}.blend"
            reference = read_rgb(args.folder / "refs" / f"{name}.exr")
            pct = int(re.search(r"pct (\d+)",
                                (args.folder / "refs" / f"{name}.txt").read_text()).group(1))
            expr = common_expr(pct)
            photon_exr, photon_time, log = render(args.blender, args.addon_dir, blend, "PHOTON",
                                                  tmp / f"{name}_photon",
                                                  expr + args.photon_expr)
            summary = re.search(r"Photon: rendered frame \d+ \d+x\d+ \(([^)]*)\)", log)
            cycles_expr = expr + (
                "c = s.cycles; c.use_adaptive_sampling = True; c.adaptive_threshold = 0.01; "
                "c.adaptive_min_samples = 0; c.use_denoising = False; c.seed = 99; ")
            # Cycles' Time Limit counts its sampling only: what it spends besides (synchronising,
            # building its BVH, loading kernels, writing the file) is measured with one sample
            # and taken off, so both engines take the same wall time from render start to file.
            _, overhead, _ = render(args.blender, args.addon_dir, blend, "CYCLES",
                                    tmp / f"{name}_overhead",
                                    cycles_expr + "c.samples = 1; c.use_adaptive_sampling = False")
            budget = max(photon_time - overhead, 0.5)
            cycles_exr, cycles_time, cycles_log = render(
                args.blender, args.addon_dir, blend, "CYCLES", tmp / f"{name}_cycles",
                cycles_expr + f"c.samples = 1 << 16; c.time_limit = {budget:.2f}")
            samples = [int(n) for n in re.findall(r"Sample (\d+)/\d+", cycles_log)]
            photon = errors(read_rgb(photon_exr), reference)
            cycles = errors(read_rgb(cycles_exr), reference)
            rows.append((name, photon_time, summary.group(1) if summary else "?", photon,
                         cycles_time, max(samples) if samples else "?", cycles))
            print(f"{name}: Photon {photon_time:.1f} s ({rows[-1][2]}): mean {photon[0]:.4f}, "
                  f"relative RMSE {photon[1]:.4f} | Cycles {cycles_time:.1f} s "
                  f"({rows[-1][5]} samples): mean {cycles[0]:.4f}, relative RMSE {cycles[1]:.4f}",
                  flush=True)
            if args.keep:
                args.keep.mkdir(parents=True, exist_ok=True)
                shutil.copy(photon_exr, args.keep / f"{name}_photon.exr")
                shutil.copy(cycles_exr, args.keep / f"{name}_cycles.exr")
    print("\n| scene | Photon s | Photon mean / ref | Photon rel. RMSE | Cycles s | Cycles samples "
          "| Cycles mean / ref | Cycles rel. RMSE |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, pt, _, (pm, pr), ct, cs, (cm, cr) in rows:
        print(f"| {name} | {pt:.1f} | {pm:.4f} | {pr:.4f} | {ct:.1f} | {cs} | {cm:.4f} | {cr:.4f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
