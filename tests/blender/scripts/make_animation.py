"""A 3-frame animation (moving camera, moving object, animated light power) saved as .blend.
Args: BLEND_PATH"""

import bpy

import builders
import harness


def main(blend_path):
    scene = builders.cornell_box(width=64, height=64, samples=4)
    scene.frame_start, scene.frame_end = 1, 3
    cam = scene.camera
    ball = builders.uv_sphere("Ball", (0.0, -0.3, 0.8), 0.2,
                              material=builders.diffuse_material("Ball", (0.2, 0.3, 0.9)))
    light = bpy.data.objects["CeilingLight"]
    builders.keyframe_motion(cam, ball, light, [(1, (-0.2, 0.3, 20)), (2, (0.0, 0.8, 40)),
                                                (3, (0.2, 1.3, 80))])
    bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    return {"saved": blend_path}


harness.run(main)
