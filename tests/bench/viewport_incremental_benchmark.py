"""Viewport edits in Blender's GUI (under Xvfb): seconds from view_update to the restarted
session's first image when one object moves, on the Cornell box and on a 1-million-triangle
grid with a small cube. Prints per move the time and the sync kind the viewport took (the
'sync_counts' of photon.viewport, absent before incremental updates), then the median.

    BLENDER_USER_SCRIPTS=build/stage xvfb-run -a -s "-screen 0 960x640x24" blender \
        --factory-startup --addons photon [test_scenes/cornell_box.blend] \
        --python tests/bench/viewport_incremental_benchmark.py -- SCENE [MOVES]

SCENE is 'cornell' (the .blend given, moving its TallBox) or 'million' (built here from the
factory startup scene: a 999,698-triangle grid under its cube, which moves).
"""

import statistics
import sys
import time
import traceback

import bpy

ARGS = sys.argv[sys.argv.index("--") + 1:]
SCENE = ARGS[0]
MOVES = int(ARGS[1]) if len(ARGS) > 1 else 5
TIMEOUT = 300.0
SUBDIVISIONS = 708  # (708 - 1)^2 quads = 999,698 triangles


def viewport():
    window = bpy.context.window_manager.windows[0]
    for area in window.screen.areas:
        if area.type == 'VIEW_3D':
            return window, area, next(r for r in area.regions if r.type == 'WINDOW')
    raise RuntimeError("no 3D viewport")


def build_million():
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=SUBDIVISIONS, y_subdivisions=SUBDIVISIONS,
                                    size=8.0, location=(0.0, 0.0, -1.0))
    cube = scene.objects["Cube"]
    cube.scale = (0.3, 0.3, 0.3)
    scene.camera.location = (0.0, -6.0, 4.0)
    scene.camera.rotation_euler = (0.9, 0.0, 0.0)
    return cube


def steps():
    scene = bpy.context.scene
    moving = build_million() if SCENE == "million" else scene.objects["TallBox"]
    scene.render.engine = 'PHOTON'
    scene.photon.preview_samples = 8
    scene.photon.photons = 50000
    scene.photon.caustic_photons = 20000
    window, area, region = viewport()
    space = area.spaces[0]
    space.overlay.show_overlays = False
    space.shading.type = 'RENDERED'
    space.region_3d.view_perspective = 'CAMERA'
    with bpy.context.temp_override(window=window, screen=window.screen, area=area,
                                   region=region):
        bpy.ops.view3d.view_center_camera()
    import photon.viewport as vp
    yield 0.5

    def wait_converged():
        t0 = time.time()
        while not (vp.last_draw.get("converged") and vp.last_draw.get("current")):
            if time.time() - t0 > TIMEOUT:
                raise RuntimeError(f"viewport did not converge: {vp.last_draw}")
            yield 0.05
        yield 0.2

    yield from wait_converged()
    counts = getattr(vp, "sync_counts", None)
    times = []
    for k in range(MOVES):
        vp.last_edit_to_image_seconds = None
        moving.location.x += 0.05 if k % 2 == 0 else -0.03
        vp.last_draw.clear()
        t0 = time.time()
        while vp.last_edit_to_image_seconds is None:
            if time.time() - t0 > TIMEOUT:
                raise RuntimeError("no image after the move")
            yield 0.005
        seconds = vp.last_edit_to_image_seconds
        times.append(seconds)
        kind = counts["last"] if counts else "full (no incremental updates)"
        print(f"benchmark: {SCENE} move {k + 1}: view_update to first image {seconds:.3f} s "
              f"({kind} sync)", flush=True)
        yield from wait_converged()
    print(f"benchmark: {SCENE}: median view_update to first image over {MOVES} moves "
          f"{statistics.median(times):.3f} s (min {min(times):.3f}, max {max(times):.3f})",
          flush=True)


def run():
    gen = steps()

    def tick():
        try:
            return next(gen)
        except StopIteration:
            pass
        except Exception:  # noqa: BLE001 - printed, then Blender quits
            traceback.print_exc()
        bpy.ops.wm.quit_blender()
        return None

    bpy.app.timers.register(tick, first_interval=1.0)


run()
