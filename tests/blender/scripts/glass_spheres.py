"""Glass spheres in the Principled-extras scene (orthographic camera, sun, grey world, 64
bounces), rendered by Cycles and by Photon to EXR in the folder given: the Principled glass at
Transmission Roughness 0 (rough and nearly smooth), tinted rough Principled glass, and the
Glass BSDF. Args: out_dir, photon_samples, cycles_samples. Returns {case: {"cycles": path,
"photon": path}}."""

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
        p.inputs["Specular Tint"].default_value = specular_tint
    return setup


def glass_bsdf(roughness, color):
    def setup(mat):
        tree = mat.node_tree
        tree.nodes.remove(principled(mat))
        glass = tree.nodes.new("ShaderNodeBsdfGlass")
        glass.distribution = 'GGX'
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
}


def main(out_dir, photon_samples, cycles_samples):
    return {name: render_both(build(name, setup), out_dir, name, photon_samples, cycles_samples)
            for name, setup in CASES.items()}


if __name__ == "__main__":
    run(main)
