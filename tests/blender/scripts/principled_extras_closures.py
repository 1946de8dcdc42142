"""A Principled BSDF with a Bump node on its Clearcoat Normal and an Anisotropic BSDF with a
linked Tangent, converted by the add-on: their closure dicts, program size and warnings.
Args: none besides the result path."""

import bpy

import builders
import harness
from material_closures import RecordingReporter, RecordingScene


def build():
    coat = bpy.data.materials.new("Coat")
    coat.use_nodes = True
    tree = coat.node_tree
    p = tree.nodes["Principled BSDF"]
    builders.set_principled(p, "Clearcoat", 1.0)
    bump = tree.nodes.new("ShaderNodeBump")
    noise = tree.nodes.new("ShaderNodeTexNoise")
    tree.links.new(noise.outputs["Fac"], bump.inputs["Height"])
    tree.links.new(bump.outputs["Normal"], builders.principled_input(p, "Clearcoat Normal"))

    brushed = bpy.data.materials.new("Brushed")
    brushed.use_nodes = True
    tree = brushed.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    aniso = tree.nodes.new("ShaderNodeBsdfAnisotropic")
    aniso.inputs["Anisotropy"].default_value = -0.4
    aniso.inputs["Rotation"].default_value = 0.2
    tangent = tree.nodes.new("ShaderNodeTangent")
    tree.links.new(tangent.outputs["Tangent"], aniso.inputs["Tangent"])
    out = tree.nodes["Material Output"]
    tree.links.new(aniso.outputs["BSDF"], out.inputs["Surface"])


def main():
    from photon.sync import materials as sync_materials, textures as sync_textures
    build()
    scene = RecordingScene()
    reporter = RecordingReporter()
    textures = sync_textures.TextureTable(scene, reporter, None)
    result = {}
    for mat in bpy.data.materials:
        reporter.current = mat.name
        name, closures, program, _aovs = sync_materials.convert_material(mat, reporter,
                                                                         textures)
        result[name] = {"closures": closures, "warnings": reporter.warnings.get(mat.name, []),
                        "program": program is not None}
    return result


if __name__ == "__main__":
    harness.run(main)
