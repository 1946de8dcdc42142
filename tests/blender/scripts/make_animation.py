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
    for frame, (cam_x, ball_z, power) in zip((1, 2, 3), ((-0.2, 0.3, 20), (0.0, 0.8, 40),
                                                         (0.2, 1.3, 80))):
        cam.location.x = cam_x
        cam.keyframe_insert("location", frame=frame)
        ball.location.z = ball_z
        ball.keyframe_insert("location", frame=frame)
        light.data.energy = power
        light.data.keyframe_insert("energy", frame=frame)
    bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    return {"saved": blend_path}


harness.run(main)
