"""A scene for the Cryptomatte passes, rendered by the engine named after `--` (PHOTON or
CYCLES): a floor, a ball half behind a 50% transparent veil, a box parented to an empty 'Rig'
(its asset), and a cube without a material. Object, Material and Asset Cryptomatte are on
(Levels 6), and the compositor keys the ball out with Blender's Cryptomatte node, so the
multilayer EXR holds the passes, their metadata and the node's matte. Used by
test_cryptomatte.py.

    blender -b --factory-startup --addons photon -o OUT -F OPEN_EXR_MULTILAYER \\
        --python cryptomatte_scene.py -f 1 -- ENGINE
"""

import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else ["PHOTON"]
engine = args[0]

scene = bpy.context.scene
for obj in list(scene.objects):
    bpy.data.objects.remove(obj, do_unlink=True)


def material(name, color, alpha=1.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Alpha"].default_value = alpha
    mat.blend_method = 'BLEND' if alpha < 1.0 else 'OPAQUE'
    return mat


bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, 0.0, 0.0))
bpy.context.object.name = "Floor"
bpy.context.object.data.materials.append(material("FloorMat", (0.6, 0.6, 0.6)))

bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(-1.2, 1.0, 1.0), segments=48,
                                     ring_count=24)
bpy.context.object.name = "Ball"
bpy.ops.object.shade_smooth()
bpy.context.object.data.materials.append(material("Red", (0.8, 0.1, 0.1)))

bpy.ops.object.empty_add(location=(1.5, 2.5, 0.0))
rig = bpy.context.object
rig.name = "Rig"
bpy.ops.mesh.primitive_cube_add(size=1.4, location=(1.5, 2.5, 0.7))
box = bpy.context.object
box.name = "Box"
box.data.materials.append(material("Blue", (0.1, 0.2, 0.8)))
box.parent = rig
box.matrix_parent_inverse = rig.matrix_world.inverted()

bpy.ops.mesh.primitive_cube_add(size=0.8, location=(0.3, -0.6, 0.4))
bpy.context.object.name = "Bare"  # no material: Cycles' default surface

# The veil covers the ball's left half, between it and the camera.
bpy.ops.mesh.primitive_plane_add(size=1.6, location=(-1.9, -0.6, 1.0), rotation=(1.5708, 0, 0))
bpy.context.object.name = "Veil"
bpy.context.object.data.materials.append(material("Gauze", (0.9, 0.9, 0.9), alpha=0.5))

bpy.ops.object.light_add(type='SUN', location=(0.0, 0.0, 10.0), rotation=(0.5, 0.2, 0.0))
bpy.context.object.data.energy = 3.0
bpy.ops.object.camera_add(location=(0.0, -9.0, 4.0), rotation=(1.2, 0.0, 0.0))
scene.camera = bpy.context.object

scene.render.engine = engine
scene.render.resolution_x, scene.render.resolution_y = 160, 120
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = 'OPEN_EXR_MULTILAYER'
scene.render.image_settings.color_depth = '32'
scene.cycles.samples = 16
scene.cycles.use_denoising = False
scene.cycles.seed = 1
if hasattr(scene, "photon"):
    scene.photon.samples = 16
    scene.photon.integrator = 'RAY_TRACE'

view_layer = scene.view_layers[0]
view_layer.use_pass_cryptomatte_object = True
view_layer.use_pass_cryptomatte_material = True
view_layer.use_pass_cryptomatte_asset = True
view_layer.pass_cryptomatte_depth = 6

# The compositor keys the ball out by name, through the metadata's manifest.
scene.use_nodes = True
tree = scene.node_tree
for node in list(tree.nodes):
    tree.nodes.remove(node)
layers = tree.nodes.new("CompositorNodeRLayers")
crypto = tree.nodes.new("CompositorNodeCryptomatteV2")
crypto.source = 'RENDER'
crypto.scene = scene
crypto.layer_name = f"{view_layer.name}.CryptoObject"
crypto.matte_id = "Ball"
composite = tree.nodes.new("CompositorNodeComposite")
tree.links.new(layers.outputs["Image"], crypto.inputs["Image"])
tree.links.new(crypto.outputs["Matte"], composite.inputs["Image"])
