"""Glass spheres in the Principled-extras scene (orthographic camera, sun, grey world, 64
bounces), rendered by Cycles and by Photon to EXR in the folder given: the Principled glass at
Transmission Roughness 0 (rough and nearly smooth), tinted rough Principled glass, and the
Glass BSDF. Args: out_dir, photon_samples, cycles_samples. Returns {case: {"cycles": path,
"photon": path}}."""

import bpy

import builders
from harness import run
from principled_extras import build, principled, render_both


def principled_glass(roughness, transmission_roughness=0.0, color=(1.0, 1.0, 1.0),
                     specular_tint=0.0):
    def setup(mat):
        p = principled(mat)
        p.inputs["Base Color"].default_value = (*color, 1.0)
        builders.set_principled(p, "Transmission", 1.0)
        p.inputs["Roughness"].default_value = roughness
        builders.set_principled(p, "Transmission Roughness", transmission_roughness)
        tint = p.inputs["Specular Tint"]
        if tint.type == 'RGBA':
            # Principled v2's colour, as Blender 4.0 converts v1's factor: mix(white, base, t).
            tint.default_value = (*(1.0 - specular_tint + specular_tint * c for c in color), 1.0)
        else:
            tint.default_value = specular_tint
    return setup


def glass_bsdf(roughness, color, distribution='GGX', node="ShaderNodeBsdfGlass"):
    def setup(mat):
        tree = mat.node_tree
        tree.nodes.remove(principled(mat))
        glass = tree.nodes.new(node)
        glass.distribution = distribution
        glass.inputs["Color"].default_value = (*color, 1.0)
        glass.inputs["Roughness"].default_value = roughness
        glass.inputs["IOR"].default_value = 1.45
        out = next(n for n in tree.nodes if n.type == 'OUTPUT_MATERIAL')
        tree.links.new(glass.outputs["BSDF"], out.inputs["Surface"])
    return setup


CASES = {
    "principled_rough": principled_glass(0.3),
    "principled_nearly_smooth": principled_glass(0.1),
    "principled_tinted": principled_glass(0.2, 0.3, (0.9, 0.5, 0.2), 0.5),
    "glass_bsdf_rough": glass_bsdf(0.3, (0.8, 0.9, 1.0)),
    "glass_bsdf_multiscatter": glass_bsdf(0.5, (0.9, 0.8, 0.6), 'MULTI_GGX'),
    "refraction_bsdf_rough": glass_bsdf(0.3, (0.7, 0.9, 0.8), node="ShaderNodeBsdfRefraction"),
    "glass_bsdf_beckmann": glass_bsdf(0.3, (0.8, 0.9, 1.0), 'BECKMANN'),
    "refraction_bsdf_beckmann": glass_bsdf(0.3, (0.7, 0.9, 0.8), 'BECKMANN',
                                           node="ShaderNodeBsdfRefraction"),
}
# Cycles 3.4's Multiscatter GGX glass is a random walk over microfacets that Photon renders as
# single-scattering GGX (with a warning); Blender 4's is albedo scaling, which it renders.
SKIPPED_BEFORE_4 = {"glass_bsdf_multiscatter": "Multiscatter GGX glass is Cycles 4's"}


def main(out_dir, photon_samples, cycles_samples):
    result = {"skipped": {}}
    for name, setup in CASES.items():
        if bpy.app.version < (4, 0, 0) and name in SKIPPED_BEFORE_4:
            result["skipped"][name] = SKIPPED_BEFORE_4[name]
            continue
        result[name] = render_both(build(name, setup), out_dir, name, photon_samples,
                                   cycles_samples)
    return result


if __name__ == "__main__":
    run(main)
