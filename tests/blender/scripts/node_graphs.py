"""Shader graphs that share sub-trees or run long, for the node-graph conversion tests.
Args: MODE KIND SIZE [BLEND]

KIND (the material is named after it):
  diamond N     Mix Shaders N levels deep; level k has two Mix nodes A_k = Mix(a_k, A_k-1, B_k-1)
                and B_k = Mix(b_k, B_k-1, A_k-1), each reusing both outputs of the level below
                (2^N paths); A_0 is a Diffuse, B_0 a Glossy BSDF; the output shows A_N.
  tex_diamond N the same with the Fac of both Mix nodes of level N // 2 + 1 driven by one
                image's Alpha.
  tex_diamonds N  the same with each level's Fac driven by the Alpha of its own image (2^N
                different texture products).
  add_chain N   an Add Shader chain N wide: a node group holding 50 Add Shaders, each adding
                Mix(Weight, nothing, Diffuse) to the previous one, instanced N / 50 times in a
                chain; instance k has its own Weight (so closures differ in constant weight).
                (Blender's nodes.new slows down with the tree's size: 2,000 Add Shaders in one
                tree take minutes to build, a group of 50 instanced 40 times a second.)
  chain N       a flat chain of N Add Shaders, each adding an Emission of its own strength.
MODE:
  convert       converts the material with the add-on (timed); result: "closures", "warnings",
                "seconds", and what the test needs to know the right answer ("facs" or
                "weights").
  scene         saves BLEND: a quad with the material in front of a camera, under a sun.
"""

import os
import sys
import time

import bpy

import builders
import harness
from material_closures import RecordingReporter, RecordingScene

GROUP_WIDTH = 50  # Add Shaders per group instance in add_chain


def _named(nodes, node_type, name):
    node = nodes.new(node_type)
    node.name = node.label = name
    return node


def _new_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    return mat, nodes, mat.node_tree.links, nodes["Material Output"]


def _level_facs(depth):
    """Distinct constant factors in (0, 1) for the diamond's Mix nodes: [(a_k, b_k)]."""
    return [(0.05 + 0.9 * ((7 * k) % 11) / 10.0, 0.05 + 0.9 * ((3 * k + 5) % 13) / 12.0)
            for k in range(1, depth + 1)]


def diamond(depth, textured=None):
    prefix = {None: "", "one": "Tex", "each": "Texs"}[textured]
    name = f"{prefix}Diamond{depth}"
    mat, nodes, links, out = _new_material(name)
    a = _named(nodes, "ShaderNodeBsdfDiffuse", "Leaf Diffuse")
    a.inputs["Color"].default_value = (0.8, 0.2, 0.1, 1.0)
    b = _named(nodes, "ShaderNodeBsdfGlossy", "Leaf Glossy")
    b.inputs["Color"].default_value = (0.1, 0.3, 0.9, 1.0)
    b.inputs["Roughness"].default_value = 0.4

    def alpha_of(level):
        image = bpy.data.images.new(f"DiamondAlpha{level}", 4, 4, alpha=True)
        image.generated_color = (0.5, 0.5, 0.5, 0.3)
        tex = _named(nodes, "ShaderNodeTexImage", f"Alpha Texture {level}")
        tex.image = image
        return tex.outputs["Alpha"]

    alpha = alpha_of(0) if textured == 'one' else None
    facs = []
    for level, (fa, fb) in enumerate(_level_facs(depth), start=1):
        if textured == 'each':
            alpha = alpha_of(level)
        mix_a = _named(nodes, "ShaderNodeMixShader", f"A{level}")
        mix_b = _named(nodes, "ShaderNodeMixShader", f"B{level}")
        mix_a.inputs["Fac"].default_value = fa
        mix_b.inputs["Fac"].default_value = fb
        links.new(a.outputs[0], mix_a.inputs[1])
        links.new(b.outputs[0], mix_a.inputs[2])
        links.new(b.outputs[0], mix_b.inputs[1])
        links.new(a.outputs[0], mix_b.inputs[2])
        if textured == 'each' or (textured and level == depth // 2 + 1):
            links.new(alpha, mix_a.inputs["Fac"])
            links.new(alpha, mix_b.inputs["Fac"])
        # The values Blender stores (float32), which the add-on reads.
        facs.append((mix_a.inputs["Fac"].default_value, mix_b.inputs["Fac"].default_value))
        a, b = mix_a, mix_b
    links.new(a.outputs[0], out.inputs["Surface"])
    return mat, {"facs": facs, "textured_level": depth // 2 + 1 if textured == 'one' else None}


def _chain_group():
    """Group: Shader in, then 50 times Add(previous, Mix(Weight, nothing, Diffuse_i)), out."""
    group = bpy.data.node_groups.new("Chain50", 'ShaderNodeTree')
    builders.new_group_socket(group, 'INPUT', 'NodeSocketShader', "Shader")
    builders.new_group_socket(group, 'INPUT', 'NodeSocketFloatFactor', "Weight")
    builders.new_group_socket(group, 'OUTPUT', 'NodeSocketShader', "Shader")
    nodes, links = group.nodes, group.links
    g_in = nodes.new("NodeGroupInput")
    g_out = nodes.new("NodeGroupOutput")
    previous = g_in.outputs["Shader"]
    for i in range(GROUP_WIDTH):
        leaf = _named(nodes, "ShaderNodeBsdfDiffuse", f"Diffuse {i}")
        leaf.inputs["Color"].default_value = (i / GROUP_WIDTH, 0.5, 0.5, 1.0)
        mix = _named(nodes, "ShaderNodeMixShader", f"Weigh {i}")
        links.new(g_in.outputs["Weight"], mix.inputs["Fac"])
        links.new(leaf.outputs[0], mix.inputs[2])
        add = _named(nodes, "ShaderNodeAddShader", f"Add {i}")
        links.new(previous, add.inputs[0])
        links.new(mix.outputs[0], add.inputs[1])
        previous = add.outputs[0]
    links.new(previous, g_out.inputs["Shader"])
    return group


def add_chain(width):
    assert width % GROUP_WIDTH == 0, width
    mat, nodes, links, out = _new_material(f"AddChain{width}")
    group = _chain_group()
    previous, weights = None, []
    count = width // GROUP_WIDTH
    for k in range(count):
        node = _named(nodes, "ShaderNodeGroup", f"Chain {k}")
        node.node_tree = group
        # A permutation of distinct weights in (0, 1]: the largest ones are not the first.
        node.inputs["Weight"].default_value = ((17 * k) % count + 1) / count
        weights += [node.inputs["Weight"].default_value] * GROUP_WIDTH
        if previous is not None:
            links.new(previous.outputs["Shader"], node.inputs["Shader"])
        previous = node
    links.new(previous.outputs["Shader"], out.inputs["Surface"])
    return mat, {"weights": weights}


def chain(length):
    mat, nodes, links, out = _new_material(f"Chain{length}")
    previous = None
    strengths = []
    for i in range(length):
        emission = _named(nodes, "ShaderNodeEmission", f"Emission {i}")
        emission.inputs["Strength"].default_value = 0.01 * (i + 1)
        strengths.append(emission.inputs["Strength"].default_value)
        if previous is None:
            previous = emission.outputs[0]
            continue
        add = _named(nodes, "ShaderNodeAddShader", f"Add {i}")
        links.new(previous, add.inputs[0])
        links.new(emission.outputs[0], add.inputs[1])
        previous = add.outputs[0]
    links.new(previous, out.inputs["Surface"])
    return mat, {"strengths": strengths}


def build(kind, size):
    size = int(size)
    if kind == "diamond":
        return diamond(size)
    if kind == "tex_diamond":
        return diamond(size, textured='one')
    if kind == "tex_diamonds":
        return diamond(size, textured='each')
    if kind == "add_chain":
        return add_chain(size)
    if kind == "chain":
        return chain(size)
    raise ValueError(f"unknown graph kind {kind!r}")


def convert(mat):
    from photon import _photon
    from photon.sync import materials as sync_materials, textures as sync_textures
    scene, reporter = RecordingScene(), RecordingReporter()
    textures = sync_textures.TextureTable(scene, reporter, _photon.TexturePixels)
    reporter.current = mat.name
    start = time.perf_counter()
    name, closures, _program, _aovs = sync_materials.convert_material(mat, reporter, textures)
    seconds = time.perf_counter() - start
    textures.release()
    return {"name": name, "closures": closures, "seconds": seconds,
            "warnings": reporter.warnings.get(mat.name, []), "textures": scene.textures}


def scene(mat, blend):
    sc = bpy.context.scene
    sc.photon.samples = 1
    builders.camera(location=(0, -3, 0), rotation=(1.5707963, 0, 0))
    builders.quad("Quad", (-1, 0, -1), (2, 0, 0), (0, 0, 2), mat)
    builders.light("Sun", 'SUN', 3.0, (0, -2, 2), rotation=(0.8, 0, 0))
    bpy.ops.wm.save_as_mainfile(filepath=blend)


def main(mode, kind, size, blend=None):
    builders.reset_scene(width=8, height=8)
    start = time.perf_counter()
    mat, expected = build(kind, size)
    print(f"node_graphs: built {mat.name} ({len(mat.node_tree.nodes)} nodes) in "
          f"{time.perf_counter() - start:.2f} s", file=sys.stderr)
    if mode == "scene":
        scene(mat, os.path.abspath(blend))
        return {"saved": blend}
    return {**convert(mat), **expected}


if __name__ == "__main__":
    harness.run(main)
