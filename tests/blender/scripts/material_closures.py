"""Builds materials with node trees and reports the closure lists the add-on makes of them.
Args: FOLDER (for the image files it creates).

The native scene is a recorder: what reaches Scene.add_texture / add_material is exactly what the
add-on would send. Result: {material: {"closures", "warnings"}}, "textures": [add_texture
arguments], "images": {name: path of the file written for the test}."""

import os

import bpy
import numpy as np

import builders
import harness


class RecordingScene:
    def __init__(self):
        self.textures = []

    def add_texture(self, path, srgb=True, extension="REPEAT", interpolation="Linear",
                    alpha="KEEP", unassociate=False):
        self.textures.append({"path": path, "srgb": srgb, "extension": extension,
                              "interpolation": interpolation, "alpha": alpha,
                              "unassociate": unassociate})
        return len(self.textures) - 1

    def add_texture_pixels(self, pixels, name, srgb=True, extension="REPEAT",
                           interpolation="Linear", alpha="KEEP", unassociate=False):
        self.textures.append({"name": name, "width": pixels.width, "height": pixels.height,
                              "pixels": [float(v) for v in pixels.array], "srgb": srgb,
                              "extension": extension, "interpolation": interpolation,
                              "alpha": alpha, "unassociate": unassociate})
        return len(self.textures) - 1


class RecordingReporter:
    """Warnings grouped by the material being converted (`current`)."""

    def __init__(self):
        self.current = None
        self.warnings = {}

    def warning(self, message):
        found = self.warnings.setdefault(self.current, [])
        if message not in found:
            found.append(message)


def write_png(name, path, width, height, rgba):
    """A PNG on disk with known pixels (rgba: the same value everywhere, alpha varying by row)."""
    image = bpy.data.images.new(name, width, height, alpha=True)
    pixels = np.tile(np.array(rgba, dtype=np.float32), (height, width, 1))
    pixels[:, :, 3] = np.linspace(0.0, 1.0, height)[:, None]
    image.pixels.foreach_set(pixels.ravel())
    image.filepath_raw = path
    image.file_format = 'PNG'
    image.save()
    return image


def new_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    return mat, nodes, mat.node_tree.links, nodes["Principled BSDF"], nodes["Material Output"]


def image_node(nodes, image, **settings):
    node = nodes.new("ShaderNodeTexImage")
    node.image = image
    for key, value in settings.items():
        setattr(node, key, value)
    return node


def build(folder):
    builders.reset_scene()
    color_png = write_png("ColorPNG", os.path.join(folder, "color.png"), 8, 4,
                          (0.25, 0.5, 0.75, 1.0))
    normal_png = write_png("NormalPNG", os.path.join(folder, "normal.png"), 4, 4,
                           (0.5, 0.5, 1.0, 1.0))
    normal_png.colorspace_settings.name = 'Non-Color'

    # Principled metal, with Sheen and Subsurface set (subsurface falls back to diffuse: one warning).
    mat, nodes, links, bsdf, out = new_material("Metal")
    bsdf.inputs["Base Color"].default_value = (0.9, 0.6, 0.2, 1.0)
    bsdf.inputs["Metallic"].default_value = 1.0
    bsdf.inputs["Roughness"].default_value = 0.2
    builders.set_principled(bsdf, "Sheen", 0.3)
    builders.set_principled(bsdf, "Subsurface", 0.1)
    builders.set_principled(bsdf, "Clearcoat", 0.4)
    builders.set_principled(bsdf, "Clearcoat Roughness", 0.1)
    builders.set_principled(bsdf, "Emission", (1.0, 0.5, 0.0, 1.0))
    bsdf.inputs["Emission Strength"].default_value = 3.0

    # Mix(fac = image alpha, Diffuse(image colour), Glossy Beckmann).
    mat, nodes, links, bsdf, out = new_material("MixAlpha")
    nodes.remove(bsdf)
    tex = image_node(nodes, color_png, extension='CLIP', interpolation='Smart')
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = 'BECKMANN'
    glossy.inputs["Roughness"].default_value = 0.3
    mix = nodes.new("ShaderNodeMixShader")
    links.new(tex.outputs["Alpha"], mix.inputs["Fac"])
    links.new(tex.outputs["Color"], diffuse.inputs["Color"])
    links.new(diffuse.outputs[0], mix.inputs[1])
    links.new(glossy.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    uv = nodes.new("ShaderNodeUVMap")
    links.new(uv.outputs["UV"], tex.inputs["Vector"])

    # Add(Diffuse, Emission) through a reroute; the same image again, its Alpha unused.
    mat, nodes, links, bsdf, out = new_material("AddEmit")
    nodes.remove(bsdf)
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 5.0
    emission.inputs["Color"].default_value = (1.0, 0.9, 0.8, 1.0)
    add = nodes.new("ShaderNodeAddShader")
    reroute = nodes.new("NodeReroute")
    tex = image_node(nodes, color_png, extension='CLIP', interpolation='Smart')
    links.new(tex.outputs["Color"], diffuse.inputs["Color"])
    links.new(diffuse.outputs[0], add.inputs[0])
    links.new(emission.outputs[0], add.inputs[1])
    links.new(add.outputs[0], reroute.inputs[0])
    links.new(reroute.outputs[0], out.inputs["Surface"])

    # Constant mixes: fac 0 keeps only the first shader, 0.25 weights both.
    mat, nodes, links, bsdf, out = new_material("MixConst")
    nodes.remove(bsdf)
    outer = nodes.new("ShaderNodeMixShader")
    outer.inputs["Fac"].default_value = 0.25
    inner = nodes.new("ShaderNodeMixShader")
    inner.inputs["Fac"].default_value = 0.0
    glass = nodes.new("ShaderNodeBsdfGlass")
    builders.set_sharp(glass)
    glass.inputs["IOR"].default_value = 1.5
    transparent = nodes.new("ShaderNodeBsdfTransparent")
    translucent = nodes.new("ShaderNodeBsdfTranslucent")
    refraction = nodes.new("ShaderNodeBsdfRefraction")
    refraction.distribution = 'GGX'
    links.new(glass.outputs[0], inner.inputs[1])
    links.new(transparent.outputs[0], inner.inputs[2])
    links.new(inner.outputs[0], outer.inputs[1])
    add = nodes.new("ShaderNodeAddShader")
    links.new(translucent.outputs[0], add.inputs[0])
    links.new(refraction.outputs[0], add.inputs[1])
    links.new(add.outputs[0], outer.inputs[2])
    links.new(outer.outputs[0], out.inputs["Surface"])

    # A Glossy BSDF with Multiscatter GGX: Cycles 3.x's random walk, Cycles 4's albedo scaling.
    mat, nodes, links, bsdf, out = new_material("MultiGlossy")
    nodes.remove(bsdf)
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = 'MULTI_GGX'
    links.new(glossy.outputs[0], out.inputs["Surface"])

    # A Glossy BSDF with the Ashikhmin-Shirley distribution, which Photon renders as GGX.
    mat, nodes, links, bsdf, out = new_material("AshikhminGlossy")
    nodes.remove(bsdf)
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = 'ASHIKHMIN_SHIRLEY'
    glossy.inputs["Roughness"].default_value = 0.4
    links.new(glossy.outputs[0], out.inputs["Surface"])

    # A packed image (written from its packed bytes) and a generated one (rendered to EXR).
    packed = write_png("PackedPNG", os.path.join(folder, "packed_src.png"), 4, 2,
                       (0.1, 0.2, 0.3, 1.0))
    packed.pack()
    os.remove(os.path.join(folder, "packed_src.png"))
    generated = bpy.data.images.new("Generated", 4, 4)
    generated.generated_color = (0.2, 0.4, 0.6, 1.0)
    mat, nodes, links, bsdf, out = new_material("Packed")
    links.new(image_node(nodes, packed, interpolation='Closest').outputs["Color"],
              bsdf.inputs["Base Color"])
    links.new(image_node(nodes, generated).outputs["Color"], bsdf.inputs["Roughness"])

    # A missing file: warning naming material, node and path; grey for colour, own value for
    # the scalar.
    missing = bpy.data.images.load(os.path.join(folder, "color.png"))
    missing.name = "Gone"
    missing.filepath = "/nonexistent/photon/gone.png"
    mat, nodes, links, bsdf, out = new_material("Missing")
    bsdf.inputs["Metallic"].default_value = 0.35
    tex = image_node(nodes, missing)
    tex.name = "Gone Texture"
    links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(tex.outputs["Alpha"], bsdf.inputs["Metallic"])

    # Nodes the native library has no evaluation for: Wireframe into Base Color (the value of
    # the input it feeds), Ambient Occlusion into Emission (its Color input), behind it an
    # image through Mapping of the Generated coordinates (compiled into a shader program).
    mat, nodes, links, bsdf, out = new_material("Wave")
    bsdf.inputs["Base Color"].default_value = (0.1, 0.5, 0.2, 1.0)
    wire = nodes.new("ShaderNodeWireframe")
    wire.name = "Wavy"
    links.new(wire.outputs["Fac"], bsdf.inputs["Base Color"])
    hue = nodes.new("ShaderNodeAmbientOcclusion")
    hue.name = "Hue Fix"
    tex = image_node(nodes, color_png, extension='EXTEND', interpolation='Closest')
    mapping = nodes.new("ShaderNodeMapping")
    mapping.inputs["Scale"].default_value = (2.0, 2.0, 1.0)
    coords = nodes.new("ShaderNodeTexCoord")
    links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    links.new(tex.outputs["Color"], hue.inputs["Color"])
    links.new(hue.outputs["Color"], builders.principled_input(bsdf, "Emission"))

    # Unsupported shader: diffuse of its colour.
    builders.shader_material("Toon", "ShaderNodeBsdfToon", Color=(0.2, 0.4, 0.9, 1.0))

    # A node group: the Principled inside, its Base Color from the group's input.
    group = bpy.data.node_groups.new("PlasticGroup", 'ShaderNodeTree')
    builders.new_group_socket(group, 'INPUT', 'NodeSocketColor', "Tint")
    builders.new_group_socket(group, 'INPUT', 'NodeSocketFloat', "Rough")
    builders.new_group_socket(group, 'OUTPUT', 'NodeSocketShader', "Shader")
    g_in = group.nodes.new("NodeGroupInput")
    g_out = group.nodes.new("NodeGroupOutput")
    g_bsdf = group.nodes.new("ShaderNodeBsdfPrincipled")
    group.links.new(g_in.outputs["Tint"], g_bsdf.inputs["Base Color"])
    group.links.new(g_in.outputs["Rough"], g_bsdf.inputs["Roughness"])
    group.links.new(g_bsdf.outputs[0], g_out.inputs["Shader"])
    mat, nodes, links, bsdf, out = new_material("Grouped")
    nodes.remove(bsdf)
    gnode = nodes.new("ShaderNodeGroup")
    gnode.node_tree = group
    gnode.inputs["Tint"].default_value = (0.2, 0.3, 0.4, 1.0)
    value = nodes.new("ShaderNodeValue")
    value.outputs[0].default_value = 0.65
    links.new(value.outputs[0], gnode.inputs["Rough"])
    links.new(gnode.outputs["Shader"], out.inputs["Surface"])

    # Normal maps: tangent space with an image; object space (warned, ignored).
    for name, space in (("Bumpy", 'TANGENT'), ("ObjectNormals", 'OBJECT')):
        mat, nodes, links, bsdf, out = new_material(name)
        nmap = nodes.new("ShaderNodeNormalMap")
        nmap.space = space
        nmap.inputs["Strength"].default_value = 0.7
        links.new(image_node(nodes, normal_png).outputs["Color"], nmap.inputs["Color"])
        links.new(nmap.outputs["Normal"], bsdf.inputs["Normal"])
        rgb = nodes.new("ShaderNodeRGB")
        rgb.outputs[0].default_value = (0.05, 0.1, 0.15, 1.0)
        links.new(rgb.outputs[0], bsdf.inputs["Base Color"])

    # Absurd values: NaN roughness, huge emission strength, negative IOR.
    mat, nodes, links, bsdf, out = new_material("Absurd")
    bsdf.inputs["Roughness"].default_value = float("nan")
    bsdf.inputs["Emission Strength"].default_value = 1e30
    bsdf.inputs["IOR"].default_value = -3.0

    # A colour output straight into the Surface: Cycles' Emission of that colour; a value
    # output: white emission at that strength; a Mix Shader of a shader and a colour.
    mat, nodes, links, bsdf, out = new_material("ColorToSurface")
    checker = nodes.new("ShaderNodeTexChecker")
    links.new(checker.outputs["Color"], out.inputs["Surface"])
    mat, nodes, links, bsdf, out = new_material("ValueToSurface")
    value = nodes.new("ShaderNodeValue")
    value.outputs[0].default_value = 2.5
    links.new(value.outputs[0], out.inputs["Surface"])
    mat, nodes, links, bsdf, out = new_material("MixedWithColor")
    rgb = nodes.new("ShaderNodeRGB")
    rgb.outputs[0].default_value = (0.9, 0.3, 0.1, 1.0)
    mix = nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.25
    links.new(bsdf.outputs[0], mix.inputs[1])
    links.new(rgb.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])

    # No nodes: the viewport colour. Nothing connected: the viewport colour and a warning.
    mat = bpy.data.materials.new("NoNodes")
    mat.use_nodes = False
    mat.diffuse_color = (0.3, 0.2, 0.1, 1.0)
    mat, nodes, links, bsdf, out = new_material("Unconnected")
    links.remove(out.inputs["Surface"].links[0])
    mat.diffuse_color = (0.6, 0.5, 0.4, 1.0)


def main(folder):
    from photon.sync import materials as sync_materials, textures as sync_textures
    try:
        from photon import _photon
        pixels_type = getattr(_photon, "TexturePixels", None)
    except ImportError:
        pixels_type = None
    os.makedirs(folder, exist_ok=True)
    build(folder)
    scene = RecordingScene()
    reporter = RecordingReporter()
    textures = sync_textures.TextureTable(scene, reporter, pixels_type)
    result = {"materials": {}}
    for mat in bpy.data.materials:
        reporter.current = mat.name
        name, closures, program, _aovs = sync_materials.convert_material(mat, reporter,
                                                                         textures)
        result["materials"][name] = {"closures": closures, "program": program,
                                     "warnings": reporter.warnings.get(mat.name, [])}
    result["textures"] = scene.textures
    # The written files stay for the test to read; the test deletes the folder.
    result["temp_dir"] = textures.temp_dir
    return result


if __name__ == "__main__":
    harness.run(main)
