#!/usr/bin/python3
"""Thread scaling and memory figures (a benchmark, not a test: it prints, it does not assert).

    tests/bench/scaling_memory_benchmark.py --build build [--runs 3] [--skip scaling,triangles,photons]

(a) 1 -> 2 thread speed-up of the default Cornell render (test_scenes/cornell_box.blend,
    Blender's -t 1 against -t 2): the engine's own render time (after sync and BVH) and the
    whole render, min of --runs runs each. On a machine shared with other jobs the figure is
    only indicative: rerun it on a quiet one.
(b) Memory per million triangles: the peak RSS Photon adds over the built scene (sync, BVH and
    a 1-pixel render, run in Blender as the engine runs them) for a 1M-triangle grid, minus the
    same for an empty scene; Blender's own copies of the mesh are not counted.
(c) Memory per million photons: peak RSS of build/photon_cli --photons N for N = 0, 1M, 2M,
    beside the CLI's photon_map_bytes and memory_estimate_bytes (photon_memory.h's model).
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

# Builds a grid of about N triangles (N from argv after --), then measures the peak RSS that
# Photon adds on top of the built scene: the peak is reset (Linux: "5" > /proc/self/clear_refs)
# and Photon's own steps run as the engine runs them (sync, then a RenderSession: BVH and a 1x1
# pixel, 1-sample RAY_TRACE render), so Blender's own copies of the mesh are not counted.
GRID_SCRIPT = r'''
import sys, bpy
args = sys.argv[sys.argv.index("--") + 1:]
triangles = int(args[0])
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
scene.render.resolution_percentage = 100
scene.photon.integrator = 'RAY_TRACE'
scene.photon.samples = 1
depsgraph = bpy.context.evaluated_depsgraph_get()
from photon import _photon, render_settings, report, sync
from photon.sync import camera as sync_camera

def status(key):
    for line in open("/proc/self/status"):
        if line.startswith(key + ":"):
            return int(line.split()[1]) / 1024.0

with open("/proc/self/clear_refs", "w") as f:
    f.write("5")
before = status("VmRSS")
native_scene, stats = sync.sync_scene(_photon, depsgraph, report.Reporter())
region = sync_camera.render_region(scene.render, 1, 1)
session = _photon.RenderSession(native_scene, render_settings.make_settings(_photon, scene, 1, 1, region))
session.start()
session.wait()
print(f"PHOTON_PEAK_MB {status('VmHWM') - before:.1f} triangles {native_scene.triangle_count}")
stats.release()
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


def photon_peak_mb(args, triangles):
    """(peak MB Photon adds over the built scene, triangles synced)."""
    with tempfile.NamedTemporaryFile("w", suffix=".py") as script:
        script.write(GRID_SCRIPT)
        script.flush()
        cmd = [args.blender, "-b", "--factory-startup", "--addons", "photon", "-P", script.name,
               "--", str(triangles)]
        proc = subprocess.run(cmd, env=blender_env(args.build), capture_output=True, text=True)
        found = re.search(r"PHOTON_PEAK_MB ([\d.]+) triangles (\d+)", proc.stdout)
        if not found:
            sys.exit(f"the {triangles}-triangle memory run failed:\n{proc.stdout[-2000:]}"
                     f"\n{proc.stderr[-2000:]}")
        return float(found.group(1)), int(found.group(2))


def triangle_memory(args):
    empty, _ = min(photon_peak_mb(args, 0) for _ in range(args.runs))
    grid, synced = min(photon_peak_mb(args, 1_000_000) for _ in range(args.runs))
    per_million = (grid - empty) / (synced / 1e6)
    print(f"BENCH Photon peak memory over the built scene (sync + BVH + 1 px): empty scene "
          f"{empty:.0f} MB, {synced:,}-triangle grid {grid:.0f} MB -> {per_million:.0f} MB per "
          f"million triangles")


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
            maps = re.search(r"photon_map_bytes: ([\d.e+]+)", out)
            model = re.search(r"memory_estimate_bytes: ([\d.e+]+)", out)
            estimate[count] = (float(maps.group(1)) / 1e6 if maps else None,
                               float(model.group(1)) / 1e6 if model else None)
    for count in (1_000_000, 2_000_000):
        per_million = (rss[count] - rss[0]) / (count / 1e6)
        maps, model = estimate[count]
        note = f"; photon maps {maps:.0f} MB" if maps is not None else ""
        note += (f", photon_memory model estimate {model:.0f} MB"
                 if model is not None else "")
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
