"""An unbalanced radiosity scene: a finely tessellated UV sphere (about 200k triangles, radius
1 m) over a 20 m floor of one quad (2 triangles), lit by a sun 40 degrees off vertical, rendered
with the RADIOSITY integrator and its automatic patch size.

Args: OUT_DIR [RAYS_THOUSANDS] [SEGMENTS]
Reports the floor's mean in the sphere's shadow and in the sun beside it (pixels at projected
world points), and the sphere's pixel-to-neighbour noise (mean absolute second difference of
horizontally and vertically adjacent pixels inside the sphere's disc, over the disc's mean; a
smooth gradient gives none).
"""

import math
import os

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

import builders
import harness

WIDTH, HEIGHT = 320, 240
SPHERE_CENTER = Vector((0.0, 0.0, 1.2))
SPHERE_RADIUS = 1.0
SUN_TILT = math.radians(40.0)  # about +Y: the light travels towards -X and down


def build_scene(rays_thousands, segments):
    scene = builders.reset_scene(width=WIDTH, height=HEIGHT)
    white = builders.diffuse_material("White", (0.8, 0.8, 0.8))
    builders.quad("Floor", (-10, -10, 0), (20, 0, 0), (0, 20, 0), white)
    builders.uv_sphere("Ball", tuple(SPHERE_CENTER), SPHERE_RADIUS, segments=segments,
                       rings=segments // 2, material=white)
    builders.light("Sun", 'SUN', 3.0, (0, 0, 5), rotation=(0.0, SUN_TILT, 0.0))
    cam = builders.camera(location=(0.0, -9.0, 6.0))
    builders.aim(cam, (0.0, 0.0, 0.5))
    cam.data.lens = 35.0
    scene.photon.integrator = 'RADIOSITY'
    scene.photon.radiosity_patch_size = 0.0  # automatic
    scene.photon.radiosity_rays = rays_thousands
    scene.photon.samples = 1
    scene.photon.seed = 0
    return scene


def pixel_of(scene, point):
    """(column, row) of a world point, row 0 at the top."""
    co = world_to_camera_view(scene, scene.camera, Vector(point))
    return co.x * WIDTH, (1.0 - co.y) * HEIGHT


def floor_mean(scene, pixels, center, half=0.3, steps=7):
    """Mean of the pixels at a grid of floor points round `center` (+-half metres)."""
    values = []
    for i in range(steps):
        for j in range(steps):
            x = center[0] - half + 2 * half * i / (steps - 1)
            y = center[1] - half + 2 * half * j / (steps - 1)
            col, row = pixel_of(scene, (x, y, 0.0))
            values.append(float(pixels[int(row), int(col), :3].mean()))
    return sum(values) / len(values)


def sphere_noise(scene, pixels):
    import numpy as np
    col, row = pixel_of(scene, SPHERE_CENTER)
    cam_right = scene.camera.matrix_world.to_3x3() @ Vector((1.0, 0.0, 0.0))
    edge_col, _ = pixel_of(scene, SPHERE_CENTER + cam_right * SPHERE_RADIUS)
    radius = abs(edge_col - col) * 0.7  # inside the silhouette
    rows, cols = np.mgrid[0:HEIGHT, 0:WIDTH]
    disc = (cols + 0.5 - col) ** 2 + (rows + 0.5 - row) ** 2 < radius ** 2
    lum = pixels[:, :, :3].mean(axis=2)
    # Second differences along rows and columns: zero for smooth (linear) shading, so the
    # sphere's light gradient does not count, only the pixel-to-neighbour jitter.
    inner = disc[1:-1, 1:-1] & disc[1:-1, :-2] & disc[1:-1, 2:] & disc[:-2, 1:-1] & disc[2:, 1:-1]
    second_h = np.abs(lum[1:-1, :-2] - 2 * lum[1:-1, 1:-1] + lum[1:-1, 2:])[inner]
    second_v = np.abs(lum[:-2, 1:-1] - 2 * lum[1:-1, 1:-1] + lum[2:, 1:-1])[inner]
    first_h = np.abs(lum[1:-1, 1:-1] - lum[1:-1, 2:])[inner]
    mean = float(lum[disc].mean())
    return {"disc_pixels": int(disc.sum()), "disc_mean": mean,
            "noise": float(0.5 * (second_h.mean() + second_v.mean())) / max(mean, 1e-9),
            "first_difference": float(first_h.mean()) / max(mean, 1e-9)}


def main(out_dir, rays_thousands="2000", segments="448"):
    os.makedirs(out_dir, exist_ok=True)
    scene = build_scene(int(rays_thousands), int(segments))
    path = os.path.join(out_dir, "radiosity_adaptive.exr")
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    pixels = harness.read_image(path)
    # The shadow's centre: the sphere's centre projected along the sun onto the floor.
    direction = Vector((-math.sin(SUN_TILT), 0.0, -math.cos(SUN_TILT)))
    shadow = SPHERE_CENTER + direction * (SPHERE_CENTER.z / math.cos(SUN_TILT))
    result = {"path": path,
              "triangles": sum(len(p.vertices) - 2 for p in bpy.data.objects["Ball"].data.polygons),
              # Beyond the sphere's silhouette in the image (checked by the projection above).
              "shadow": floor_mean(scene, pixels, (shadow.x - 0.6, shadow.y)),
              "lit": floor_mean(scene, pixels, (3.0, 0.0))}
    result.update(sphere_noise(scene, pixels))
    return result


if __name__ == "__main__":
    harness.run(main)
