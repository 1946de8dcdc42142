"""Time to first pixel of a 1-million-triangle smooth-shaded, UV-mapped mesh, Photon beside
Cycles, rendered back to back in one Blender process (1 sample, 1x1 pixel, so the figures are
sync + BVH + one sample).

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \
        -P tests/bench/sync_benchmark.py [-- --runs 5 --threads 0]

For Photon it prints the engine's own breakdown (sync, BVH, first sample) and the wall time of
bpy.ops.render.render(); for Cycles the wall time of bpy.ops.render.render(). Each figure is
the minimum over the runs (the machine may be shared: the minimum is the least disturbed run),
and the engines alternate run by run so a load change hits both alike.
"""

import argparse
import re
import sys
import time

import bpy

SUBDIVISIONS = 708  # (708 - 1)^2 quads = 499,849 quads = 999,698 triangles

# The engine's summary line: "... sync 0.123 s (...), BVH 0.456 s, render 0.012 s, total 0.7 s".
SUMMARY = re.compile(r"sync ([\d.]+) s .*BVH ([\d.]+) s, render ([\d.]+) s, total ([\d.]+) s")


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="sync_benchmark.py")
    parser.add_argument("--runs", type=int, default=5, help="runs per engine (minimum reported)")
    parser.add_argument("--threads", type=int, default=0, help="render threads (0: all cores)")
    parser.add_argument("--no-cycles", action="store_true", help="time Photon only")
    parser.add_argument("--integrator", default="RAY_TRACE",
                        help="Photon integrator (RAY_TRACE compares like with like: Cycles has "
                             "no photon pre-pass; PHOTON_MAP adds its photon tracing)")
    return parser.parse_args(argv)


def build_scene(threads, integrator):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=SUBDIVISIONS, y_subdivisions=SUBDIVISIONS,
                                    size=4.0, calc_uvs=True)
    grid = bpy.context.active_object
    grid.data.polygons.foreach_set("use_smooth", [True] * len(grid.data.polygons))
    grid.data.update()
    scene = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.location = (0, 0, 5)
    scene.collection.objects.link(cam)
    scene.camera = cam
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
    scene.collection.objects.link(sun)
    scene.render.resolution_x = scene.render.resolution_y = 1
    scene.render.resolution_percentage = 100
    scene.render.use_compositing = False
    scene.render.use_sequencer = False
    scene.render.threads_mode = 'FIXED' if threads > 0 else 'AUTO'
    if threads > 0:
        scene.render.threads = threads
    scene.photon.samples = 1
    scene.photon.integrator = integrator
    scene.cycles.samples = 1
    scene.cycles.device = 'CPU'
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    return scene, len(grid.data.polygons) * 2


class PhotonSummary:
    """Captures the engine's summary line (Reporter.info) and its RenderSession's stats during
    one render."""

    def __init__(self):
        from photon import _photon, report
        self._report = report
        self._info = report.Reporter.info
        self._native = _photon
        self._session_type = _photon.RenderSession
        self.sessions = []
        self.line = ""

    def __enter__(self):
        original = self._info

        def info(reporter, message):
            if SUMMARY.search(message):
                self.line = message
            original(reporter, message)

        def session(*args, **kwargs):
            made = self._session_type(*args, **kwargs)
            self.sessions.append(made)
            return made

        self._report.Reporter.info = info
        self._native.RenderSession = session
        return self

    def __exit__(self, *exc):
        self._report.Reporter.info = self._info
        self._native.RenderSession = self._session_type


def render_once(scene, engine):
    scene.render.engine = engine
    t0 = time.perf_counter()
    bpy.ops.render.render()
    return time.perf_counter() - t0


def main():
    args = parse_args()
    scene, triangles = build_scene(args.threads, args.integrator)
    engines = ['PHOTON'] + ([] if args.no_cycles else ['CYCLES'])
    for engine in engines:  # warm-up: kernels, add-on import, caches; not timed
        render_once(scene, engine)

    photon = {"sync": [], "bvh": [], "prepare": [], "sample": [], "engine total": [],
              "wall": []}
    cycles = []
    for _ in range(args.runs):
        with PhotonSummary() as summary:
            wall = render_once(scene, 'PHOTON')
        match = SUMMARY.search(summary.line)
        if not match:
            raise SystemExit(f"no Photon summary line captured (got {summary.line!r})")
        for key, value in zip(("sync", "bvh", "sample", "engine total"), match.groups()):
            photon[key].append(float(value))
        photon["wall"].append(wall)
        photon["prepare"].append(summary.sessions[-1].stats.prepare_seconds)
        if 'CYCLES' in engines:
            cycles.append(render_once(scene, 'CYCLES'))

    print(f"BENCH mesh triangles: {triangles:,}; min of {args.runs} runs, "
          f"threads {args.threads or 'all'}, Photon integrator {args.integrator}")
    print(f"BENCH Photon sync (depsgraph -> native scene): {min(photon['sync']):.3f} s")
    print(f"BENCH Photon BVH (+ lights, emitters):        {min(photon['bvh']):.3f} s")
    print(f"BENCH Photon prepare (photon pre-pass):       {min(photon['prepare']):.3f} s")
    print(f"BENCH Photon first sample (1x1 px, 1 spp):    {min(photon['sample']):.3f} s")
    print(f"BENCH Photon total in engine.render():        {min(photon['engine total']):.3f} s")
    print(f"BENCH Photon time to first pixel (render op): {min(photon['wall']):.3f} s")
    if cycles:
        print(f"BENCH Cycles time to first pixel (render op): {min(cycles):.3f} s")
        print(f"BENCH Photon / Cycles: {min(photon['wall']) / min(cycles):.2f}")
    print("BENCH all Photon render-op runs: " + " ".join(f"{t:.3f}" for t in photon["wall"]))
    if cycles:
        print("BENCH all Cycles render-op runs: " + " ".join(f"{t:.3f}" for t in cycles))


main()
