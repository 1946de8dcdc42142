#!/usr/bin/python3
"""Noise of an HDRI with a small, very bright sun: Photon's importance-sampled environment light
against Cycles' at the same sample count.

Writes a 1024 x 512 equirectangular HDRI (a blue sky gradient and a sun disc a few pixels wide
carrying most of the light), builds a scene lit only by it (a grey floor, a white diffuse sphere
and a rough gold sphere, seen through an Environment Texture node), renders a converged Cycles
reference (Clamp Indirect and Filter Glossy off: unbiased, as Photon is), then Cycles and Photon at the same sample count (64 by default), and prints each
image's relative RMSE against the reference and its render time.

    tests/bench/sun_hdri.py --addon-dir build/stage [--blender blender] [--samples 64]
        [--reference-samples 4096] [--keep DIR]
"""

import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

WIDTH, HEIGHT = 1024, 512
SUN_ELEVATION, SUN_AZIMUTH = math.radians(35.0), math.radians(60.0)
SUN_RADIUS_PIXELS = 2.5
SUN_RADIANCE = 4.0e4  # about 75% of the floor's irradiance comes from the sun

SCENE_SCRIPT = r'''
import math, sys, bpy
hdri, out = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.resolution_x, scene.render.resolution_y = 160, 90
scene.view_settings.view_transform = 'Standard'
scene.cycles.use_denoising = False
scene.cycles.pixel_filter_type = 'BOX'
scene.cycles.filter_width = 1.0
scene.cycles.max_bounces = 8
scene.cycles.sample_clamp_indirect = 0.0  # unbiased, like Photon: no clamp, no glossy blur
scene.cycles.blur_glossy = 0.0
world = bpy.data.worlds.new("sun")
world.use_nodes = True
env = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
env.image = bpy.data.images.load(hdri)
world.node_tree.links.new(env.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
scene.world = world
def principled(name, **inputs):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    for key, value in inputs.items():
        mat.node_tree.nodes["Principled BSDF"].inputs[key].default_value = value
    return mat
def add(obj, mat):
    obj.data.materials.append(mat)
    bpy.ops.object.shade_smooth()
bpy.ops.mesh.primitive_plane_add(size=40.0)
add(bpy.context.active_object, principled("floor", **{"Base Color": (0.5, 0.5, 0.5, 1), "Specular": 0.0, "Roughness": 1.0}))
bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(-1.2, 0.0, 1.0), segments=64, ring_count=32)
add(bpy.context.active_object, principled("white", **{"Base Color": (0.8, 0.8, 0.8, 1), "Specular": 0.0, "Roughness": 1.0}))
bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(1.2, 0.5, 1.0), segments=64, ring_count=32)
add(bpy.context.active_object, principled("gold", **{"Base Color": (1.0, 0.77, 0.34, 1), "Metallic": 1.0, "Roughness": 0.3}))
cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
cam.location = (0.0, -7.5, 3.0)
cam.rotation_euler = (math.radians(72.0), 0.0, 0.0)
scene.collection.objects.link(cam)
scene.camera = cam
bpy.ops.wm.save_as_mainfile(filepath=out)
'''


def write_hdri(path):
    """Sky: a vertical gradient (zenith blue, horizon white), black below the horizon; sun: a
    disc of SUN_RADIUS_PIXELS at SUN_ELEVATION / SUN_AZIMUTH."""
    v = (np.arange(HEIGHT) + 0.5) / HEIGHT
    u = (np.arange(WIDTH) + 0.5) / WIDTH
    elevation = (0.5 - v) * math.pi  # row 0 is the zenith
    t = np.clip(np.sin(elevation), 0.0, 1.0)[:, None, None]
    zenith, horizon = np.array([0.25, 0.45, 0.9]), np.array([0.9, 0.9, 0.95])
    image = np.where(t > 0.0, horizon + (zenith - horizon) * t, 0.02)
    image = np.broadcast_to(image, (HEIGHT, WIDTH, 3)).astype(np.float32).copy()
    # Blender's equirectangular mapping: u = atan2(dir.y, -dir.x) / 2 pi + 0.5.
    sun_u = math.atan2(math.sin(SUN_AZIMUTH), -math.cos(SUN_AZIMUTH)) / (2 * math.pi) + 0.5
    sun_v = 0.5 - SUN_ELEVATION / math.pi
    du = np.minimum(np.abs(u[None, :] - sun_u), 1.0 - np.abs(u[None, :] - sun_u)) * WIDTH
    dv = (v[:, None] - sun_v) * HEIGHT
    image[du ** 2 + dv ** 2 <= SUN_RADIUS_PIXELS ** 2] = SUN_RADIANCE
    out = oiio.ImageBuf(oiio.ImageSpec(WIDTH, HEIGHT, 3, oiio.FLOAT))
    out.set_pixels(oiio.ROI(), image)
    if not out.write(str(path)):
        raise RuntimeError(out.geterror())


def render(blender, addon_dir, blend, engine, samples, out, integrator=None):
    setup = (f"import bpy; s = bpy.context.scene; s.cycles.samples = {samples}; "
             f"s.photon.samples = {samples}")
    if integrator:
        setup += f"; s.photon.integrator = '{integrator}'"
    cmd = [blender, "-b", "--factory-startup", "--addons", "photon", str(blend), "-E", engine,
           "--python-expr", setup, "-o", f"{out}_####", "-F", "OPEN_EXR", "-x", "1", "-t", "0",
           "-f", "1"]
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    times = re.findall(r"Time: (\d+):(\d+\.\d+)", proc.stdout)
    seconds = int(times[-1][0]) * 60 + float(times[-1][1]) if times else time.perf_counter() - t0
    pixels = oiio.ImageBuf(f"{out}_0001.exr").get_pixels(oiio.FLOAT)[..., :3]
    return pixels, seconds


def rel_rmse(image, reference):
    return float(np.sqrt(np.mean((image - reference) ** 2)) / reference.mean())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--addon-dir", required=True, type=Path)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--samples", type=int, default=64)
    parser.add_argument("--reference-samples", type=int, default=4096)
    parser.add_argument("--keep", type=Path, help="keep the HDRI, scene and renders here")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = args.keep or Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        hdri, blend = folder / "sun.exr", folder / "sun_hdri.blend"
        write_hdri(hdri)
        subprocess.run([args.blender, "-b", "--factory-startup", "--python-expr", SCENE_SCRIPT,
                        "--", str(hdri), str(blend)], capture_output=True, check=True)
        reference, ref_time = render(args.blender, args.addon_dir, blend, "CYCLES",
                                     args.reference_samples, folder / "reference")
        print(f"reference: Cycles {args.reference_samples} spp, {ref_time:.1f} s, "
              f"mean {reference.mean():.4f}")
        runs = [("Cycles", "CYCLES", None), ("Photon ray trace", "PHOTON", "RAY_TRACE"),
                ("Photon photon map", "PHOTON", "PHOTON_MAP")]
        for label, engine, integrator in runs:
            image, seconds = render(args.blender, args.addon_dir, blend, engine, args.samples,
                                    folder / label.replace(" ", "_").lower(), integrator)
            print(f"{label:18s} {args.samples} spp {seconds:6.1f} s  rel RMSE "
                  f"{rel_rmse(image, reference):.4f}  mean {image.mean() / reference.mean() - 1:+.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
