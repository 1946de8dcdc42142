"""A tiny 3-frame animated Cornell box for the farm tests, saved as .blend with its output
settings: Blender's `-a` and the farm must agree on every pass of every frame.

    blender -b --factory-startup --addons photon --python make_farm_scene.py -- BLEND FORMAT

FORMAT is an image_settings.file_format (OPEN_EXR_MULTILAYER keeps the data and light passes).
"""

import sys

import bpy

import builders

args = sys.argv[sys.argv.index("--") + 1:]
blend_path, file_format = args[0], args[1]

scene = builders.cornell_box(width=48, height=40, samples=2)
scene.photon.photons = 20000
scene.photon.caustic_photons = 5000
scene.frame_start, scene.frame_end = 1, 3
ball = builders.uv_sphere("Ball", (0.0, -0.3, 0.8), 0.2,
                          material=builders.diffuse_material("Ball", (0.2, 0.3, 0.9)))
builders.keyframe_motion(scene.camera, ball, bpy.data.objects["CeilingLight"],
                         [(1, (-0.2, 0.3, 20)), (2, (0.0, 0.8, 40)), (3, (0.2, 1.3, 80))])
layer = scene.view_layers[0]
layer.use_pass_z = True
layer.use_pass_normal = True
layer.use_pass_diffuse_color = True
layer.photon.use_pass_direct = True
layer.photon.use_pass_indirect = True
scene.render.image_settings.file_format = file_format
if file_format.startswith("OPEN_EXR"):
    scene.render.image_settings.color_depth = "16"
scene.render.filepath = "//render/farm_"
scene.render.use_compositing = False
bpy.ops.wm.save_as_mainfile(filepath=blend_path)
