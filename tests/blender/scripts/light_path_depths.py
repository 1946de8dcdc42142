"""Light Path depth outputs seen through delta bounces, rendered by Cycles and by Photon to EXR in
the folder given. Args: out_dir, samples. An orthographic camera looks down on an emitter plane
whose Emission colour is (Ray Depth, Glossy Depth, Transmission Depth) / 4 in one render and
(Transparent Depth, Diffuse Depth, 0) / 4 in the other. The left half of the view looks through
two Transparent panes, the right half through a sharp glass slab (two refractions, plus Fresnel
paths reflected inside it). Returns {case: {"cycles": path, "photon": path}}."""

import os

import bpy
import builders
from harness import run


def plane(name, z, x0, x1, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(x0, -2, z), (x1, -2, z), (x1, 2, z), (x0, 2, z)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def material(name, bsdf_type, **inputs):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    bsdf = nodes.new(bsdf_type)
    for key, value in inputs.items():
        bsdf.inputs[key].default_value = value
    mat.node_tree.links.new(bsdf.outputs[0], nodes["Material Output"].inputs["Surface"])
    return mat, bsdf


def emitter(outputs):
    mat, emission = material("depths", "ShaderNodeEmission")
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    path = nodes.new("ShaderNodeLightPath")
    combine = nodes.new("ShaderNodeCombineXYZ")
    for i, name in enumerate(outputs):
        if name:
            links.new(path.outputs[name], combine.inputs[i])
    scale = nodes.new("ShaderNodeVectorMath")
    scale.operation = 'SCALE'
    scale.inputs["Scale"].default_value = 0.25
    links.new(combine.outputs[0], scale.inputs[0])
    links.new(scale.outputs[0], emission.inputs["Color"])
    return mat


def scene_for(engine, samples, outputs):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if engine == 'PHOTON':
        import addon_utils
        addon_utils.enable("photon", default_set=True)
    scene = bpy.context.scene
    scene.render.engine = engine
    scene.render.resolution_x, scene.render.resolution_y = 48, 24
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
        scene.photon.integrator = 'RAY_TRACE'
    plane("emitter", 0.0, -4, 4, emitter(outputs))
    pane, _ = material("pane", "ShaderNodeBsdfTransparent")
    plane("pane_low", 1.0, -4, 0, pane)
    plane("pane_high", 1.5, -4, 0, pane)
    glass, node = material("glass", "ShaderNodeBsdfGlass", IOR=1.5)
    builders.set_sharp(node)
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(2.0, 0.0, 1.25))
    slab = bpy.context.active_object
    slab.scale = (4.0, 4.0, 0.5)
    slab.data.materials.append(glass)
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = 7.0
    cam.location = (0.0, 0.0, 5.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    return scene


def main(out_dir, samples):
    result = {}
    for case, outputs in (("depth_glossy_transmission",
                           ("Ray Depth", "Glossy Depth", "Transmission Depth")),
                          ("transparent_diffuse", ("Transparent Depth", "Diffuse Depth", None))):
        result[case] = {}
        for engine in ("CYCLES", "PHOTON"):
            scene = scene_for(engine, int(samples), outputs)
            path = os.path.join(out_dir, f"{case}_{engine.lower()}.exr")
            scene.render.filepath = path
            bpy.ops.render.render(write_still=True)
            result[case][engine.lower()] = path
    return result


if __name__ == "__main__":
    run(main)
