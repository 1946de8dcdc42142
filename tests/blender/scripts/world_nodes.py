"""World node trees rendered by Cycles and by Photon to EXR in the folder given. Args: out_dir,
photon_samples, cycles_samples. Three worlds:
  camera_trick: Mix Shader of two Backgrounds by Light Path "Is Camera Ray" (camera rays see
      blue, everything else is lit by white), over a white diffuse floor;
  hdri: Blender's studio HDRI through an Environment Texture rotated by a Mapping node, seen
      by the camera above the horizon and lighting a white diffuse floor below it;
  hdri_direct: the same Environment Texture's Color wired straight into the World Output.
Returns {case: {"cycles": path, "photon": path}}."""

import math
import os

import bpy

import builders
from harness import run

STUDIO = "/usr/share/blender/datafiles/studiolights/world/courtyard.exr"


def scene_for(engine, samples):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if engine == 'PHOTON':
        import addon_utils
        addon_utils.enable("photon", default_set=True)
    scene = bpy.context.scene
    scene.render.engine = engine
    scene.render.resolution_x, scene.render.resolution_y = 64, 48
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.view_settings.view_transform = 'Standard'
    # Cycles' Film, which Photon reads too: a one-pixel box in both engines.
    scene.cycles.pixel_filter_type = 'BOX'
    scene.cycles.filter_width = 1.0
    if engine == 'CYCLES':
        scene.cycles.samples = samples
        scene.cycles.use_denoising = False
    else:
        scene.photon.samples = samples
        scene.photon.integrator = 'PHOTON_MAP'
    mesh = bpy.data.meshes.new("floor")
    mesh.from_pydata([(-20, -20, 0), (20, -20, 0), (20, 20, 0), (-20, 20, 0)], [],
                     [(0, 1, 2, 3)])
    floor = bpy.data.objects.new("floor", mesh)
    mat = bpy.data.materials.new("white")
    mat.use_nodes = True
    mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8,) * 3 + (1,)
    builders.set_principled(mat.node_tree.nodes["Principled BSDF"], "Specular", 0.0)
    mat.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 1.0
    mesh.materials.append(mat)
    scene.collection.objects.link(floor)
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.location = (0.0, -6.0, 1.5)
    cam.rotation_euler = (math.radians(88.0), 0.0, 0.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    return scene


def camera_trick_world(scene):
    world = bpy.data.worlds.new("trick")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputWorld")
    lighting = nodes.new("ShaderNodeBackground")
    lighting.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    seen = nodes.new("ShaderNodeBackground")
    seen.inputs["Color"].default_value = (0.1, 0.2, 0.9, 1.0)
    path = nodes.new("ShaderNodeLightPath")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    links.new(lighting.outputs[0], mix.inputs[1])
    links.new(seen.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    scene.world = world


def hdri_world(scene):
    world = bpy.data.worlds.new("hdri")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = bpy.data.images.load(STUDIO)
    mapping = nodes.new("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(40.0))
    coords = nodes.new("ShaderNodeTexCoord")
    links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    links.new(env.outputs["Color"], nodes["Background"].inputs["Color"])
    scene.world = world


def hdri_direct_world(scene):
    """The HDRI's Color wired straight into the World Output, without a Background node."""
    hdri_world(scene)
    nodes, links = scene.world.node_tree.nodes, scene.world.node_tree.links
    links.new(nodes["Environment Texture"].outputs["Color"],
              nodes["World Output"].inputs["Surface"])


def main(out_dir, photon_samples, cycles_samples):
    result = {}
    for case, make_world in (("camera_trick", camera_trick_world), ("hdri", hdri_world),
                             ("hdri_direct", hdri_direct_world)):
        result[case] = {}
        for engine, samples in (("CYCLES", int(cycles_samples)),
                                ("PHOTON", int(photon_samples))):
            scene = scene_for(engine, samples)
            make_world(scene)
            path = os.path.join(out_dir, f"{case}_{engine.lower()}.exr")
            scene.render.filepath = path
            bpy.ops.render.render(write_still=True)
            result[case][engine.lower()] = path
    return result


if __name__ == "__main__":
    run(main)
