"""Photon's spectral settings in Blender: scene.photon.spectral / spectral_samples (generated
from the native schema), material.photon.abbe_number on the material's glass closures, and a
light's spectrum (light.photon, or a Blackbody node feeding its Emission colour). Reports the
RNA definitions, the closure dicts and add_light arguments the add-on makes, and what the native
scene accepts of them."""

import bpy

import builders
import harness


def rna(owner, name):
    p = owner.bl_rna.properties[name]
    info = {"type": p.type}
    if p.type == "ENUM":
        info.update(default=p.default, items=[i.identifier for i in p.enum_items])
    elif p.type == "BOOLEAN":
        info["default"] = p.default
    else:
        info.update(default=p.default, min=p.hard_min, max=p.hard_max)
    return info


class Reporter:
    def __init__(self):
        self.warnings = []

    def warning(self, message):
        self.warnings.append(message)


def glass_material(name, node, abbe):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    tree = mat.node_tree
    principled = tree.nodes["Principled BSDF"]
    if node != "ShaderNodeBsdfPrincipled":
        tree.nodes.remove(principled)
        shader = tree.nodes.new(node)
        out = next(n for n in tree.nodes if n.type == 'OUTPUT_MATERIAL')
        tree.links.new(shader.outputs[0], out.inputs["Surface"])
    else:
        builders.set_principled(principled, "Transmission", 1.0)
    mat.photon.abbe_number = abbe
    return mat


def main():
    from photon.sync import lights as sync_lights, materials as sync_materials
    from photon.sync import textures as sync_textures
    scene = bpy.context.scene
    result = {"rna": {
        "spectral": rna(scene.photon, "spectral"),
        "spectral_samples": rna(scene.photon, "spectral_samples"),
        "abbe_number": rna(bpy.types.Material.bl_rna.properties["photon"].fixed_type,
                           "abbe_number"),
    }}
    light_settings = bpy.types.Light.bl_rna.properties["photon"].fixed_type
    for name in ("spectrum", "temperature", "illuminant"):
        result["rna"][name] = rna(light_settings, name)

    reporter = Reporter()
    textures = sync_textures.TextureTable(None, reporter, None)
    closures = {}
    for name, node, abbe in (("Glass", "ShaderNodeBsdfGlass", 30.0),
                             ("Refraction", "ShaderNodeBsdfRefraction", 40.0),
                             ("Principled", "ShaderNodeBsdfPrincipled", 20.0),
                             ("Diffuse", "ShaderNodeBsdfDiffuse", 20.0),
                             ("PlainGlass", "ShaderNodeBsdfGlass", 0.0),
                             ("Absurd", "ShaderNodeBsdfGlass", 0.001)):
        _, found, _, _ = sync_materials.convert_material(glass_material(name, node, abbe),
                                                         reporter, textures)
        closures[name] = found
    result["closures"] = closures

    spectra = {}
    plain = bpy.data.lights.new("Plain", 'POINT')
    spectra["plain"] = sync_lights.light_spectrum(plain)
    named = bpy.data.lights.new("Fluorescent", 'AREA')
    named.photon.spectrum = 'ILLUMINANT'
    named.photon.illuminant = 'F11'
    spectra["illuminant"] = sync_lights.light_spectrum(named)
    noded = bpy.data.lights.new("Warm", 'SPOT')
    noded.use_nodes = True
    tree = noded.node_tree
    emission = next(n for n in tree.nodes if n.type == 'EMISSION')
    blackbody = tree.nodes.new("ShaderNodeBlackbody")
    blackbody.inputs["Temperature"].default_value = 2700.0
    tree.links.new(blackbody.outputs["Color"], emission.inputs["Color"])
    spectra["blackbody_node"] = sync_lights.light_spectrum(noded)
    noded.photon.spectrum = 'BLACKBODY'
    noded.photon.temperature = 9000.0
    spectra["blackbody_setting"] = sync_lights.light_spectrum(noded)
    result["spectra"] = spectra

    # The native scene takes what the add-on sends.
    from photon import _photon
    native = _photon.Scene()
    obj = bpy.data.objects.new("Warm", noded)
    args = sync_lights.light_arguments(_photon, obj, obj.matrix_world, reporter)
    result["light_arguments"] = {k: args[k] for k in ("spectrum", "temperature", "illuminant")}
    native.add_light(**args)
    native.add_material("Glass", closures["Glass"])
    result["native_abbe"] = {
        name: [c["abbe"] for c in _photon.describe_material(name, closures[name])["closures"]]
        for name in closures}
    # An Abbe number that reaches the native module by another way than the add-on's sync.
    result["native_abbe"]["raw_absurd"] = [c["abbe"] for c in _photon.describe_material(
        "raw", [dict(closures["Glass"][0], abbe=0.001)])["closures"]]
    result["warnings"] = reporter.warnings
    result["panels"] = [name for name in ("PHOTON_PT_spectral", "PHOTON_PT_material")
                        if hasattr(bpy.types, name)]
    return result


if __name__ == "__main__":
    harness.run(main)
