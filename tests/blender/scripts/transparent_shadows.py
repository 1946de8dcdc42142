"""A floor lit by an area light through a pane, rendered by Cycles and by Photon to EXR in the
folder given: light reaches the floor through the pane's Transparent share, which shadow rays
cross in both engines (and through its glass share, refracted: caustics). The camera, below the
pane, sees only the floor. Cases: a window as artists make one (Mix 0.8 of a sharp Glass and a
grey Transparent BSDF, on a 1 cm slab), the same material on a single sheet (the floor is then
"inside the glass": photons take the adjoint's 1 / eta^2 there), a tinted Transparent BSDF, and a
Principled BSDF at Alpha 0.4.
Args: out_dir, photon_samples, cycles_samples. Returns {case: {"cycles": path, "photon": path}}.
"""

import bpy

import builders
from harness import run
from principled_extras import render_both

RES = 48


def window(mat):
    tree = mat.node_tree
    glass = tree.nodes.new("ShaderNodeBsdfGlass")
    builders.set_sharp(glass)
    glass.inputs["IOR"].default_value = 1.45
    clear = tree.nodes.new("ShaderNodeBsdfTransparent")
    clear.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    mix = tree.nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.8
    tree.links.new(glass.outputs["BSDF"], mix.inputs[1])
    tree.links.new(clear.outputs["BSDF"], mix.inputs[2])
    return mix.outputs["Shader"]


def tinted(mat):
    clear = mat.node_tree.nodes.new("ShaderNodeBsdfTransparent")
    clear.inputs["Color"].default_value = (0.9, 0.5, 0.2, 1.0)
    return clear.outputs["BSDF"]


def alpha(mat):
    p = mat.node_tree.nodes.new("ShaderNodeBsdfPrincipled")
    p.inputs["Base Color"].default_value = (0.2, 0.6, 0.2, 1.0)
    p.inputs["Alpha"].default_value = 0.4
    return p.outputs["BSDF"]


CASES = {"window": window, "sheet": window, "tinted": tinted, "alpha": alpha}


def build(case):
    scene = builders.reset_scene(width=RES, height=RES)
    builders.quad("Floor", (-3, -3, 0), (6, 0, 0), (0, 6, 0),
                  builders.diffuse_material("Floor", (0.8, 0.8, 0.8)))
    mat = bpy.data.materials.new(case)
    mat.use_nodes = True
    tree = mat.node_tree
    for node in list(tree.nodes):
        if node.type != 'OUTPUT_MATERIAL':
            tree.nodes.remove(node)
    out = next(n for n in tree.nodes if n.type == 'OUTPUT_MATERIAL')
    tree.links.new(CASES[case](mat), out.inputs["Surface"])
    if case == "window":
        # Glass 1 cm thick, as windows are modelled.
        builders.box("Pane", (-2, -2, 0.99), (2, 2, 1.0), mat)
    else:
        builders.quad("Pane", (-2, -2, 1.0), (4, 0, 0), (0, 4, 0), mat)
    builders.light("Lamp", 'AREA', 300.0, (0.0, 0.3, 2.0), size=1.0)
    cam = builders.camera(location=(0.0, 0.0, 0.8), rotation=(0.0, 0.0, 0.0))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = 2.0
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.05, 0.05, 0.05,
                                                                                1.0)
    scene.view_settings.view_transform = 'Standard'
    return scene


def main(out_dir, photon_samples, cycles_samples):
    return {case: render_both(build(case), out_dir, case, photon_samples, cycles_samples)
            for case in CASES}


if __name__ == "__main__":
    run(main)
