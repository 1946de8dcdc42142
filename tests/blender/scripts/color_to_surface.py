"""A plane whose Material Output's Surface is fed by a Checker Texture's Color, seen from above
under a black world with no lights, rendered by the engine named in the arguments: Cycles
shows the checker as emission (its automatic conversion of a colour into a shader input).

Args: ENGINE OUT_EXR
"""

import bpy

import builders
import harness


def main(engine, out_path):
    scene = builders.reset_scene(engine=engine, width=48, height=48)
    mat = bpy.data.materials.new("ColorToSurface")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    checker = nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 3.0
    checker.inputs["Color1"].default_value = (0.9, 0.4, 0.1, 1.0)
    checker.inputs["Color2"].default_value = (0.1, 0.2, 0.6, 1.0)
    links.new(checker.outputs["Color"], nodes["Material Output"].inputs["Surface"])
    builders.quad("Plane", (-1, -1, 0), (2, 0, 0), (0, 2, 0), mat)
    builders.camera(location=(0.0, 0.0, 3.0), rotation=(0.0, 0.0, 0.0), lens=35.0)
    scene.cycles.samples = 16
    scene.cycles.use_denoising = False
    scene.cycles.pixel_filter_type = 'BOX'
    scene.photon.samples = 16
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.filepath = out_path
    bpy.ops.render.render(write_still=True)
    return {"written": out_path}


if __name__ == "__main__":
    harness.run(main)
