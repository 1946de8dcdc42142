"""Light must not leak through closed geometry: a closed cube (Blender's default cube mesh, 2 m,
its bottom 0.5 m above a 20 m floor plane) under a black world, rendered with Photon.

  sealed_light: a point light inside the cube, the camera outside. Nothing outside the cube can
    receive light, so the floor and the cube's outer faces must be black.
  sealed_camera: the camera inside the cube, a point light outside lighting the floor and the
    cube's top. Nothing the camera sees can receive light, so the image must be black.

Args: OUT_DIR CASE [SETTINGS_JSON]
  CASE: sealed_light or sealed_camera; SETTINGS_JSON overrides scene.photon settings (for
  measuring which estimate leaks, e.g. {"final_gather_rays": 0}).
Writes light_leak_<case>.exr to OUT_DIR and reports the image's mean and max (every pixel) and
the mean and max of the floor pixels (pixels whose centre ray hits the floor, found with
scene.ray_cast; for sealed_camera the floor is never seen and these are the interior's).
"""

import json
import os

import bmesh
import bpy
from mathutils import Vector

import builders
import harness

WIDTH, HEIGHT = 64, 48
CUBE_CENTER = (0.0, 0.0, 1.5)  # default 2 m cube, bottom face 0.5 m above the floor


def default_cube(material):
    mesh = bpy.data.meshes.new("Cube")
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=2.0)
    bm.to_mesh(mesh)
    bm.free()
    mesh.materials.append(material)
    obj = builders.link(bpy.data.objects.new("Cube", mesh))
    obj.location = CUBE_CENTER
    return obj


def build_scene(case):
    scene = builders.reset_scene(width=WIDTH, height=HEIGHT)
    white = builders.diffuse_material("White", (0.8, 0.8, 0.8))
    builders.quad("Floor", (-10, -10, 0), (20, 0, 0), (0, 20, 0), white)
    default_cube(white)
    if case == "sealed_light":
        builders.light("Lamp", 'POINT', 1000.0, CUBE_CENTER, shadow_soft_size=0.1)
        cam = builders.camera(location=(5.0, -6.0, 4.0), lens=30.0)
        builders.aim(cam, (0.0, 0.0, 0.8))
    elif case == "sealed_camera":
        builders.light("Lamp", 'POINT', 1000.0, (3.0, -3.0, 4.0), shadow_soft_size=0.1)
        # In a corner of the cube looking at the opposite bottom corner: floor and three walls.
        cam = builders.camera(location=(0.8, 0.8, 2.3), lens=12.0)
        builders.aim(cam, (-1.0, -1.0, 0.5))
    else:
        raise ValueError(f"unknown case {case}")
    scene.photon.integrator = "PHOTON_MAP"
    scene.photon.samples = 4
    scene.photon.seed = 0
    scene.photon.photons = 50000
    scene.photon.caustic_photons = 0
    return scene


def floor_mask(scene):
    """Pixels (row 0 at the top) whose centre ray from the camera hits the floor."""
    import numpy as np
    depsgraph = bpy.context.evaluated_depsgraph_get()
    cam = scene.camera
    frame = cam.data.view_frame(scene=scene)  # camera-space corners: tr, br, bl, tl
    top_right, bottom_left = frame[0], frame[2]
    origin = cam.matrix_world.translation
    mask = np.zeros((HEIGHT, WIDTH), dtype=bool)
    for row in range(HEIGHT):
        for col in range(WIDTH):
            u = (col + 0.5) / WIDTH
            v = (row + 0.5) / HEIGHT
            local = Vector((bottom_left.x + u * (top_right.x - bottom_left.x),
                            top_right.y - v * (top_right.y - bottom_left.y), top_right.z))
            direction = (cam.matrix_world.to_3x3() @ local).normalized()
            hit, _, _, _, obj, _ = scene.ray_cast(depsgraph, origin, direction)
            mask[row, col] = hit and obj.name == "Floor"
    return mask


def main(out_dir, case, settings_json="{}"):
    os.makedirs(out_dir, exist_ok=True)
    scene = build_scene(case)
    for key, value in json.loads(settings_json).items():
        setattr(scene.photon, key, value)
    path = os.path.join(out_dir, f"light_leak_{case}.exr")
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    pixels = harness.read_image(path)[:, :, :3]
    floor = floor_mask(scene)
    result = {"path": path, "mean": float(pixels.mean()), "max": float(pixels.max()),
              "floor_pixels": int(floor.sum())}
    if floor.any():
        result["floor_mean"] = float(pixels[floor].mean())
        result["floor_max"] = float(pixels[floor].max())
    return result


if __name__ == "__main__":
    harness.run(main)
