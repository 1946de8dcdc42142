"""A floor seen from above, lit by lamps with IES profiles, rendered by Cycles and by Photon to
EXR in the folder given: a turned point lamp whose profile is a text datablock, a spot whose
profile is a file scaled by a Math Multiply node, an area light (Cycles reads its profile along
its axis only) and a point lamp whose file is missing (Cycles renders that as 100 in every
direction). Args: out_dir, photon_samples, cycles_samples. Returns {"cycles": path, "photon":
path, "warnings": [...], "version": [...]}."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
from harness import run  # noqa: E402
from principled_extras import clear, render_both  # noqa: E402

# Profiles made for the tests (test_scenes/ies): skewed.ies is brighter to one side than the
# other and dark above 120 degrees from the lamp's -Z axis; quadrant.ies is a type C quadrant,
# mirrored to the whole circle by the reader.
PROFILES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                        "test_scenes", "ies")


def profile(name):
    with open(os.path.join(PROFILES, name)) as f:
        return f.read()


def lamp(name, kind, location, energy, rotation=(0.0, 0.0, 0.0)):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    if kind in {'POINT', 'SPOT'}:
        data.shadow_soft_size = 0.0
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.collection.objects.link(obj)
    data.use_nodes = True
    return data


def feed_ies(data, mode, profile=None, path=None, multiply=None):
    tree = data.node_tree
    emission = next(n for n in tree.nodes if n.type == 'EMISSION')
    ies = tree.nodes.new("ShaderNodeTexIES")
    ies.mode = mode
    if mode == 'INTERNAL':
        text = bpy.data.texts.new(f"{data.name}.ies")
        text.write(profile)
        ies.ies = text
    else:
        ies.filepath = path
    out = ies.outputs["Fac"]
    if multiply is not None:
        math_node = tree.nodes.new("ShaderNodeMath")
        math_node.operation = 'MULTIPLY'
        math_node.inputs[1].default_value = multiply
        tree.links.new(out, math_node.inputs[0])
        out = math_node.outputs[0]
    tree.links.new(out, emission.inputs["Strength"])


def main(out_dir, photon_samples, cycles_samples):
    clear()
    for text in list(bpy.data.texts):
        bpy.data.texts.remove(text)
    scene = bpy.context.scene
    scene.render.resolution_x = scene.render.resolution_y = 96
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.view_settings.view_transform = 'Standard'
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    scene.world = world

    bpy.ops.mesh.primitive_plane_add(size=8.0)
    floor = bpy.context.active_object
    material = bpy.data.materials.new("floor")
    material.use_nodes = True
    bsdf = next(n for n in material.node_tree.nodes if n.type == 'BSDF_PRINCIPLED')
    bsdf.inputs["Base Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    for name in ("Specular", "Specular IOR Level"):
        if name in bsdf.inputs:
            bsdf.inputs[name].default_value = 0.0
    floor.data.materials.append(material)

    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.type = 'ORTHO'
    camera.data.ortho_scale = 8.0
    camera.location = (0.0, 0.0, 10.0)
    scene.collection.objects.link(camera)
    scene.camera = camera

    point = lamp("ies_point", 'POINT', (-2.0, 1.5, 1.2), 3.0, (0.6, 0.0, 0.5))
    feed_ies(point, 'INTERNAL', profile=profile("skewed.ies"))
    spot_file = os.path.join(PROFILES, "quadrant.ies")
    spot = lamp("ies_spot", 'SPOT', (2.0, 1.5, 1.5), 8.0, (0.3, 0.4, 0.0))
    spot.spot_size = math.radians(120.0)
    spot.spot_blend = 0.3
    feed_ies(spot, 'EXTERNAL', path=spot_file, multiply=0.5)
    area = lamp("ies_area", 'AREA', (1.5, -2.0, 1.0), 2.0)
    area.size = 0.5
    feed_ies(area, 'INTERNAL', profile=profile("skewed.ies"))
    missing = lamp("ies_missing", 'POINT', (-2.0, -2.0, 1.0), 0.02)
    feed_ies(missing, 'EXTERNAL', path=os.path.join(out_dir, "missing.ies"))

    paths = render_both(scene, out_dir, "ies", photon_samples, cycles_samples)
    return dict(paths, version=list(bpy.app.version))


if __name__ == "__main__":
    run(main)
