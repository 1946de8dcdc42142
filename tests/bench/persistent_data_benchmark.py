"""Persistent Data over an animation: a 1-million-triangle smooth, UV-mapped grid (static), a
moving sphere and a camera moving over 5 frames, rendered with `-a` semantics
(render(animation=True)) with Render > Performance > Persistent Data off, then on. Prints per
frame the sync, BVH and total seconds Photon reports, and the mean saved per frame after the
first.

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \
        -P tests/bench/persistent_data_benchmark.py
"""

import contextlib
import io
import re
import statistics
import tempfile

import bpy

SUBDIVISIONS = 708  # (708 - 1)^2 quads = 999,698 triangles
FRAMES = 5
LINE = re.compile(r"^Photon: rendered frame (\d+) .*sync ([\d.]+) s .*BVH ([\d.]+) s, "
                  r"render ([\d.]+) s, total ([\d.]+) s", re.MULTILINE)


def build_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=SUBDIVISIONS, y_subdivisions=SUBDIVISIONS,
                                    size=4.0, calc_uvs=True)
    grid = bpy.context.active_object
    grid.data.polygons.foreach_set("use_smooth", [True] * len(grid.data.polygons))
    grid.data.update()
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.3, location=(0, 0, 0.5))
    ball = bpy.context.active_object
    scene = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(cam)
    scene.camera = cam
    for frame in range(1, FRAMES + 1):
        cam.location = (0.2 * frame, -0.5, 5.0)
        cam.keyframe_insert("location", frame=frame)
        ball.location.x = 0.3 * frame - 1.0
        ball.keyframe_insert("location", frame=frame)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
    scene.collection.objects.link(sun)
    scene.frame_start, scene.frame_end = 1, FRAMES
    scene.render.engine = 'PHOTON'
    scene.render.resolution_x = scene.render.resolution_y = 64
    scene.render.use_compositing = False
    scene.photon.integrator = 'RAY_TRACE'  # isolates sync and BVH from lighting work
    scene.photon.samples = 1
    scene.render.image_settings.file_format = 'PNG'
    scene.render.filepath = tempfile.mkdtemp(prefix="photon_persist_bench_") + "/f_####"
    return scene, len(grid.data.polygons) * 2


def run(scene, persistent):
    scene.render.use_persistent_data = persistent
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        bpy.ops.render.render(animation=True)
    rows = [(int(f), float(s), float(b), float(r), float(t))
            for f, s, b, r, t in LINE.findall(out.getvalue())]
    assert len(rows) == FRAMES, out.getvalue()
    return rows


def main():
    scene, triangles = build_scene()
    print(f"BENCH persistent data: {triangles:,} triangles, {FRAMES} frames, moving camera "
          f"and sphere")
    results = {}
    for persistent in (False, True):
        rows = run(scene, persistent)
        results[persistent] = rows
        label = "on " if persistent else "off"
        for frame, sync, bvh, render, total in rows:
            print(f"BENCH persistent {label} frame {frame}: sync {sync:.3f} s, BVH {bvh:.3f} s, "
                  f"render {render:.3f} s, total {total:.3f} s")
    off, on = results[False][1:], results[True][1:]
    for name, column in (("sync", 1), ("BVH", 2), ("total", 4)):
        before = statistics.mean(row[column] for row in off)
        after = statistics.mean(row[column] for row in on)
        print(f"BENCH frames 2-{FRAMES} mean {name}: {before:.3f} s off, {after:.3f} s on, "
              f"saved {before - after:.3f} s per frame")


main()
