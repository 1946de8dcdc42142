"""The scene of tests/bench/farm_benchmark.py, saved as .blend: the Cornell box with its two
boxes, a glass ball and a mirror ball (caustics), lit by the ceiling's area light, rendered
with Photon's default photon mapping (200,000 global and 100,000 caustic photons, 16 final
gather rays, irradiance cache) at 16 samples, OpenEXR output. The camera moves over 3 frames.

    blender -b --factory-startup --addons photon --python farm_bench_scene.py -- BLEND WIDTH HEIGHT
(with PYTHONPATH=test_scenes for the builders)
"""

import sys

import bpy

import builders

args = sys.argv[sys.argv.index("--") + 1:]
blend_path, width, height = args[0], int(args[1]), int(args[2])

scene = builders.cornell_box(width=width, height=height, samples=16)
glass = builders.glass_material()
for node in glass.node_tree.nodes:
    if node.bl_idname == "ShaderNodeBsdfGlass":
        node.distribution = 'SHARP'
builders.uv_sphere("GlassBall", (0.35, -0.45, 0.25), 0.25, segments=64, rings=32,
                   material=glass)
builders.uv_sphere("MirrorBall", (-0.55, -0.5, 0.3), 0.3, segments=64, rings=32,
                   material=builders.mirror_material())
photon = scene.photon
photon.integrator = 'PHOTON_MAP'
photon.photons = 200000
photon.caustic_photons = 100000
photon.final_gather_rays = 16
photon.irradiance_cache = True
photon.seed = 3
camera = scene.camera
for frame, x in ((1, -0.15), (2, 0.0), (3, 0.15)):
    camera.location.x = x
    camera.keyframe_insert("location", frame=frame)
scene.frame_start, scene.frame_end = 1, 3
scene.render.image_settings.file_format = 'OPEN_EXR'
scene.render.image_settings.color_depth = '16'
scene.render.filepath = "//render/bench_"
scene.render.use_compositing = False
bpy.ops.wm.save_as_mainfile(filepath=blend_path)
