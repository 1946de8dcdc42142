"""A small emissive UV sphere (Emission material, no lights) almost touching the back wall of two
diffuse planes (floor and wall), rendered with Photon and, optionally, with Cycles.

Args: OUT_DIR [ENGINES] [CYCLES_SAMPLES] [BLEND_PATH] [PHOTON_INTEGRATOR] [CYCLES_BOUNCES]
  ENGINES: comma-separated subset of photon,cycles (default both); BLEND_PATH "" saves nothing.
Writes emissive_near_wall_<engine>.exr to OUT_DIR and reports each image's mean RGB, the mean of
every pixel but the sphere's ("wall": floor and wall), and the means of two wall regions (near: the wall round the sphere; far: the wall well beside it).
The sphere's own pixels and a 2-pixel rim round them (where pixel filters differ: Photon's box,
Cycles' Blackman-Harris) are left out of the regions.
"""

import os

import bpy

import builders
import harness

WIDTH, HEIGHT = 64, 48
SPHERE_CENTER = (0.0, 0.84, 0.5)  # 0.04 m of air between the sphere (r = 0.12) and the wall
SPHERE_RADIUS = 0.12
# Regions in pixels (x0, y0, x1, y1), y down, at 64 x 48: the wall round the sphere and the wall
# well to its side.
NEAR = (20, 10, 44, 30)
FAR = (2, 4, 10, 14)


def build_scene(cycles_samples):
    scene = builders.reset_scene(width=WIDTH, height=HEIGHT)
    white = builders.diffuse_material("White", (0.8, 0.8, 0.8))
    builders.quad("Floor", (-3, -3, 0), (6, 0, 0), (0, 4, 0), white)
    builders.quad("Wall", (-3, 1, 0), (6, 0, 0), (0, 0, 3), white)
    glow = builders.shader_material("Glow", "ShaderNodeEmission", Color=(1.0, 0.9, 0.7, 1.0),
                                    Strength=10.0)
    builders.uv_sphere("Lamp", SPHERE_CENTER, SPHERE_RADIUS, segments=32, rings=16,
                       material=glow)
    cam = builders.camera(location=(0.0, -2.0, 0.9))
    builders.aim(cam, (0.0, 0.9, 0.45))
    cam.data.lens = 40.0
    scene.photon.samples = 64
    scene.photon.seed = 0
    scene.cycles.device = 'CPU'
    scene.cycles.samples = cycles_samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.seed = 1
    scene.cycles.max_bounces = 8
    return scene


def sphere_mask(pixels, rim=2):
    """The sphere's pixels (far brighter than any lit wall) grown by `rim` pixels."""
    mask = pixels[:, :, :3].max(axis=2) > 3.0
    for _ in range(rim):
        grown = mask.copy()
        grown[1:] |= mask[:-1]
        grown[:-1] |= mask[1:]
        grown[:, 1:] |= mask[:, :-1]
        grown[:, :-1] |= mask[:, 1:]
        mask = grown
    return mask


def region_mean(pixels, box, excluded):
    x0, y0, x1, y1 = box
    keep = ~excluded[y0:y1, x0:x1]
    return float(pixels[y0:y1, x0:x1, :3][keep].mean())


def render(scene, engine, out_dir):
    scene.render.engine = engine
    path = os.path.join(out_dir, f"emissive_near_wall_{engine.lower()}.exr")
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    return path, harness.read_image(path)


def main(out_dir, engines="photon,cycles", cycles_samples="256", blend_path="",
         photon_integrator="PHOTON_MAP", cycles_bounces="8"):
    os.makedirs(out_dir, exist_ok=True)
    scene = build_scene(int(cycles_samples))
    scene.cycles.max_bounces = int(cycles_bounces)
    scene.photon.integrator = photon_integrator
    if blend_path:
        bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    images = {engine: render(scene, engine.upper(), out_dir) for engine in engines.split(",")}
    # One mask for every image, so the regions hold the same pixels in each.
    excluded = None
    for _, pixels in images.values():
        mask = sphere_mask(pixels)
        excluded = mask if excluded is None else excluded | mask
    result = {}
    for engine, (path, pixels) in images.items():
        result[engine] = {"path": path,
                          "mean": [float(pixels[:, :, c].mean()) for c in range(3)],
                          "sphere_pixels": int(sphere_mask(pixels, rim=0).sum()),
                          "wall": float(pixels[:, :, :3][~excluded].mean()),
                          "near": region_mean(pixels, NEAR, excluded),
                          "far": region_mean(pixels, FAR, excluded)}
    return result


if __name__ == "__main__":
    harness.run(main)
