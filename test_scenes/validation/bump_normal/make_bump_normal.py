"""A bumped sphere (Noise Texture -> Bump, Distance 0.1 -> Principled Normal) and a
normal-mapped sphere (Image Texture of a tangent-space normal map -> Normal Map -> Principled
Normal) on a grey floor under a square area light: scene bump_normal.

The normal map bump_normal/normal_map.png is generated here with numpy: the analytic normals of
the height field h(u, v) = A sin(2 pi 12 u) sin(2 pi 6 v) over the sphere's UV map (u around,
v up), encoded as Blender expects, (n + 1) / 2 with +X along the tangent (dP/du), +Y along the
bitangent and +Z along the surface normal, 8-bit, read as Non-Color.

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \\
        -P test_scenes/validation/bump_normal/make_bump_normal.py
"""

import math
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import artist_kit as kit  # noqa: E402
import builders  # noqa: E402
import library  # noqa: E402

REFERENCE_SAMPLES = 1024
MAP_SIZE = 256
BUMPS_U, BUMPS_V = 12, 6   # periods of the height field along u and v
SLOPE = 0.6                # height amplitude x 2 pi x period, in UV units -> tangent slopes


def write_normal_map(path, size=MAP_SIZE):
    """Writes the tangent-space normal map of the bump field; returns the path."""
    v, u = (np.mgrid[0:size, 0:size] + 0.5) / size   # row 0 is v near 0 (Blender: bottom row)
    dh_du = SLOPE * np.cos(2 * math.pi * BUMPS_U * u) * np.sin(2 * math.pi * BUMPS_V * v)
    dh_dv = SLOPE * np.sin(2 * math.pi * BUMPS_U * u) * np.cos(2 * math.pi * BUMPS_V * v)
    normal = np.stack([-dh_du, -dh_dv, np.ones_like(u)], axis=-1)
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    pixels = np.ones((size, size, 4), dtype=np.float32)
    pixels[..., :3] = np.round((normal * 0.5 + 0.5) * 255.0) / 255.0
    image = bpy.data.images.new("normal_map_tmp", size, size, alpha=False)
    image.colorspace_settings.name = 'Non-Color'
    image.pixels.foreach_set(pixels.ravel())
    image.filepath_raw = path
    image.file_format = 'PNG'
    image.save()
    bpy.data.images.remove(image)
    return path


def bumped_material():
    mat, nodes, links, bsdf = kit.principled("Bumped", **{"Base Color": (0.75, 0.3, 0.15, 1.0),
                                                           "Roughness": 0.35})
    coords = nodes.new("ShaderNodeTexCoord")
    noise = nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 6.0
    noise.inputs["Detail"].default_value = 3.0
    noise.inputs["Roughness"].default_value = 0.5
    bump = nodes.new("ShaderNodeBump")
    bump.inputs["Distance"].default_value = 0.1
    bump.inputs["Strength"].default_value = 1.0
    links.new(coords.outputs["Object"], noise.inputs["Vector"])
    links.new(noise.outputs["Fac"], bump.inputs["Height"])
    links.new(bump.outputs["Normal"], bsdf.inputs["Normal"])
    return mat


def normal_mapped_material(image_path):
    mat, nodes, links, bsdf = kit.principled("NormalMapped", **{
        "Base Color": (0.2, 0.45, 0.75, 1.0), "Roughness": 0.35})
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(image_path)
    texture.image.colorspace_settings.name = 'Non-Color'
    normal_map = nodes.new("ShaderNodeNormalMap")
    normal_map.space = 'TANGENT'
    normal_map.uv_map = "UVMap"
    normal_map.inputs["Strength"].default_value = 1.0
    links.new(texture.outputs["Color"], normal_map.inputs["Color"])
    links.new(normal_map.outputs["Normal"], bsdf.inputs["Normal"])
    return mat


def build():
    scene = kit.base_scene(samples=64)
    # The floor's contact shadows are lit only indirectly; photon-map blur there is the one
    # difference left against Cycles (about +3% on the tiles holding them at 50k photons).
    scene.photon.photons, scene.photon.final_gather_rays = 400000, 8
    grey, *_ = kit.principled("Floor", **{"Base Color": (0.5, 0.5, 0.5, 1.0), "Roughness": 0.8})
    kit.floor(grey, size=12.0)
    kit.uv_sphere("BumpedSphere", (-0.62, 0.0, 0.55), 0.55, bumped_material())
    image = write_normal_map(os.path.join(HERE, "normal_map.png"))
    sphere = kit.uv_sphere("NormalMappedSphere", (0.62, 0.0, 0.55), 0.55,
                           normal_mapped_material(image))
    sphere.rotation_euler = kit.radians(0, 0, 30)
    lamp = builders.light("Key", 'AREA', 250.0, (1.0, -1.6, 2.4), shape='SQUARE', size=0.8)
    builders.aim(lamp, (0.0, 0.0, 0.4))
    kit.camera_at((0.0, -4.0, 1.6), (0.0, 0.0, 0.5), lens=45.0)
    library.cycles_reference(scene, samples=REFERENCE_SAMPLES, max_bounces=8, caustics=False)
    return scene


scene = build()
kit.save(scene, "bump_normal", kit.sidecar(
    scene, REFERENCE_SAMPLES,
    f"Bump and normal mapping against Cycles ({REFERENCE_SAMPLES} spp, 8 bounces) under a square "
    f"area light: left, Noise (Object coordinates, scale 6) -> Bump (Distance 0.1) -> Principled "
    f"Normal; right, a generated tangent-space normal map (bump_normal/normal_map.png, Non-Color) "
    f"-> Normal Map (Tangent, UVMap) -> Principled Normal. Image mean within 2%, each 4x4 tile "
    f"within 5% (tests/blender/test_validation_artist_scenes.py)."))
