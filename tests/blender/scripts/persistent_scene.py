"""A 3-frame animation for Persistent Data tests, saved as .blend: a Cornell box (static walls
and boxes) with a moving camera, a moving sphere (transform only) and a plane whose shape key
lifts a corner from frame 1 to frame 3 (geometry changes). Args: BLEND_PATH"""

import bpy

import builders
import harness


def main(blend_path):
    scene = builders.cornell_box(width=64, height=64, samples=4)
    scene.frame_start, scene.frame_end = 1, 3
    cam = scene.camera
    ball = builders.uv_sphere("Ball", (0.0, -0.3, 0.8), 0.2,
                              material=builders.diffuse_material("Ball", (0.2, 0.3, 0.9)))
    # A horizontal plane on the floor whose first corner rises to 0.9 m by frame 3.
    sheet = builders.quad("Sheet", (-0.8, -0.8, 0.05), (0.6, 0.0, 0.0), (0.0, 0.6, 0.0),
                          material=builders.diffuse_material("Sheet", (0.9, 0.2, 0.2)))
    sheet.shape_key_add(name="Basis")
    lift = sheet.shape_key_add(name="Lift")
    lift.data[0].co.z = 0.9
    lift.value = 0.0
    lift.keyframe_insert("value", frame=1)
    lift.value = 1.0
    lift.keyframe_insert("value", frame=3)
    for frame, (cam_x, z) in [(1, (-0.2, 0.3)), (2, (0.0, 0.8)), (3, (0.2, 1.3))]:
        cam.location.x = cam_x
        cam.keyframe_insert("location", frame=frame)
        ball.location.z = z
        ball.keyframe_insert("location", frame=frame)
    # Linear keys: a shape key halfway at frame 2, so every frame differs.
    for obj in (cam, ball):
        for fcurve in builders.action_fcurves(obj.animation_data):
            for key in fcurve.keyframe_points:
                key.interpolation = 'LINEAR'
    for fcurve in builders.action_fcurves(sheet.data.shape_keys.animation_data):
        for key in fcurve.keyframe_points:
            key.interpolation = 'LINEAR'
    scene.render.use_persistent_data = False
    bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    return {"saved": blend_path, "meshes": [o.name for o in scene.objects if o.type == 'MESH']}


harness.run(main)
