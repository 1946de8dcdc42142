"""A small scene (floor, red back wall, a box, a smooth ball, a Curves hair tuft in a red
emission material, a sun and a point light with a radius) built `offset` metres from the origin
along x and y, with the camera 6.7 m from it, rendered with PHOTON_MAP.

Arguments: out_dir tag offset [mode: "render" (default) or "bake"]. Every object's location is
`offset` plus whole metres (geometry lives in the meshes), so at 1e7, where a float32 step is 1 m, Blender's own 32-bit matrices hold
the scene exactly and only the renderer's precision is tested. Reports the image's mean and the
path of the EXR; in "bake" mode it bakes the lighting into colour attributes and 32 x 32
lightmaps instead and saves them (per object, in name order) to an .npz file.
"""

import math
import os

import bpy
import numpy as np

import builders
import harness

RES = 64


def build(offset):
    scene = builders.reset_scene(width=RES, height=RES)
    white = builders.diffuse_material("White", (0.8, 0.8, 0.8))
    red = builders.diffuse_material("Red", (0.8, 0.1, 0.1))
    at = lambda x, y, z: (offset + x, offset + y, float(z))  # noqa: E731
    for obj in (builders.quad("Floor", (-3, -3, 0), (6, 0, 0), (0, 6, 0), white),
                builders.quad("Back", (-3, 1.5, 0), (6, 0, 0), (0, 0, 3), red),
                builders.box("Box", (-0.5, -0.5, 0.0), (0.5, 0.5, 1.0), white)):
        obj.location = at(0, 0, 0)
    builders.uv_sphere("Ball", at(1, 0, 0), 0.45, material=white).location.z = 0.45
    bpy.ops.object.curves_random_add(location=at(-1, -1, 0))
    tuft = bpy.context.active_object
    tuft.scale = (0.15, 0.15, 0.15)  # the operator's strands span about 4 m
    tuft.data.materials.append(builders.shader_material(
        "HairRed", "ShaderNodeEmission", Color=(1.0, 0.1, 0.1, 1.0), Strength=2.0))
    sun = builders.light("Sun", 'SUN', 2.0, at(0, 0, 0),
                         rotation=(math.radians(40), 0.0, math.radians(30)))
    sun.data.angle = math.radians(2.0)
    lamp = builders.light("Lamp", 'POINT', 300.0, at(-2, -1, 3))
    lamp.data.shadow_soft_size = 0.25
    builders.camera(location=at(0, -6, 3), rotation=(math.radians(70), 0.0, 0.0), lens=35.0)
    scene.camera.data.clip_start = 0.01
    scene.camera.data.clip_end = 100.0
    scene.photon.integrator = 'PHOTON_MAP'
    scene.photon.samples = 16
    scene.photon.photons = 20000
    scene.photon.caustic_photons = 0
    scene.photon.seed = 0
    scene.photon.threads = 2
    return scene


def bake(scene, out_dir, tag):
    scene.photon.bake_source = 'PHOTON_MAP'
    scene.photon.bake_target = 'BOTH'
    scene.photon.bake_samples = 8
    scene.photon.lightmap_size = 32
    assert bpy.ops.photon.bake_lighting() == {'FINISHED'}
    arrays = {}
    for obj in sorted((o for o in scene.objects if o.type == 'MESH'), key=lambda o: o.name):
        attribute = obj.data.color_attributes["PhotonLighting"]
        values = np.empty(len(attribute.data) * 4, np.float32)
        attribute.data.foreach_get("color", values)
        arrays[f"{obj.name}_corners"] = values
        image = bpy.data.images[obj["photon_lightmap"]]
        pixels = np.empty(len(image.pixels), np.float32)
        image.pixels.foreach_get(pixels)
        arrays[f"{obj.name}_lightmap"] = pixels
    path = os.path.join(out_dir, f"far_from_origin_bake_{tag}.npz")
    np.savez(path, **arrays)
    return {"path": path, "finite": all(bool(np.isfinite(a).all()) for a in arrays.values())}


def main(out_dir, tag, offset, mode="render"):
    os.makedirs(out_dir, exist_ok=True)
    scene = build(float(offset))
    if mode == "bake":
        return bake(scene, out_dir, tag)
    path = os.path.join(out_dir, f"far_from_origin_{tag}.exr")
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    rgb = harness.read_image(path)[:, :, :3]
    return {"path": path, "mean": float(rgb.mean()), "finite": bool((rgb == rgb).all())}


harness.run(main)
