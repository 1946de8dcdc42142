"""Lighting bake on bad input: a scene without meshes, then a scene mixing a good plane with a
mesh without faces, a mesh with a NaN vertex and a mesh whose modifier changes its topology."""

import math

import bpy
import numpy as np

import builders
import harness

ATTRIBUTE = "PhotonLighting"


def attribute_info(obj):
    attribute = obj.data.color_attributes.get(ATTRIBUTE)
    return None if attribute is None else [attribute.domain, attribute.data_type]


def values(obj):
    attribute = obj.data.color_attributes[ATTRIBUTE]
    colors = np.empty(len(attribute.data) * 4, np.float32)
    attribute.data.foreach_get("color", colors)
    return colors.reshape(-1, 4)[:, :3]


def main():
    scene = builders.reset_scene()
    scene.photon.photons = 20000
    scene.photon.bake_samples = 4
    builders.light("Lamp", 'POINT', 200.0, (0, 0, 2))
    builders.camera()
    result = {"no_meshes": sorted(bpy.ops.photon.bake_lighting())}

    white = builders.diffuse_material("White", (0.8, 0.8, 0.8))
    good = builders.quad("Good", (-1, -1, 0), (2, 0, 0), (0, 2, 0), white)
    builders.mesh_object("NoFaces", [(0, 0, 1), (1, 0, 1)], [])
    builders.mesh_object("NaNVertex", [(2, 0, 0), (3, 0, 0), (3, 1, 0), (math.nan, 1, 0)],
                         [(0, 1, 2, 3)], white)
    cube = builders.box("Subdivided", (-3, -1, 0), (-2, 0, 1), white)
    cube.modifiers.new("Subdivision", 'SUBSURF')
    result["mixed"] = sorted(bpy.ops.photon.bake_lighting())
    objects = [good, bpy.data.objects["NoFaces"], bpy.data.objects["NaNVertex"], cube]
    result["attributes"] = {o.name: attribute_info(o) for o in objects}
    result["finite"] = {o.name: bool(np.isfinite(values(o)).all())
                        for o in objects if attribute_info(o)}
    result["good_max"] = float(values(good).max())

    scene.photon.bake_target = 'LIGHTMAP'
    scene.photon.lightmap_size = 32
    result["lightmap"] = sorted(bpy.ops.photon.bake_lighting())
    image = bpy.data.images.get(good.get("photon_lightmap", ""))
    if image is not None:
        pixels = np.empty(len(image.pixels), np.float32)
        image.pixels.foreach_get(pixels)
        rgb = pixels.reshape(-1, 4)[:, :3]
        result["lightmap_image"] = {"size": list(image.size), "packed": image.packed_file is not None,
                                    "covered_fraction": float((rgb.max(axis=1) > 0).mean())}
    return result


harness.run(main)
