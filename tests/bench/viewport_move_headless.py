"""A moved object in the viewport's native pipeline, driven from Python in background Blender
(no GUI, so no redraw or texture upload in the figures): a 999,698-triangle grid and a small
cube, synced once; the cube moves MOVES times. For each move, the old path (sync the scene
again through the MeshCache and BlasCache, new session building the top level, lights and
textures) and the new one (ViewportScene.move_instances, new session on the shared
resources) are timed from the edit to the session's first image (the coarse quick image) and
to its first full-resolution image. Both paths start sessions with the coarse first pass, so
the difference is what the transform path saves (sync, top-level/lights/emitter build); the
figures before the coarse pass came from the GUI benchmark (viewport_incremental_benchmark.py).

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \
        -P tests/bench/viewport_move_headless.py -- [MOVES]
"""

import statistics
import sys
import time

import bpy
import numpy as np

from photon import render_settings, report, sync
from photon.native import native_module
from photon.sync import cache as sync_cache
from photon.sync.origin import rebased_matrix

ARGS = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
MOVES = int(ARGS[0]) if ARGS else 5
SUBDIVISIONS = 708  # (708 - 1)^2 quads = 999,698 triangles
WIDTH, HEIGHT = 800, 520


def build_scene():
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=SUBDIVISIONS, y_subdivisions=SUBDIVISIONS,
                                    size=8.0, location=(0.0, 0.0, -1.0))
    cube = scene.objects["Cube"]
    cube.scale = (0.3, 0.3, 0.3)
    scene.camera.location = (0.0, -6.0, 4.0)
    scene.camera.rotation_euler = (0.9, 0.0, 0.0)
    scene.render.engine = 'PHOTON'
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.render.resolution_percentage = 100
    scene.photon.preview_samples = 8
    scene.photon.photons = 50000
    scene.photon.caustic_photons = 20000
    return cube


def first_images(session, t0):
    """(seconds to the first image of any kind, to the first full-resolution one)."""
    first = None
    while True:
        image = session.image()
        if image is not None and first is None:
            first = time.perf_counter() - t0
        if image is not None and image[0].shape[:2] == (HEIGHT, WIDTH):
            return first, time.perf_counter() - t0
        time.sleep(0.001)


def main():
    native = native_module()
    cube = build_scene()
    scene = bpy.context.scene
    settings = render_settings.viewport_settings(native, scene, WIDTH, HEIGHT, (0, 0, WIDTH, HEIGHT))
    reporter = report.Reporter(None)
    mesh_cache, blas_cache = sync_cache.MeshCache(), native.BlasCache()
    results = {"full": [], "transform": []}

    def full_path(depsgraph, previous):
        if previous is not None:
            previous.cancel()
            previous.wait()
        blas_cache.begin_frame()
        native_scene, stats = sync.sync_scene(native, depsgraph, reporter,
                                              mesh_cache=mesh_cache)
        session = native.ProgressiveSession(native_scene, settings, blas_cache=blas_cache)
        session.start()
        return session, native_scene, stats

    depsgraph = bpy.context.evaluated_depsgraph_get()
    session, native_scene, stats = full_path(depsgraph, None)
    first_images(session, time.perf_counter())
    for k in range(MOVES):  # the old path: every edit re-syncs
        cube.location.x += 0.05
        depsgraph.update()
        t0 = time.perf_counter()
        mesh_cache.reclaim(native_scene)
        session, native_scene, stats = full_path(depsgraph, session)
        results["full"].append(first_images(session, t0))
        stats.release()
    session.cancel()
    session.wait()

    # The new path: one sync, then moves re-place the cube's instance.
    instances = {}
    mesh_cache.reclaim(native_scene)
    native_scene, stats = sync.sync_scene(native, depsgraph, reporter,
                                          object_instances=instances, mesh_cache=mesh_cache)
    shared = native.ViewportScene(native_scene, blas_cache)
    session = native.ProgressiveSession(shared, settings)
    session.start()
    first_images(session, time.perf_counter())
    for k in range(MOVES):
        cube.location.x -= 0.05
        depsgraph.update()
        t0 = time.perf_counter()
        session.cancel()
        session.wait()
        matrix = rebased_matrix(depsgraph.objects["Cube"].matrix_world, stats.origin)
        indices = instances["Cube"]
        shared.move_instances(indices, np.stack([matrix] * len(indices)))
        session = native.ProgressiveSession(shared, settings)
        session.start()
        results["transform"].append(first_images(session, t0))
    session.cancel()
    session.wait()
    stats.release()

    for kind, times in results.items():
        first = [t[0] for t in times]
        full = [t[1] for t in times]
        print(f"benchmark: {kind} path, {WIDTH}x{HEIGHT}, 1M triangles: edit to first image "
              f"median {statistics.median(first):.3f} s (min {min(first):.3f}), to first "
              f"full-resolution image median {statistics.median(full):.3f} s "
              f"(min {min(full):.3f})", flush=True)


main()
