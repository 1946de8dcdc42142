"""A Cornell box with textured, mixed and unsupported materials, saved as a .blend.
Args: FOLDER BLEND_PATH (FOLDER receives the image files the materials read)."""

import os

import bpy

import builders
import harness
from material_closures import image_node, new_material, write_png


def main(folder, blend_path):
    os.makedirs(folder, exist_ok=True)
    builders.cornell_box(width=64, height=64, samples=4)

    # A packed image mixing a diffuse and a glossy by its alpha, on a UV-mapped floor tile.
    packed = write_png("Checker", os.path.join(folder, "checker.png"), 8, 8, (0.9, 0.2, 0.1, 1))
    packed.pack()
    mat, nodes, links, bsdf, out = new_material("TexturedMix")
    nodes.remove(bsdf)
    tex = image_node(nodes, packed)
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(tex.outputs["Alpha"], mix.inputs["Fac"])
    links.new(tex.outputs["Color"], diffuse.inputs["Color"])
    links.new(diffuse.outputs[0], mix.inputs[1])
    links.new(glossy.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    tile = builders.quad("Tile", (-0.9, -0.9, 0.01), (0.8, 0, 0), (0, 0.8, 0), mat)
    tile.data.uv_layers.new(name="UVMap")

    # A Wireframe node (not evaluated natively) into Base Color, a missing image into Roughness.
    mat, nodes, links, bsdf, out = new_material("WaveMat")
    bsdf.inputs["Base Color"].default_value = (0.1, 0.5, 0.2, 1.0)
    links.new(nodes.new("ShaderNodeWireframe").outputs["Fac"], bsdf.inputs["Base Color"])
    missing = bpy.data.images.new("Lost", 4, 4)
    missing.source = 'FILE'
    missing.filepath = os.path.join(folder, "lost.png")
    tex = image_node(nodes, missing)
    tex.name = "Lost Texture"
    links.new(tex.outputs["Color"], bsdf.inputs["Roughness"])
    builders.uv_sphere("WaveBall", (0.3, -0.3, 0.85), 0.2, material=mat)

    toon = builders.shader_material("ToonMat", "ShaderNodeBsdfToon", Color=(0.2, 0.4, 0.9, 1))
    builders.uv_sphere("ToonBall", (-0.4, -0.5, 0.3), 0.2, material=toon)

    bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    return {"saved": blend_path}


if __name__ == "__main__":
    harness.run(main)
