#!/usr/bin/python3
"""Thread scaling and memory figures (a benchmark, not a test: it prints, it does not assert).

    tests/bench/scaling_memory_benchmark.py --build build [--runs 3] [--skip scaling,triangles,photons]

(a) 1 -> 2 thread speed-up of the default Cornell render (test_scenes/cornell_box.blend,
    Blender's -t 1 against -t 2): the engine's own render time (after sync and BVH) and the
    whole render, min of --runs runs each. On a machine shared with other jobs the figure is
    only indicative: rerun it on a quiet one.
(b) Memory per million triangles: peak RSS (/usr/bin/time) of a Photon render of a 1M-triangle
    grid minus that of the same Blender process building the grid without rendering, with the
    same difference for an empty scene taken off, so Blender's own copy of the mesh is excluded.
(c) Memory per million photons: peak RSS of build/photon_cli --photons N for N = 0, 1M, 2M,
    beside the size of the maps the CLI reports (photon_map_bytes).
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SUMMARY = re.compile(r"sync ([\d.]+) s .*BVH ([\d.]+) s, render ([\d.]+) s, total ([\d.]+) s")

# Builds a grid of about N triangles (N from argv after --), optionally renders it with Photon
# (RAY_TRACE, 1 sample, 1x1 pixel): the scene Blender holds is the same either way.
GRID_SCRIPT = r'''
import sys, bpy
args = sys.argv[sys.argv.index("--") + 1:]
triangles, render = int(args[0]), args[1] == "render"
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
if triangles:
    side = int(round((triangles / 2) ** 0.5)) + 1
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=side, y_subdivisions=side, size=4.0)
cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
cam.location = (0, 0, 5)
scene.collection.objects.link(cam)
scene.camera = cam
scene.render.resolution_x = scene.render.resolution_y = 1
scene.render.use_compositing = False
scene.render.engine = 'PHOTON'
scene.photon.integrator = 'RAY_TRACE'
scene.photon.samples = 1
bpy.context.evaluated_depsgraph_get()
if render:
    bpy.ops.render.render()
'''


def peak_rss_mb(cmd, env=None):
    """Peak resident set size of `cmd` in MB (GNU time's %M, in KiB)."""
    with tempfile.NamedTemporaryFile("r", suffix=".txt") as out:
        proc = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", out.name] + cmd, env=env,
                              capture_output=True, text=True)
        if proc.returncode != 0:
            sys.exit(f"failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stdout}\n{proc.stderr}")
        return int(out.read().split()[-1]) / 1024.0, proc.stdout


def blender_env(build):
    return dict(os.environ, BLENDER_USER_SCRIPTS=str(build / "stage"))


def cornell_times(args, threads):
    """(engine render seconds, engine total seconds), min over the runs."""
    render, total = [], []
    for _ in range(args.runs):
        with tempfile.TemporaryDirectory() as tmp:
            cmd = [args.blender, "-b", "--factory-startup", "--addons", "photon",
                   str(REPO / "test_scenes" / "cornell_box.blend"), "-E", "PHOTON",
                   "-o", f"{tmp}/c_####", "-F", "PNG", "-x", "1", "-t", str(threads), "-f", "1"]
            proc = subprocess.run(cmd, env=blender_env(args.build), capture_output=True,
                                  text=True)
        match = SUMMARY.search(proc.stdout)
        if proc.returncode != 0 or not match:
            sys.exit(f"Cornell render with -t {threads} failed:\n{proc.stdout[-2000:]}")
        render.append(float(match.group(3)))
        total.append(float(match.group(4)))
    return min(render), min(total)


def scaling(args):
    r1, t1 = cornell_times(args, 1)
    r2, t2 = cornell_times(args, 2)
    print(f"BENCH Cornell render -t 1: render {r1:.2f} s, total {t1:.2f} s (min of {args.runs})")
    print(f"BENCH Cornell render -t 2: render {r2:.2f} s, total {t2:.2f} s (min of {args.runs})")
    print(f"BENCH 1 -> 2 thread speed-up: render {r1 / r2:.2f}x, total {t1 / t2:.2f}x "
          f"(load average now {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores)")


def grid_rss(args, triangles, render):
    with tempfile.NamedTemporaryFile("w", suffix=".py") as script:
        script.write(GRID_SCRIPT)
        script.flush()
        cmd = [args.blender, "-b", "--factory-startup", "--addons", "photon", "-P", script.name,
               "--", str(triangles), "render" if render else "none"]
        rss, out = peak_rss_mb(cmd, env=blender_env(args.build))
        if render and not SUMMARY.search(out):
            sys.exit(f"Photon did not render the {triangles}-triangle grid:\n{out[-2000:]}")
        return rss


def triangle_memory(args):
    million = 1_000_000
    rows = {}
    for triangles in (0, million):
        rows[triangles] = [min(grid_rss(args, triangles, render) for _ in range(args.runs))
                           for render in (False, True)]
    photon_0 = rows[0][1] - rows[0][0]
    photon_1m = rows[million][1] - rows[million][0]
    print(f"BENCH peak RSS, empty scene: Blender {rows[0][0]:.0f} MB, with a Photon render "
          f"{rows[0][1]:.0f} MB")
    print(f"BENCH peak RSS, 1M-triangle grid: Blender {rows[million][0]:.0f} MB, with a Photon "
          f"render {rows[million][1]:.0f} MB")
    print(f"BENCH Photon memory per million triangles: {photon_1m - photon_0:.0f} MB "
          f"(render minus no render, 1M grid minus empty scene)")


def photon_memory(args):
    cli = args.build / "photon_cli"
    rss = {}
    estimate = {}
    for count in (0, 1_000_000, 2_000_000):
        with tempfile.TemporaryDirectory() as tmp:
            cmd = [str(cli), "--scene", "cornell", "--width", "32", "--height", "32",
                   "--samples", "1", "--photons", str(count), "--caustic-photons", "0",
                   "--out", f"{tmp}/p.exr"]
            rss[count], out = min(peak_rss_mb(cmd) for _ in range(args.runs))
            found = re.search(r"photon_map_bytes: (\d+)", out)
            estimate[count] = int(found.group(1)) / 1e6 if found else None
    for count in (1_000_000, 2_000_000):
        per_million = (rss[count] - rss[0]) / (count / 1e6)
        note = (f"; the photon maps themselves: {estimate[count]:.0f} MB (photon_map_bytes)"
                if estimate[count] else "")
        print(f"BENCH photon_cli --photons {count:,}: peak RSS {rss[count]:.0f} MB "
              f"(0 photons: {rss[0]:.0f} MB) -> {per_million:.0f} MB per million photons{note}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", type=Path, default=REPO / "build")
    parser.add_argument("--blender", default="/usr/bin/blender")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--skip", default="", help="comma list: scaling,triangles,photons")
    args = parser.parse_args()
    skip = set(filter(None, args.skip.split(",")))
    if "scaling" not in skip:
        scaling(args)
    if "triangles" not in skip:
        triangle_memory(args)
    if "photons" not in skip:
        photon_memory(args)


main()
