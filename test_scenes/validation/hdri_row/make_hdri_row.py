"""A row of Principled spheres (metal, plastic, glass, rough dielectric, anisotropic metal, sheen)
on a grey floor, lit only by an HDRI: Blender's own studio light 'courtyard.exr' (shipped with
Blender, CC0; copied beside this script) through an Environment Texture rotated by a Mapping
node: scene hdri_row.

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \\
        -P test_scenes/validation/hdri_row/make_hdri_row.py
"""

import math
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import artist_kit as kit  # noqa: E402
import library  # noqa: E402

REFERENCE_SAMPLES = 1024


def hdri_world(scene):
    world = bpy.data.worlds.new("Courtyard")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes["Background"]
    background.inputs["Strength"].default_value = 1.2
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = bpy.data.images.load(os.path.join(HERE, "courtyard.exr"))
    mapping = nodes.new("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(75.0))
    coords = nodes.new("ShaderNodeTexCoord")
    links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    links.new(env.outputs["Color"], background.inputs["Color"])
    scene.world = world


def build():
    scene = kit.base_scene(width=192, height=96, samples=128)
    scene.photon.photons, scene.photon.final_gather_rays = 100000, 8
    hdri_world(scene)
    floor, *_ = kit.principled("Floor", **{"Base Color": (0.45, 0.45, 0.45, 1.0),
                                           "Roughness": 0.9, "Specular": 0.2})
    kit.floor(floor, size=30.0)
    spheres = [
        ("Metal", {"Base Color": (0.95, 0.75, 0.45, 1.0), "Metallic": 1.0, "Roughness": 0.2}),
        ("Plastic", {"Base Color": (0.1, 0.3, 0.8, 1.0), "Roughness": 0.3}),
        ("Glass", {"Transmission": 1.0, "Roughness": 0.0, "IOR": 1.45}),
        ("Rough", {"Base Color": (0.8, 0.2, 0.15, 1.0), "Roughness": 0.8}),
        ("Anisotropic", {"Base Color": (0.8, 0.8, 0.85, 1.0), "Metallic": 1.0,
                         "Roughness": 0.35, "Anisotropic": 0.8}),
        ("Sheen", {"Base Color": (0.3, 0.05, 0.1, 1.0), "Roughness": 0.9, "Sheen": 1.0,
                   "Sheen Tint": 0.5}),
    ]
    for i, (name, inputs) in enumerate(spheres):
        mat, *_ = kit.principled(name, **inputs)
        kit.uv_sphere(name, (-2.5 + i, 0.0, 0.42), 0.42, mat)
    kit.camera_at((0.0, -5.5, 1.6), (0.0, 0.0, 0.4), lens=42.0)
    library.cycles_reference(scene, samples=REFERENCE_SAMPLES, max_bounces=8, caustics=True)
    return scene


scene = build()
kit.save(scene, "hdri_row", kit.sidecar(
    scene, REFERENCE_SAMPLES,
    f"Six Principled spheres (metal, plastic, glass, rough, anisotropic metal, sheen) lit only "
    f"by Blender's studio HDRI courtyard.exr through an Environment Texture rotated by a "
    f"Mapping node (importance-sampled environment light, photons from the HDRI); Cycles "
    f"reference {REFERENCE_SAMPLES} spp, 8 bounces, caustics on. Image mean within 2%, each 4x4 tile within "
    f"5%.", timeout=240))
