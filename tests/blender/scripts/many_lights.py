"""A room (floor, three walls, ceiling, two boxes) lit by N small coloured point lights in a grid
under the ceiling, some of them spots. Used by test_many_lights_lights.py and, through
build_room(), by tests/bench/many_lights.py.

Args: OUT_DIR N_LIGHTS GROUP SAMPLES [INTEGRATOR]
Renders the room with all N lights at once (Photon picks among them with its light tree when
there are more than 8), then again in groups of at most GROUP lights (Photon samples every light
when there are at most 8), and reports the means of both images and the relative RMSE of
their 8 x 8-pixel block means: light adds up, so the sum of the group renders is the image the
every-light estimator gives for the whole room.
"""

import colorsys
import math
import os

import bpy
import numpy as np

import builders
import harness

WIDTH, HEIGHT = 64, 48


def build_room(n_lights, width=WIDTH, height=HEIGHT, samples=64, total_power=300.0, seed=1):
    """The room with n_lights lights of total power `total_power` W; returns (scene, lights)."""
    scene = builders.reset_scene(width=width, height=height)
    white = builders.diffuse_material("White", (0.7, 0.7, 0.7))
    red = builders.diffuse_material("Red", (0.7, 0.15, 0.1))
    builders.quad("Floor", (-3, -3, 0), (6, 0, 0), (0, 6, 0), white)
    builders.quad("Ceiling", (-3, -3, 2.5), (0, 6, 0), (6, 0, 0), white)
    builders.quad("Back", (-3, 3, 0), (6, 0, 0), (0, 0, 2.5), white)
    builders.quad("Left", (-3, -3, 0), (0, 0, 2.5), (0, 6, 0), red)
    builders.quad("Right", (3, -3, 0), (0, 6, 0), (0, 0, 2.5), white)
    builders.box("BoxA", (-1.6, 0.2, 0.0), (-0.6, 1.2, 1.0), white)
    builders.box("BoxB", (0.5, -0.5, 0.0), (1.3, 0.3, 0.6), white)
    cols = max(1, int(math.ceil(math.sqrt(n_lights * 1.5))))
    rows = max(1, int(math.ceil(n_lights / cols)))
    lights = []
    rng = np.random.default_rng(seed)
    for i in range(n_lights):
        r, c = divmod(i, cols)
        x = -2.7 + 5.4 * (c + 0.5) / cols
        y = -2.7 + 5.4 * (r + 0.5) / rows
        z = 2.2 - 0.3 * rng.random()
        hue = rng.random()
        spot = i % 5 == 4
        light = builders.light(f"Lamp{i:04d}", 'SPOT' if spot else 'POINT',
                               total_power / n_lights * (0.5 + rng.random()), (x, y, z),
                               shadow_soft_size=0.03,
                               color=colorsys.hsv_to_rgb(hue, 0.6, 1.0))
        if spot:
            light.data.spot_size = 1.2
        lights.append(light)
    cam = builders.camera(location=(0.0, -2.9, 1.3))
    builders.aim(cam, (0.0, 1.0, 0.9))
    cam.data.lens = 20.0
    scene.photon.samples = samples
    scene.photon.seed = 0
    scene.cycles.device = 'CPU'
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0  # direct light only, like Photon's RAY_TRACE on diffuse walls
    scene.cycles.seed = 1
    return scene, lights


def render(scene, path):
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    return harness.read_image(path)[:, :, :3].astype(np.float64)


def block_means(pixels, size=8):
    h, w = pixels.shape[0] // size * size, pixels.shape[1] // size * size
    p = pixels[:h, :w]
    return p.reshape(h // size, size, w // size, size, 3).mean(axis=(1, 3))


def main(out_dir, n_lights="40", group="8", samples="64", integrator="RAY_TRACE"):
    os.makedirs(out_dir, exist_ok=True)
    n_lights, group = int(n_lights), int(group)
    scene, lights = build_room(n_lights, samples=int(samples))
    scene.photon.integrator = integrator
    whole = render(scene, os.path.join(out_dir, "many_lights_all.exr"))
    summed = np.zeros_like(whole)
    for start in range(0, n_lights, group):
        for i, light in enumerate(lights):
            light.hide_render = not (start <= i < start + group)
        summed += render(scene, os.path.join(out_dir, f"many_lights_group{start:04d}.exr"))
    a, b = block_means(whole), block_means(summed)
    return {"mean_tree": [float(whole[..., c].mean()) for c in range(3)],
            "mean_every": [float(summed[..., c].mean()) for c in range(3)],
            "block_rel_rmse": float(np.sqrt(np.mean((a - b) ** 2)) / b.mean()),
            "renders": 1 + (n_lights + group - 1) // group}


if __name__ == "__main__":
    harness.run(main)
