"""Builds the scene of tests/blender/test_view_layers.py in the running Blender; the command line
then renders it (`-o OUT --python view_layers_scene.py -f 1 -- MODE [OPTION=VALUE ...]`).

A camera at the origin looks down +Y over a grey floor. Collection "LeftSet" holds a sphere at
x = -0.6, collection "RightSet" a cube at x = +0.6, both 4 m in front of the camera; a sun lights
them against a black world.

MODE:
  layers   view layers "OnlyLeft" (RightSet excluded) and "OnlyRight" (LeftSet excluded), both
           used for rendering, the first with the Photon Direct pass enabled.
  stereo   one view layer, stereo 3D multiview (off-axis, pivot CENTER, interocular 0.3 m).
  mono     one view layer, no multiview; options move the camera (cam_x=metres along its x)
           and set its lens shift (shift_x=...), to stand in for one eye of `stereo`.
Options: pivot=LEFT|RIGHT|CENTER and convergence=OFFAXIS|PARALLEL|TOE (stereo),
exclude=, indirect_only= and holdout=COLLECTION[,...], and material_override=MATERIAL (in the
first view layer),
integrator=..., samples=N.
"""

import math
import sys

import bpy

import builders

INTEROCULAR = 0.3
CONVERGENCE = 1.95
DEPTH = 4.0


def args():
    argv = sys.argv
    rest = argv[argv.index("--") + 1:] if "--" in argv else []
    mode = rest[0] if rest else "layers"
    options = dict(item.split("=", 1) for item in rest[1:])
    return mode, options


def emission_free_material(name, color):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    builders.set_principled(bsdf, "Specular", 0.0)
    return mat


def build(mode, options):
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    scene = bpy.context.scene
    scene.render.engine = 'PHOTON'
    scene.render.resolution_x = 160
    scene.render.resolution_y = 96
    scene.render.resolution_percentage = 100
    scene.render.use_compositing = False
    scene.render.use_sequencer = False
    scene.photon.integrator = options.get("integrator", "RAY_TRACE")
    scene.photon.samples = int(options.get("samples", 16))
    scene.photon.seed = 7
    scene.world.use_nodes = False
    scene.world.color = (0.0, 0.0, 0.0)
    scene.view_settings.view_transform = 'Standard'

    cam_data = bpy.data.cameras.new("Camera")
    cam_data.lens = 50.0
    cam_data.sensor_width = 36.0
    cam_data.sensor_fit = 'AUTO'
    cam_data.shift_x = float(options.get("shift_x", 0.0))
    cam_data.stereo.interocular_distance = INTEROCULAR
    cam_data.stereo.convergence_distance = CONVERGENCE
    cam_data.stereo.convergence_mode = options.get("convergence", "OFFAXIS")
    cam_data.stereo.pivot = options.get("pivot", "CENTER")
    cam = bpy.data.objects.new("Camera", cam_data)
    cam.location = (float(options.get("cam_x", 0.0)), 0.0, 0.0)
    cam.rotation_euler = (math.radians(90.0), 0.0, 0.0)  # looks down +Y, +Z up, +X right
    scene.collection.objects.link(cam)
    scene.camera = cam

    sun_data = bpy.data.lights.new("Sun", 'SUN')
    sun_data.energy = 3.0
    sun = bpy.data.objects.new("Sun", sun_data)
    sun.rotation_euler = (math.radians(30.0), math.radians(-20.0), 0.0)
    scene.collection.objects.link(sun)

    bpy.ops.mesh.primitive_plane_add(size=30.0, location=(0.0, DEPTH, -0.6))
    bpy.context.object.name = "Floor"
    bpy.context.object.data.materials.append(emission_free_material("Grey", (0.2, 0.2, 0.2)))

    left_set = bpy.data.collections.new("LeftSet")
    right_set = bpy.data.collections.new("RightSet")
    scene.collection.children.link(left_set)
    scene.collection.children.link(right_set)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.4, location=(-0.6, DEPTH, 0.0))
    sphere = bpy.context.object
    sphere.name = "LeftSphere"
    sphere.data.materials.append(emission_free_material("Red", (0.8, 0.05, 0.05)))
    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(0.6, DEPTH, 0.0))
    cube = bpy.context.object
    cube.name = "RightCube"
    cube.data.materials.append(emission_free_material("Blue", (0.05, 0.05, 0.8)))
    for obj, target in ((sphere, left_set), (cube, right_set)):
        for owner in list(obj.users_collection):
            owner.objects.unlink(obj)
        target.objects.link(obj)

    first = scene.view_layers[0]
    if mode == "layers":
        first.name = "OnlyLeft"
        second = scene.view_layers.new("OnlyRight")
        first.layer_collection.children["RightSet"].exclude = True
        second.layer_collection.children["LeftSet"].exclude = True
        first.use = second.use = True
        first.photon.use_pass_direct = True
    for name in filter(None, options.get("exclude", "").split(",")):
        first.layer_collection.children[name].exclude = True
    if "material_override" in options:
        first.material_override = bpy.data.materials[options["material_override"]]
    for name in filter(None, options.get("indirect_only", "").split(",")):
        first.layer_collection.children[name].indirect_only = True
    for name in filter(None, options.get("holdout", "").split(",")):
        first.layer_collection.children[name].holdout = True
    if mode == "stereo":
        scene.render.use_multiview = True
        scene.render.views_format = 'STEREO_3D'
        scene.render.image_settings.views_format = 'INDIVIDUAL'
    print(f"view_layers_scene: built {mode} {sorted(options.items())}", flush=True)


build(*args())
