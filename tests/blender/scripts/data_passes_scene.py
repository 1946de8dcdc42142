"""A small scene for the data passes (Depth, Mist, Normal, Position, UV, Object and Material
Index), rendered by the engine named after `--` (PHOTON or CYCLES) with one sample through the
pixel centre, so both engines see the same first hits. Used by test_data_passes.py.

    blender -b --factory-startup --addons photon -o OUT -F OPEN_EXR_MULTILAYER \
        --python data_passes_scene.py -f 1 -- ENGINE [extra: ortho | all | shaders | veil | denoise]

`veil` hangs two planes in front of the objects: Alpha 0 (index 12) and Alpha 0.7 (index 13),
on either side of View Layer > Passes > Alpha Threshold (0.5).
`shaders` gives the objects materials with every kind of closure (Principled metal and glass,
Glossy, Glass, Translucent and Emission nodes) and enables the colour passes and Emit.
`denoise` enables the Denoising Data passes (Denoising Normal, Albedo, Depth).
`aov` (with `clash`: and an AOV named Mist) adds shader AOVs (View Layer > Shader AOV: "tint" colour, "height" value, "unused" value)
and AOV Output nodes writing them: the floor a noise colour and its height, the sphere a constant
colour and its height from inside a node group, the cube's top only a Value into the colour AOV
(which writes its Color input), the veils (with `veil`) 100 into "height", the world a gradient
of the direction into "tint" and 50 into "height".
"""

import math
import sys

import bpy

import builders

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else ["PHOTON"]
engine = args[0]
extra = args[1:]

scene = bpy.context.scene
for obj in list(scene.objects):
    bpy.data.objects.remove(obj, do_unlink=True)


def material(name, color, pass_index):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*color, 1.0)
    mat.pass_index = pass_index
    return mat


bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, 0.0, 0.0))
floor = bpy.context.object
floor.data.materials.append(material("Floor", (0.6, 0.6, 0.6), 3))

bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(-1.2, 1.0, 1.0), segments=48,
                                     ring_count=24)
sphere = bpy.context.object
bpy.ops.object.shade_smooth()
sphere.pass_index = 2
sphere.data.materials.append(material("Red", (0.8, 0.1, 0.1), 5))

bpy.ops.mesh.primitive_cube_add(size=1.4, location=(1.5, 2.5, 0.7),
                                rotation=(0.0, 0.0, math.radians(30.0)))
cube = bpy.context.object
cube.pass_index = 7
cube.data.materials.append(material("Blue", (0.1, 0.2, 0.8), 9))
# A second slot on some faces: the material index follows the face's material.
cube.data.materials.append(material("Green", (0.1, 0.8, 0.2), 11))
for polygon in cube.data.polygons:
    if polygon.normal.z > 0.5:  # the top face, which the camera sees
        polygon.material_index = 1

bpy.ops.object.light_add(type="SUN", rotation=(math.radians(40), 0.0, math.radians(30)))
bpy.context.object.data.energy = 3.0

bpy.ops.object.camera_add(location=(0.0, -7.0, 3.0), rotation=(math.radians(75), 0.0, 0.0))
camera = bpy.context.object
scene.camera = camera
if "ortho" in extra:
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = 9.0

world = scene.world or bpy.data.worlds.new("World")
scene.world = world
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.05, 0.05, 0.08, 1.0)
world.mist_settings.start = 3.0
world.mist_settings.depth = 9.0
world.mist_settings.falloff = "QUADRATIC"

render = scene.render
render.resolution_x, render.resolution_y = 80, 60
render.resolution_percentage = 100
render.use_compositing = False
render.use_sequencer = False
render.image_settings.color_depth = "32"

layer = scene.view_layers[0]
for prop in ("use_pass_z", "use_pass_mist", "use_pass_normal", "use_pass_position",
             "use_pass_uv", "use_pass_object_index", "use_pass_material_index"):
    setattr(layer, prop, True)
if "all" in extra:
    # Passes Photon does not write: they must be reported, not silently zero.
    layer.use_pass_ambient_occlusion = True
    layer.use_pass_environment = True
if "denoise" in extra:
    # View Layer > Passes > Data > Denoising Data: Denoising Normal, Albedo and Depth.
    layer.cycles.denoising_store_passes = True
if "shaders" in extra:
    for prop in ("use_pass_diffuse_color", "use_pass_glossy_color",
                 "use_pass_transmission_color", "use_pass_emit"):
        setattr(layer, prop, True)

    def node_material(name, kind, **inputs):
        mat = bpy.data.materials.new(name)
        mat.use_nodes = True
        nodes = mat.node_tree.nodes
        nodes.remove(nodes["Principled BSDF"])
        node = nodes.new(kind)
        for key, value in inputs.items():
            node.inputs[key].default_value = value
        mat.node_tree.links.new(node.outputs[0], nodes["Material Output"].inputs["Surface"])
        return mat

    red = sphere.data.materials[0].node_tree.nodes["Principled BSDF"]
    red.inputs["Metallic"].default_value = 0.3
    builders.set_principled(red, "Transmission", 0.4)
    builders.set_principled(red, "Sheen", 0.5)
    cube.data.materials[0] = node_material("Glossy", "ShaderNodeBsdfGlossy",
                                           Color=(0.9, 0.6, 0.2, 1.0), Roughness=0.3)
    cube.data.materials[1] = node_material("Glass", "ShaderNodeBsdfGlass",
                                           Color=(0.7, 0.9, 0.8, 1.0), Roughness=0.2, IOR=1.5)
    floor.data.materials[0] = node_material("Translucent", "ShaderNodeBsdfTranslucent",
                                            Color=(0.3, 0.5, 0.4, 1.0))
    bpy.ops.mesh.primitive_ico_sphere_add(radius=0.5, location=(0.3, -0.5, 0.5))
    lamp = bpy.context.object
    lamp.data.materials.append(node_material("Glow", "ShaderNodeEmission",
                                             Color=(1.0, 0.8, 0.5, 1.0), Strength=3.0))
    # An area light facing the camera and shown to it: its radiance goes into Emit, and the
    # camera ray goes on to the floor behind it (Cycles' camera rays pass through lamps).
    bpy.ops.object.light_add(type="AREA", location=(1.9, -1.5, 0.6),
                             rotation=(math.radians(-90), 0.0, 0.0))
    area = bpy.context.object
    area.data.energy = 20.0
    area.data.size = 0.6
    area.visible_camera = True



def aov_output(tree, name, color=None, value=None):
    """An AOV Output node in `tree` writing AOV `name` (sockets: an output to link, or a
    constant)."""
    node = tree.nodes.new("ShaderNodeOutputAOV")
    if hasattr(node, "aov_name"):
        node.aov_name = name
    else:
        node.name = name  # Blender 3.x: the AOV name hides the node's name
    for socket, given in (("Color", color), ("Value", value)):
        if given is None:
            continue
        if isinstance(given, bpy.types.NodeSocket):
            tree.links.new(given, node.inputs[socket])
        else:
            node.inputs[socket].default_value = given
    return node


def height_group():
    """A node group that writes the shading point's height into AOV "height"."""
    group = bpy.data.node_groups.new("HeightAOV", "ShaderNodeTree")
    geometry = group.nodes.new("ShaderNodeNewGeometry")
    split = group.nodes.new("ShaderNodeSeparateXYZ")
    group.links.new(geometry.outputs["Position"], split.inputs[0])
    aov_output(group, "height", value=split.outputs["Z"])
    return group


if "aov" in extra:
    names = (("tint", "COLOR"), ("height", "VALUE"), ("unused", "VALUE"))
    if "clash" in extra:
        names += (("Mist", "VALUE"),)  # the Mist pass's name: Blender marks the AOV invalid
    for name, kind in names:
        aov = layer.aovs.add()
        aov.name, aov.type = name, kind
    tree = floor.data.materials[0].node_tree
    noise = tree.nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 0.8
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    split = tree.nodes.new("ShaderNodeSeparateXYZ")
    tree.links.new(geometry.outputs["Position"], split.inputs[0])
    aov_output(tree, "tint", color=noise.outputs["Color"])
    aov_output(tree, "height", value=split.outputs["Z"])
    aov_output(tree, "unused", value=7.0).mute = True  # muted: writes nothing
    tree = sphere.data.materials[0].node_tree
    aov_output(tree, "tint", color=(0.2, 0.4, 0.6, 1.0))
    tree.nodes.new("ShaderNodeGroup").node_tree = height_group()
    aov_output(cube.data.materials[1].node_tree, "tint", value=5.0)
    aov_output(cube.data.materials[0].node_tree, "elsewhere", value=3.0)  # not a view layer AOV
    tree = world.node_tree
    gradient = tree.nodes.new("ShaderNodeTexGradient")
    gradient.gradient_type = "LINEAR"
    aov_output(tree, "tint", color=gradient.outputs["Color"])
    aov_output(tree, "height", value=50.0)

render.engine = engine
# Photon reads Cycles' Film settings too: Box, and Photon's own Box width below.
scene.cycles.pixel_filter_type = "BOX"
if engine == "CYCLES":
    scene.cycles.samples = 1
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.filter_width = 0.01
    scene.cycles.device = "CPU"
else:
    scene.photon.samples = 1
    scene.photon.filter_width = 0.01

if "veil" in extra:
    for prop in ("use_pass_diffuse_color", "use_pass_glossy_color", "use_pass_emit"):
        setattr(layer, prop, True)
    for x, alpha, index in ((-1.3, 0.0, 12), (1.4, 0.7, 13)):
        bpy.ops.mesh.primitive_plane_add(size=1.6, location=(x, -2.5, 1.2),
                                         rotation=(math.radians(90), 0.0, 0.0))
        veil = bpy.context.object
        veil.pass_index = index
        mat = material(f"Veil{index}", (0.2, 0.7, 0.3), index)
        mat.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = alpha
        mat.blend_method = "BLEND"
        veil.data.materials.append(mat)
        if "aov" in extra:
            aov_output(mat.node_tree, "height", value=100.0)
