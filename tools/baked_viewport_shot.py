"""Screenshot of the baked lighting in Blender's viewport (run under Xvfb with the GUI):

  BLENDER_USER_SCRIPTS=build/stage PYTHONPATH=test_scenes xvfb-run -a -s "-screen 0 1280x800x24" \
      blender --factory-startup --addons photon test_scenes/cornell_box.blend \
      -P tools/baked_viewport_shot.py -- OUT.png [LIGHTMAP]

(Opening a .blend keeps the splash screen away; the scene is rebuilt anyway.)

Builds the Cornell box (surfaces subdivided so the per-corner colours have detail), bakes it
from the photon maps, switches the viewports to the baked colours, looks through the camera and
saves a screenshot.
"""

import sys

import bmesh
import bpy

import builders

ARGS = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
OUT = ARGS[0] if ARGS else "/tmp/baked_viewport.png"
MODE = ARGS[1] if len(ARGS) > 1 else "ATTRIBUTE"


def setup():
    scene = builders.cornell_box(width=256, height=256)
    scene.photon.photons = 200000
    scene.photon.bake_samples = 16
    scene.photon.bake_target = 'BOTH' if MODE == "LIGHTMAP" else 'COLOR_ATTRIBUTE'
    for obj in [o for o in scene.objects if o.type == 'MESH']:
        bm = bmesh.new()
        bm.from_mesh(obj.data)
        bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=16, use_grid_fill=True)
        bm.to_mesh(obj.data)
        bm.free()
        if MODE == "LIGHTMAP":  # one material per object, so each shows its own lightmap
            obj.material_slots[0].material = obj.material_slots[0].material.copy()
    print("bake:", bpy.ops.photon.bake_lighting(), flush=True)
    print("show:", bpy.ops.photon.show_baked_lighting(mode=MODE), flush=True)
    for window in bpy.context.window_manager.windows:
        for area in list(window.screen.areas):
            if area.type == 'VIEW_3D':
                space = area.spaces.active
                space.region_3d.view_perspective = 'CAMERA'
                space.overlay.show_overlays = False
                region = next(r for r in area.regions if r.type == 'WINDOW')
                with bpy.context.temp_override(window=window, area=area, region=region):
                    bpy.ops.view3d.view_center_camera()
                    bpy.ops.screen.screen_full_area()
                break
    # Give the viewport a few redraws before the screenshot.
    bpy.app.timers.register(snap, first_interval=3.0)
    return None


def snap():
    bpy.ops.screen.screenshot(filepath=OUT)
    bpy.ops.wm.quit_blender()


bpy.app.timers.register(setup, first_interval=1.0)
