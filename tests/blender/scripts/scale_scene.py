"""One small sun-lit scene (floor, red back wall, a box casting a shadow that only indirect light
fills) built at any scale and distance from the origin, rendered with PHOTON_MAP.

Arguments: out_dir tag scale offset [near_camera: 1 = camera 6.7 units away] [far_box: a
distance D; when not 0, a 1-unit box also stands at (-D, -D, 0), out of view, so the scene's own
extent is about 1.4 D]. Every length (geometry, camera position, clip range) is
multiplied by `scale`; every object is then moved by (offset, offset, 0). The sun is scale
invariant, so the image should not change with `scale`. Object locations are exactly `offset`
and the camera's coordinates are whole numbers at scale 1, so a 1e7 offset is exactly
representable in Blender's 32-bit matrices and only the renderer's precision is tested.
Reports the image's mean, its 8x8 block means and the path of the EXR.
"""

import math
import os

import bpy

import builders
import harness

RES = 64
BLOCKS = 8


def scaled_quad(name, corner, edge_u, edge_v, material, scale, offset):
    s = lambda v: tuple(scale * c for c in v)  # noqa: E731
    obj = builders.quad(name, s(corner), s(edge_u), s(edge_v), material)
    obj.location = (offset, offset, 0.0)
    return obj


def scaled_box(name, lo, hi, material, scale, offset):
    obj = builders.box(name, tuple(scale * c for c in lo), tuple(scale * c for c in hi), material)
    obj.location = (offset, offset, 0.0)
    return obj


def build(scale, offset, near_camera=False, far_box=0.0):
    scene = builders.reset_scene(width=RES, height=RES)
    white = builders.diffuse_material("White", (0.8, 0.8, 0.8))
    red = builders.diffuse_material("Red", (0.8, 0.1, 0.1))
    scaled_quad("Floor", (-3, -3, 0), (6, 0, 0), (0, 6, 0), white, scale, offset)
    scaled_quad("Back", (-3, 1.5, 0), (6, 0, 0), (0, 0, 3), red, scale, offset)
    scaled_box("Box", (-0.5, -0.5, 0.0), (0.5, 0.5, 1.0), white, scale, offset)
    if far_box:
        scaled_box("FarBox", (-0.5, -0.5, 0.0), (0.5, 0.5, 1.0), white, scale, -far_box)
    sun = builders.light("Sun", 'SUN', 3.0, (offset, offset, 0.0),
                         rotation=(math.radians(40), 0.0, math.radians(30)))
    sun.data.angle = math.radians(2.0)
    # Far away with a long lens: Blender clamps clip_start to at least 1e-6 m, which at scale
    # 1e-7 is 10 scene units, so the scene must lie farther than that from the camera.
    cam = builders.camera(location=(offset, offset - 18.0 * scale, 9.0 * scale),
                          rotation=(math.radians(65.5), 0.0, 0.0), lens=100.0)
    if near_camera:  # a usual framing: 6.7 units away, inside Blender's clip floor at 1e-7
        cam.location = (offset, offset - 6.0 * scale, 3.0 * scale)
        cam.rotation_euler = (math.radians(70), 0.0, 0.0)
        cam.data.lens = 35.0
    cam.data.clip_start = 0.01 * scale
    cam.data.clip_end = 100.0 * scale
    scene.photon.integrator = 'PHOTON_MAP'
    scene.photon.samples = 16
    scene.photon.photons = 20000
    scene.photon.caustic_photons = 0
    scene.photon.seed = 0
    scene.photon.threads = 2
    return scene


def main(out_dir, tag, scale, offset, near_camera="0", far_box="0"):
    os.makedirs(out_dir, exist_ok=True)
    scene = build(float(scale), float(offset), near_camera == "1", float(far_box))
    path = os.path.join(out_dir, f"scale_scene_{tag}.exr")
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    rgb = harness.read_image(path)[:, :, :3]
    step = RES // BLOCKS
    blocks = rgb.reshape(BLOCKS, step, BLOCKS, step, 3).mean(axis=(1, 3, 4))
    return {"path": path, "mean": float(rgb.mean()), "blocks": blocks.tolist(),
            "finite": bool((rgb == rgb).all())}


harness.run(main)
