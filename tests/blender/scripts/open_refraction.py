"""A white floor under one refracting surface (a Refraction BSDF sheet of IOR 1.33, like the
surface of a pool), lit by a sun straight down, seen from above through the sheet; rendered by
Cycles and by Photon's photon map, SPPM and VCM to EXR in the folder given. Cycles' paths see
radiance unscaled across a refraction, so the floor gets the sun's irradiance over eta^2;
Photon's photons must carry the adjoint's 1 / eta^2 to agree. The sun is 20 degrees wide so that
Cycles' floor samples find it through the sheet. Then the same with a rough sheet (roughness
0.3), with Cycles, the photon map and VCM (whose techniques weigh each other through it).
Args: out_dir, photon_samples, cycles_samples.
Returns {"sharp": {"cycles": path, INTEGRATOR: path, ...}, "rough": {...}}.
"""

import math
import os

import bpy

import builders
from harness import run
from principled_extras import render

RES = 48
INTEGRATORS = {"sharp": ["PHOTON_MAP", "SPPM", "VCM"], "rough": ["PHOTON_MAP", "VCM"]}


def build(roughness):
    scene = builders.reset_scene(width=RES, height=RES)
    builders.quad("Floor", (-3, -3, 0), (6, 0, 0), (0, 6, 0),
                  builders.diffuse_material("Floor", (0.8, 0.8, 0.8)))
    water = builders.shader_material("Water", "ShaderNodeBsdfRefraction", IOR=1.33)
    node = next(n for n in water.node_tree.nodes if n.type == 'BSDF_REFRACTION')
    if roughness == 0.0:
        builders.set_sharp(node)
    else:
        node.inputs["Roughness"].default_value = roughness
    builders.quad("Water", (-3, -3, 1.0), (6, 0, 0), (0, 6, 0), water)
    builders.light("Sun", 'SUN', 2.0, (0.0, 0.0, 5.0), angle=math.radians(20.0))
    builders.camera(location=(0.0, 0.0, 3.0), rotation=(0.0, 0.0, 0.0), lens=80.0)
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    scene.view_settings.view_transform = 'Standard'
    return scene


def render_case(case, roughness, out_dir, photon_samples, cycles_samples):
    scene = build(roughness)
    scene.render.engine = 'CYCLES'
    scene.cycles.samples = int(cycles_samples)
    scene.cycles.use_denoising = False
    scene.cycles.blur_glossy = 0.0
    scene.cycles.sample_clamp_indirect = 0.0
    scene.cycles.pixel_filter_type = 'BOX'
    scene.cycles.seed = 1
    result = {"cycles": os.path.join(out_dir, f"{case}_cycles.exr")}
    render(scene, result["cycles"])
    scene.render.engine = 'PHOTON'
    scene.photon.samples = int(photon_samples)
    scene.photon.seed = 1
    for integrator in INTEGRATORS[case]:
        scene.photon.integrator = integrator
        result[integrator] = os.path.join(out_dir, f"{case}_{integrator.lower()}.exr")
        render(scene, result[integrator])
    return result


def main(out_dir, photon_samples, cycles_samples):
    return {case: render_case(case, roughness, out_dir, photon_samples, cycles_samples)
            for case, roughness in (("sharp", 0.0), ("rough", 0.3))}


if __name__ == "__main__":
    run(main)
