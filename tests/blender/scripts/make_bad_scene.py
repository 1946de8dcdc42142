"""Builds one kind of bad input and saves it as a .blend.  Args: CASE BLEND_PATH"""

import math

import bpy
import numpy as np

import builders
import harness


def nan_geometry():
    builders.cornell_box(width=64, height=64, samples=4)
    obj = builders.box("NaNBox", (-0.2, -0.2, 0.5), (0.2, 0.2, 0.9))
    co = np.empty(len(obj.data.vertices) * 3, dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    co[0] = math.nan
    co[4] = math.inf
    obj.data.vertices.foreach_set("co", co)
    # Degenerate faces: a zero-area triangle and a face whose corners coincide.
    builders.mesh_object("Degenerate", [(0, 0, 1), (0.5, 0, 1), (1, 0, 1), (0.3, 0.3, 1)],
                         [(0, 1, 2)])


def zero_area_light():
    builders.cornell_box(width=64, height=64, samples=4)
    builders.light("FlatLight", 'AREA', 100.0, (0, 0, 1.5), shape='RECTANGLE', size=0.0,
                   size_y=0.5)
    builders.light("DarkLight", 'POINT', 0.0, (0, 0, 1.0))


def empty_scene():
    scene = builders.reset_scene(width=64, height=64)
    builders.camera()
    scene.photon.samples = 4


def no_lights():
    scene = builders.cornell_box(width=64, height=64, samples=4)
    bpy.data.objects.remove(bpy.data.objects["CeilingLight"])
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.2, 0.3, 0.4, 1)


def unsupported_node():
    builders.cornell_box(width=64, height=64, samples=4)
    mat = builders.shader_material("ToonMat", "ShaderNodeBsdfToon",
                                   Color=(0.2, 0.4, 0.9, 1.0))
    builders.uv_sphere("ToonBall", (0.3, -0.3, 0.9), 0.25, material=mat)


def absurd_settings():
    scene = builders.cornell_box(width=64, height=64, samples=4)
    scene.photon.max_depth = 1000
    scene.photon.tile_size = 4096
    scene.photon.gather_count = 1000
    scene.photon.caustic_gather_count = 1000
    scene.photon.gather_radius = 1e6
    scene.photon.photon_time = 0.1
    cam = scene.camera.data
    cam.clip_start = 50.0          # past everything: only the world is visible
    cam.clip_end = 0.001


def nan_camera():
    builders.cornell_box(width=32, height=32, samples=1)
    bpy.context.scene.camera.location.x = math.nan


def zero_scale_camera():
    builders.cornell_box(width=32, height=32, samples=1)
    bpy.context.scene.camera.scale = (0.0, 0.0, 0.0)


CASES = {f.__name__: f for f in (nan_geometry, zero_area_light, empty_scene, no_lights,
                                 unsupported_node, absurd_settings, nan_camera,
                                 zero_scale_camera)}


def main(case, blend_path):
    CASES[case]()
    bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    return {"saved": blend_path}


harness.run(main)
