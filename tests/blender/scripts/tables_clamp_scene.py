"""Builds a plane whose Principled BSDF gets one input above the range Photon accepts, fed
either by a Value / RGB node (a constant) or by a float image texture of the same value, and
saves it as a .blend. Args: INPUT MODE VALUE BLEND_PATH.

INPUT "Emission Strength": an Emission colour of 1e-6 (no lights: the plane shows colour x the
clamped strength); "Base Color": a grey base colour under a sun. MODE "constant" or "texture"."""

import math

import bpy

import builders
import harness


def main(input_name, mode, value, blend):
    value = float(value)
    scene = builders.reset_scene(width=16, height=16)
    scene.photon.integrator = "RAY_TRACE"
    scene.photon.samples = 4
    builders.camera(location=(0, -3.0, 1.0), lens=50.0)
    mat = bpy.data.materials.new("Clamped")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    socket = bsdf.inputs[input_name]
    if input_name == "Emission Strength":
        bsdf.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        builders.set_principled(bsdf, "Specular", 0.0)
        builders.set_principled(bsdf, "Emission", (1e-6, 1e-6, 1e-6, 1.0))
    else:
        builders.light("Sun", 'SUN', 1.0, (0, -2, 2), rotation=(math.pi / 2, 0, 0))
    if mode == "constant":
        node = nodes.new("ShaderNodeRGB" if socket.type == 'RGBA' else "ShaderNodeValue")
        node.outputs[0].default_value = ((value, value, value, 1.0) if socket.type == 'RGBA'
                                         else value)
        links.new(node.outputs[0], socket)
    elif mode == "texture":
        # A generated float image (saved with the .blend as its settings, not its pixels) of
        # linear `value`: Blender takes the fill colour as sRGB.
        image = bpy.data.images.new("Above", 4, 4, float_buffer=True)
        c = 1.055 * value ** (1.0 / 2.4) - 0.055
        image.generated_color = (c, c, c, 1.0)
        tex = nodes.new("ShaderNodeTexImage")
        tex.image = image
        links.new(tex.outputs["Color"], socket)
    else:
        raise ValueError(mode)
    plane = builders.quad("Plane", (-1, 0, 0), (2, 0, 0), (0, 0, 2), material=mat)
    uv = plane.data.uv_layers.new(name="UVMap")
    for loop, co in zip(uv.data, [(0, 0), (1, 0), (1, 1), (0, 1)]):
        loop.uv = co
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    return {"pixel": bpy.data.images[0].pixels[0] if mode == "texture" else value}


harness.run(main)
