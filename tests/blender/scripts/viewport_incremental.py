"""Drives Photon's Rendered viewport through edits in Blender's GUI (under Xvfb), from timers:

  xvfb-run blender --factory-startup --addons photon cornell_box.blend \
      --python viewport_incremental.py -- RESULT.json OUT_DIR

Looks through the Cornell box's camera until the viewport converges, then: moves the TallBox
(which must take the transform-only path), screenshots the converged image; adds an Empty,
which changes the scene's objects and so syncs the whole scene again, screenshots that; hides
the ShortBox (an edit Blender reports only as a scene update) and moves the lamp (lights
always sync fully). Writes the screenshots, the sync kind after each edit and the sync counts
into RESULT.json.
"""

import json
import sys
import time
import traceback
from pathlib import Path

import bpy

ARGS = sys.argv[sys.argv.index("--") + 1:]
RESULT = Path(ARGS[0])
OUT = Path(ARGS[1])
TIMEOUT = 120.0
result = {}


def viewport():
    window = bpy.context.window_manager.windows[0]
    for area in window.screen.areas:
        if area.type == 'VIEW_3D':
            return window, area, next(r for r in area.regions if r.type == 'WINDOW')
    raise RuntimeError("no 3D viewport")


def screenshot(name):
    window, area, region = viewport()
    path = OUT / f"{name}.png"
    with bpy.context.temp_override(window=window, screen=window.screen, area=area,
                                   region=region):
        bpy.ops.screen.screenshot_area(filepath=str(path))
    return str(path)


def steps():
    scene = bpy.context.scene
    scene.render.engine = 'PHOTON'
    scene.photon.preview_samples = 8
    scene.photon.photons = 50000
    scene.photon.caustic_photons = 20000
    scene.view_settings.view_transform = 'Standard'
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
            yield 0.1
        yield 0.3  # the converged pass is drawn

    def edit(name, change):
        """Applies `change`, waits for the restarted session's image and its convergence."""
        before = dict(vp.sync_counts)
        vp.last_edit_to_image_seconds = None
        change()
        vp.last_draw.clear()
        t0 = time.time()
        while vp.last_edit_to_image_seconds is None:
            if time.time() - t0 > TIMEOUT:
                raise RuntimeError(f"no image after the edit '{name}'")
            yield 0.01
        result[f"{name}_seconds"] = vp.last_edit_to_image_seconds
        yield from wait_converged()
        result[f"{name}_sync"] = vp.sync_counts["last"]
        result[f"{name}_full_syncs"] = vp.sync_counts["full"] - before["full"]
        result[f"{name}_transform_syncs"] = vp.sync_counts["transform"] - before["transform"]
        result[f"{name}_material_syncs"] = vp.sync_counts["material"] - before["material"]
        result[name] = screenshot(name)

    yield from wait_converged()
    result["start"] = screenshot("start")
    box = scene.objects["TallBox"]

    def move():
        box.location.x += 0.3
        box.location.y -= 0.2
        box.rotation_euler.z += 0.3
    yield from edit("moved", move)

    def recolor():
        # The red wall's Diffuse BSDF colour, as an artist drags it.
        material = scene.objects["Left"].material_slots[0].material
        bsdf = next(n for n in material.node_tree.nodes if n.type == 'BSDF_DIFFUSE')
        bsdf.inputs["Color"].default_value = (0.1, 0.3, 0.9, 1.0)
    yield from edit("recolored", recolor)

    def add_empty():
        empty = bpy.data.objects.new("Marker", None)
        scene.collection.objects.link(empty)
    yield from edit("resynced", add_empty)

    yield from edit("hidden", lambda: scene.objects["ShortBox"].hide_set(True))

    def move_lamp():
        scene.objects["CeilingLight"].location.z -= 0.3
    yield from edit("lamp", move_lamp)


def run():
    gen = steps()

    def tick():
        try:
            return next(gen)
        except StopIteration:
            finish()
        except Exception:  # noqa: BLE001 - reported through the result file
            result["exception"] = traceback.format_exc()
            finish()
        return None

    bpy.app.timers.register(tick, first_interval=1.0)


def finish():
    RESULT.write_text(json.dumps(result))
    bpy.ops.wm.quit_blender()


run()
