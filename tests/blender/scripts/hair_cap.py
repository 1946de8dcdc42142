"""Renders the open .blend with Photon's hair point budget lowered, so that a small hair system
exceeds it.  Args: RESULT_PATH MAX_POINTS IMAGE_PATH"""

import bpy

import harness


def main(max_points, image_path):
    from photon.sync import hair as sync_hair  # the enabled add-on's module, used by its render
    sync_hair.MAX_HAIR_POINTS = int(max_points)
    scene = bpy.context.scene
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.filepath = image_path
    result = bpy.ops.render.render(write_still=True)
    return {"render": sorted(result)}


harness.run(main)
