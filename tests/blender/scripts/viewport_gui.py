"""Drives Photon's Rendered viewport shading in Blender's GUI (under Xvfb), from timers:

  xvfb-run blender --factory-startup --addons photon SCENE.blend --python viewport_gui.py -- \
      RESULT.json OUT_DIR

Looks through the scene camera in Rendered shading until the viewport converges, screenshots
the 3D viewport, moves the TallBox, waits for the new image, screenshots again, then
screenshots Material Preview shading. Writes the screenshots' paths, the camera frame's pixel
rectangle in them, and the seconds from the edit to the first new image into RESULT.json.
"""

import json
import sys
import time
import traceback
from pathlib import Path

import bpy
from bpy_extras import view3d_utils

ARGS = sys.argv[sys.argv.index("--") + 1:]
RESULT = Path(ARGS[0])
OUT = Path(ARGS[1])
TIMEOUT = 120.0
result = {}


def viewport():
    window = bpy.context.window_manager.windows[0]
    for area in window.screen.areas:
        if area.type == 'VIEW_3D':
            region = next(r for r in area.regions if r.type == 'WINDOW')
            return window, area, region
    raise RuntimeError("no 3D viewport")


def screenshot(name):
    window, area, region = viewport()
    path = OUT / f"{name}.png"
    with bpy.context.temp_override(window=window, screen=window.screen, area=area,
                                   region=region):
        bpy.ops.screen.screenshot_area(filepath=str(path))
    return str(path)


def camera_frame():
    """(x0, y0, x1, y1) of the camera frame in the viewport screenshot, y downwards."""
    scene = bpy.context.scene
    _, area, region = viewport()
    rv3d = area.spaces[0].region_3d
    cam = scene.camera
    points = [view3d_utils.location_3d_to_region_2d(region, rv3d, cam.matrix_world @ v)
              for v in cam.data.view_frame(scene=scene)]
    xs, ys = [p.x for p in points], [p.y for p in points]
    return [min(xs), region.height - max(ys), max(xs), region.height - min(ys)]


def photon_viewport():
    import photon.viewport
    return photon.viewport


def steps():
    """A generator of timer steps: yields seconds to wait before the next one."""
    scene = bpy.context.scene
    scene.render.engine = 'PHOTON'
    # Few photons and samples: the test machine's cores are shared.
    scene.photon.preview_samples = 8
    scene.photon.samples = 16
    scene.photon.photons = 50000
    scene.photon.caustic_photons = 20000
    scene.view_settings.view_transform = 'Standard'
    _, area, region = viewport()
    space = area.spaces[0]
    space.overlay.show_overlays = False
    space.shading.type = 'RENDERED'
    space.region_3d.view_perspective = 'CAMERA'
    window, area, region = viewport()
    with bpy.context.temp_override(window=window, screen=window.screen, area=area,
                                   region=region):
        bpy.ops.view3d.view_center_camera()  # the camera frame fills the viewport
    vp = photon_viewport()
    yield 0.5

    def wait_converged():
        t0 = time.time()
        while not (vp.last_draw.get("converged") and vp.last_draw.get("current")):
            if time.time() - t0 > TIMEOUT:
                raise RuntimeError(f"viewport did not converge: {vp.last_draw}")
            yield 0.1
        yield 0.3  # the converged pass is drawn

    yield from wait_converged()
    result["frame"] = camera_frame()
    result["rendered"] = screenshot("rendered")
    result["first_draw"] = dict(vp.last_draw)

    # An edit: the viewport must re-sync the box only and show it moved.
    vp.last_edit_to_image_seconds = None
    box = scene.objects["TallBox"]
    box.location.x += 0.35
    box.location.y -= 0.2
    vp.last_draw.clear()  # wait for a draw after the change
    t0 = time.time()
    while vp.last_edit_to_image_seconds is None:
        if time.time() - t0 > TIMEOUT:
            raise RuntimeError("no image after the edit")
        yield 0.01
    result["edit_to_first_image_seconds"] = vp.last_edit_to_image_seconds
    yield from wait_converged()
    result["moved"] = screenshot("moved")

    # Another integrator: a new session (no quick pass for ray tracing) whose converged image
    # replaces the photon-mapped one; ray tracing has no indirect light, so it is darker.
    scene.photon.integrator = 'RAY_TRACE'
    vp.last_draw.clear()  # wait for a draw after the change
    yield 0.3
    yield from wait_converged()
    result["ray_trace"] = screenshot("ray_trace")
    scene.photon.integrator = 'PHOTON_MAP'

    # A view change alone (orbit) restarts the session's accumulation, never a sync.
    vp.last_edit_to_image_seconds = None
    space.region_3d.view_perspective = 'PERSP'
    space.region_3d.view_location = (0.0, 0.0, 1.0)  # the box's centre, seen from 6 m
    space.region_3d.view_distance = 6.0
    vp.last_draw.clear()  # wait for a draw after the change
    area.tag_redraw()  # as navigating the view does
    space.region_3d.view_rotation.rotate(__import__("mathutils").Euler((0.0, 0.0, 0.3)))
    yield from wait_converged()
    result["orbit_resynced"] = vp.last_edit_to_image_seconds is not None
    result["orbit"] = screenshot("orbit")

    # An orthographic user view (Blender clips it from -far/2 to far/2 around the view point).
    space.region_3d.view_perspective = 'ORTHO'
    vp.last_draw.clear()  # wait for a draw after the change
    area.tag_redraw()  # as navigating the view does
    yield from wait_converged()
    result["ortho"] = screenshot("ortho")

    # A material thumbnail (Material Properties > Preview) rendered by Photon.
    import photon.preview
    done = photon.preview.previews_rendered
    box = scene.objects["TallBox"]
    bpy.context.view_layer.objects.active = box
    box.select_set(True)
    material = box.active_material
    yield 0.5  # the Properties editor offers the object's tabs once it redrew
    window = bpy.context.window_manager.windows[0]
    for props in (a for a in window.screen.areas if a.type == 'PROPERTIES'):
        props.spaces[0].context = 'MATERIAL'  # its Preview panel and slot icons render
        props.tag_redraw()
    t0 = time.time()
    while photon.preview.previews_rendered == done:
        if time.time() - t0 > TIMEOUT:
            raise RuntimeError("no preview thumbnail rendered")
        yield 0.1
    yield 0.5
    preview = material.preview
    pixels = list(preview.icon_pixels_float) + list(preview.image_pixels_float)
    result["preview_size"] = list(preview.icon_size)
    result["preview_mean"] = sum(pixels) / max(len(pixels), 1)

    space.shading.type = 'MATERIAL'
    yield 4.0  # EEVEE compiles its shaders
    result["material_preview"] = screenshot("material_preview")

    # The final render (F12) of the edited scene, for the brightness comparison.
    scene.render.filepath = str(OUT / "final.png")
    scene.render.image_settings.file_format = 'PNG'
    bpy.ops.render.render(write_still=True)
    result["final"] = str(OUT / "final.png")


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
