"""Sync time of a 1-million-triangle smooth-shaded, UV-mapped mesh: Photon's depsgraph sync (and
sync + BVH + a 1-pixel render) beside Cycles' time for the same 1-pixel render.

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \
        -P tests/bench/sync_benchmark.py
"""

import statistics
import time

import bpy

SUBDIVISIONS = 708  # (708 - 1)^2 quads = 499,849 quads = 999,698 triangles
RUNS = 3


def build_scene():
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
    scene.render.use_compositing = False
    return scene, len(grid.data.polygons) * 2


def time_photon_sync():
    from photon import _photon, report, sync
    times = []
    for _ in range(RUNS):
        depsgraph = bpy.context.evaluated_depsgraph_get()
        t0 = time.perf_counter()
        native_scene, stats = sync.sync_scene(_photon, depsgraph, report.Reporter())
        times.append(time.perf_counter() - t0)
        triangles = native_scene.triangle_count
        del native_scene
    return statistics.median(times), triangles


def time_render(scene, engine):
    scene.render.engine = engine
    if engine == 'CYCLES':
        scene.cycles.samples = 1
        scene.cycles.device = 'CPU'
        scene.cycles.use_denoising = False
    else:
        scene.photon.samples = 1
    times = []
    for _ in range(RUNS):
        t0 = time.perf_counter()
        bpy.ops.render.render()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    scene, triangles = build_scene()
    sync_s, synced = time_photon_sync()
    photon_s = time_render(scene, 'PHOTON')
    cycles_s = time_render(scene, 'CYCLES')
    print(f"BENCH mesh triangles: {triangles:,} (synced {synced:,})")
    print(f"BENCH Photon sync (depsgraph -> native scene): {sync_s:.3f} s")
    print(f"BENCH Photon 1-pixel render (sync + BVH + render): {photon_s:.3f} s")
    print(f"BENCH Cycles 1-pixel render (sync + BVH + render): {cycles_s:.3f} s")


main()
