"""Principled BSDF v2 (Blender 4.0+) spheres, one material each, in a grid 6 wide lit by a sun
and a grey world, rendered by Cycles and by Photon to EXR in the folder given. Args: out_dir,
photon_samples, cycles_samples. Returns {"cycles": path, "photon": path, "version": [...],
"regions": {name: [cx, cy, r] in pixels, y down}} (or {"skip": reason} before Blender 4.0)."""

import math
import os
import sys

# Blender 4.2+ ignores PYTHONPATH unless started with --python-use-system-env: find the helpers
# beside this script.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
from harness import run  # noqa: E402
from principled_extras import clear, render_both  # noqa: E402

COLS = 6
RES_X = 384
ORTHO_SCALE = 6.2
RADIUS = 0.45


def principled_setup(**inputs):
    def setup(mat):
        p = next(n for n in mat.node_tree.nodes if n.type == 'BSDF_PRINCIPLED')
        for name, value in inputs.items():
            if name == "distribution":
                p.distribution = value
                continue
            socket = p.inputs[name]
            socket.default_value = (*value, 1.0) if isinstance(value, tuple) and \
                len(value) == 3 and socket.type == 'RGBA' else value
    return setup


def diffuse_setup(color, roughness):
    def setup(mat):
        tree = mat.node_tree
        tree.nodes.remove(next(n for n in tree.nodes if n.type == 'BSDF_PRINCIPLED'))
        diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (*color, 1.0)
        diffuse.inputs["Roughness"].default_value = roughness
        out = next(n for n in tree.nodes if n.type == 'OUTPUT_MATERIAL')
        tree.links.new(diffuse.outputs[0], out.inputs["Surface"])
    return setup


def glossy_setup(color, roughness, anisotropy=0.0):
    def setup(mat):
        tree = mat.node_tree
        tree.nodes.remove(next(n for n in tree.nodes if n.type == 'BSDF_PRINCIPLED'))
        glossy = tree.nodes.new("ShaderNodeBsdfAnisotropic")  # 4.x: the merged Glossy BSDF
        glossy.inputs["Color"].default_value = (*color, 1.0)
        glossy.inputs["Roughness"].default_value = roughness
        glossy.inputs["Anisotropy"].default_value = anisotropy
        out = next(n for n in tree.nodes if n.type == 'OUTPUT_MATERIAL')
        tree.links.new(glossy.outputs[0], out.inputs["Surface"])
    return setup


RED = (0.8, 0.2, 0.1)
MATERIALS = [
    ("ior_level_0", principled_setup(**{"Base Color": RED, "Roughness": 0.3,
                                        "Specular IOR Level": 0.0})),
    ("ior_level_half", principled_setup(**{"Base Color": RED, "Roughness": 0.3})),
    ("ior_level_1", principled_setup(**{"Base Color": RED, "Roughness": 0.3,
                                        "Specular IOR Level": 1.0})),
    ("specular_tint", principled_setup(**{"Base Color": (0.3, 0.3, 0.3), "Roughness": 0.2,
                                          "Specular IOR Level": 1.0,
                                          "Specular Tint": (0.2, 0.5, 1.0)})),
    ("metal_edge_tint", principled_setup(**{"Base Color": (0.9, 0.6, 0.3), "Metallic": 1.0,
                                            "Roughness": 0.35,
                                            "Specular Tint": (0.3, 0.6, 1.0)})),
    ("metal_rough", principled_setup(**{"Base Color": (0.95, 0.95, 0.95), "Metallic": 1.0,
                                        "Roughness": 0.8})),
    ("coat_tint", principled_setup(**{"Base Color": (0.8, 0.8, 0.8), "Roughness": 0.5,
                                      "Coat Weight": 1.0, "Coat Roughness": 0.1,
                                      "Coat Tint": (0.9, 0.5, 0.2)})),
    ("transmission", principled_setup(**{"Base Color": (0.9, 0.9, 0.6), "Roughness": 0.2,
                                         "Transmission Weight": 1.0, "IOR": 1.45})),
    ("emission", principled_setup(**{"Base Color": (0.2, 0.2, 0.2),
                                     "Emission Color": (1.0, 0.5, 0.2),
                                     "Emission Strength": 2.0})),
    ("anisotropic", principled_setup(**{"Base Color": (0.9, 0.7, 0.5), "Metallic": 1.0,
                                        "Roughness": 0.4, "Anisotropic": 0.8})),
    ("glossy", glossy_setup((0.7, 0.8, 0.9), 0.6)),
    ("single_scatter", principled_setup(**{"Base Color": (0.2, 0.6, 0.3), "Metallic": 0.5,
                                           "Roughness": 0.7, "distribution": 'GGX'})),
]
# Blender 4.3's energy-preserving Oren-Nayar: the Principled BSDF's Diffuse Roughness (new in
# 4.3) and a rough Diffuse BSDF.
if bpy.app.version >= (4, 3, 0):
    MATERIALS += [
        ("diffuse_roughness", principled_setup(**{"Base Color": (0.8, 0.5, 0.3),
                                                  "Roughness": 0.5, "Diffuse Roughness": 1.0})),
        ("diffuse_bsdf_rough", diffuse_setup((0.5, 0.7, 0.9), 0.8)),
    ]
ROWS = (len(MATERIALS) + COLS - 1) // COLS
RES_Y = 64 * ROWS


def build():
    clear()
    scene = bpy.context.scene
    regions = {}
    px_per_unit = RES_X / ORTHO_SCALE
    for i, (name, setup) in enumerate(MATERIALS):
        col, row = i % COLS, i // COLS
        x = (col - (COLS - 1) / 2) * 1.0
        z = ((ROWS - 1) / 2 - row) * 1.0
        bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=RADIUS,
                                             location=(x, 0.0, z))
        sphere = bpy.context.active_object
        bpy.ops.object.shade_smooth()
        mat = bpy.data.materials.new(name)
        mat.use_nodes = True
        sphere.data.materials.append(mat)
        setup(mat)
        regions[name] = [RES_X / 2 + x * px_per_unit, RES_Y / 2 - z * px_per_unit,
                         RADIUS * px_per_unit]
    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = 'ORTHO'
    cam_data.ortho_scale = ORTHO_SCALE
    cam = bpy.data.objects.new("cam", cam_data)
    cam.location = (0.0, -6.0, 0.0)
    cam.rotation_euler = (math.pi / 2, 0.0, 0.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    sun_data = bpy.data.lights.new("sun", 'SUN')
    sun_data.energy = 3.0
    sun_data.angle = math.radians(2.0)
    sun = bpy.data.objects.new("sun", sun_data)
    sun.rotation_euler = (math.radians(60), 0.0, math.radians(40))
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.3, 0.3, 0.3, 1.0)
    scene.world = world
    scene.render.resolution_x, scene.render.resolution_y = RES_X, RES_Y
    scene.render.resolution_percentage = 100
    scene.render.use_compositing = False
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.view_settings.view_transform = 'Standard'
    return scene, regions


def main(out_dir, photon_samples, cycles_samples):
    if bpy.app.version < (4, 0, 0):
        return {"skip": f"Blender {bpy.app.version_string} has the Principled BSDF v1"}
    scene, regions = build()
    paths = render_both(scene, out_dir, "principled_v2", photon_samples, cycles_samples)
    return dict(paths, regions=regions, version=list(bpy.app.version))


if __name__ == "__main__":
    run(main)
