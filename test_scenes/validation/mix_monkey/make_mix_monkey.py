"""Two Suzannes whose colour comes from Blender 3.4's Mix node (data type Color) driven by a
Layer Weight: left MULTIPLY (Facing as factor), right OVERLAY (Fresnel as factor): scene
mix_monkey.

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \\
        -P test_scenes/validation/mix_monkey/make_mix_monkey.py
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import artist_kit as kit  # noqa: E402
import builders  # noqa: E402
import library  # noqa: E402

REFERENCE_SAMPLES = 1024


def mix_material(name, blend_type, weight_output, blend):
    mat, nodes, links, bsdf = kit.principled(name, Roughness=0.45)
    weight = nodes.new("ShaderNodeLayerWeight")
    weight.inputs["Blend"].default_value = blend
    checker = nodes.new("ShaderNodeTexChecker")   # some texture in the B colour
    checker.inputs["Scale"].default_value = 6.0
    checker.inputs["Color1"].default_value = (0.2, 0.5, 0.9, 1.0)
    checker.inputs["Color2"].default_value = (0.9, 0.8, 0.2, 1.0)
    mix = nodes.new("ShaderNodeMix")
    mix.data_type = 'RGBA'
    mix.blend_type = blend_type
    mix.clamp_result = False
    colour_in = [s for s in mix.inputs if s.type == 'RGBA']
    colour_in[0].default_value = (0.8, 0.45, 0.3, 1.0)
    links.new(weight.outputs[weight_output], mix.inputs["Factor"])
    links.new(checker.outputs["Color"], colour_in[1])
    links.new(next(s for s in mix.outputs if s.type == 'RGBA'), bsdf.inputs["Base Color"])
    return mat


def build():
    scene = kit.base_scene(samples=64)
    scene.photon.photons, scene.photon.final_gather_rays = 50000, 8
    grey, *_ = kit.principled("Floor", **{"Base Color": (0.5, 0.5, 0.5, 1.0), "Roughness": 0.8})
    kit.floor(grey, size=12.0)
    kit.monkey("MonkeyMultiply", (-0.7, 0.0, 0.55),
               mix_material("MixMultiply", 'MULTIPLY', "Facing", 0.4),
               rotation=kit.radians(-10, 0, 15))
    kit.monkey("MonkeyOverlay", (0.7, 0.0, 0.55),
               mix_material("MixOverlay", 'OVERLAY', "Fresnel", 0.5),
               rotation=kit.radians(-10, 0, -15))
    lamp = builders.light("Key", 'AREA', 300.0, (0.8, -2.0, 2.5), shape='SQUARE', size=1.0)
    builders.aim(lamp, (0.0, 0.0, 0.5))
    kit.camera_at((0.0, -3.8, 1.4), (0.0, 0.0, 0.5), lens=45.0)
    library.cycles_reference(scene, samples=REFERENCE_SAMPLES, max_bounces=8, caustics=False)
    return scene


scene = build()
kit.save(scene, "mix_monkey", kit.sidecar(
    scene, REFERENCE_SAMPLES,
    f"Two subdivided Suzannes coloured by the 3.4 Mix node (Color): left MULTIPLY with Layer "
    f"Weight Facing (blend 0.4), right OVERLAY with Layer Weight Fresnel (blend 0.5), a "
    f"constant colour and a Checker as A and B; Cycles reference {REFERENCE_SAMPLES} spp, "
    f"8 bounces. Image mean within 2%, each 4x4 tile within 5% "
    f"(tests/blender/test_validation_artist_scenes.py)."))
