"""A sharp shadow edge under RADIOSITY: a 20 m floor (one quad) under a sun shining straight
down (angle 0), a 4 m square occluder 3 m above it, and a camera looking down at the shadow's
edge x = 2 from below the occluder. Automatic patch size.

Args: OUT_DIR [RAYS_THOUSANDS]
Reports the floor's brightness profile across the edge (mean over a band of y), its shadow and
lit levels, and the 10%-90% transition width in metres and in image pixels.
"""

import os

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

import builders
import harness

WIDTH, HEIGHT = 320, 240
EDGE_X = 2.0  # the occluder covers |x|, |y| < 2
X_RANGE = (1.0, 3.0)
Y_BAND = (-0.4, 0.4)


def build_scene(rays_thousands):
    scene = builders.reset_scene(width=WIDTH, height=HEIGHT)
    white = builders.diffuse_material("White", (0.8, 0.8, 0.8))
    builders.quad("Floor", (-10, -10, 0), (20, 0, 0), (0, 20, 0), white)
    builders.quad("Occluder", (-EDGE_X, -EDGE_X, 3.0), (2 * EDGE_X, 0, 0), (0, 2 * EDGE_X, 0),
                  white)
    builders.light("Sun", 'SUN', 3.0, (0, 0, 8), angle=0.0)
    cam = builders.camera(location=(EDGE_X, -0.3, 2.5))
    builders.aim(cam, (EDGE_X, 0.0, 0.0))
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


def crossing(xs, profile, level):
    """First x where the profile reaches `level`, linearly interpolated."""
    for k in range(1, len(xs)):
        if profile[k] >= level:
            a, b = profile[k - 1], profile[k]
            t = (level - a) / (b - a) if b != a else 0.0
            return xs[k - 1] + t * (xs[k] - xs[k - 1])
    return xs[-1]


def main(out_dir, rays_thousands="2000"):
    import numpy as np
    os.makedirs(out_dir, exist_ok=True)
    scene = build_scene(int(rays_thousands))
    path = os.path.join(out_dir, "radiosity_refine.exr")
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    pixels = harness.read_image(path)
    lum = pixels[:, :, :3].mean(axis=2)
    xs = list(np.linspace(X_RANGE[0], X_RANGE[1], 401))
    profile = []
    for x in xs:
        values = []
        for y in np.linspace(Y_BAND[0], Y_BAND[1], 9):
            col, row = pixel_of(scene, (x, y, 0.0))
            if 0 <= col < WIDTH and 0 <= row < HEIGHT:
                values.append(float(lum[int(row), int(col)]))
        profile.append(sum(values) / max(len(values), 1))
    shadow = float(np.mean([p for x, p in zip(xs, profile) if x < X_RANGE[0] + 0.25]))
    lit = float(np.mean([p for x, p in zip(xs, profile) if x > X_RANGE[1] - 0.25]))
    x10 = crossing(xs, profile, shadow + 0.1 * (lit - shadow))
    x90 = crossing(xs, profile, shadow + 0.9 * (lit - shadow))
    c0, _ = pixel_of(scene, (EDGE_X - 0.5, 0.0, 0.0))
    c1, _ = pixel_of(scene, (EDGE_X + 0.5, 0.0, 0.0))
    pixels_per_metre = abs(c1 - c0)
    return {"path": path, "shadow": shadow, "lit": lit, "x10": x10, "x90": x90,
            "width_m": x90 - x10, "width_px": (x90 - x10) * pixels_per_metre,
            "pixels_per_metre": pixels_per_metre,
            "profile": [round(p, 4) for p in profile[::20]]}


if __name__ == "__main__":
    harness.run(main)
