"""Procedural wood on a cube and marble on a sphere, built as artists build them: scene
wood_marble.

Wood: Object coordinates -> Mapping (stretched along the grain) -> Wave Texture (Rings,
distortion from its own noise) whose Fac is perturbed by a Noise Texture (Mix Add) -> ColorRamp
(early/late wood) -> Base Color, and a second ColorRamp of the same Fac -> Roughness.
Marble: Noise Texture (detail 8, distortion) -> ColorRamp (white, grey veins) -> Base Color.

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \\
        -P test_scenes/validation/wood_marble/make_wood_marble.py
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import artist_kit as kit  # noqa: E402
import builders  # noqa: E402
import library  # noqa: E402

REFERENCE_SAMPLES = 1024


def wood_material():
    mat, nodes, links, bsdf = kit.principled("Wood")
    coords = nodes.new("ShaderNodeTexCoord")
    mapping = nodes.new("ShaderNodeMapping")
    mapping.inputs["Scale"].default_value = (1.0, 1.0, 0.25)   # long grain along z
    mapping.inputs["Location"].default_value = (0.3, -0.2, 0.0)
    wave = nodes.new("ShaderNodeTexWave")
    wave.wave_type = 'RINGS'
    wave.rings_direction = 'Z'
    wave.wave_profile = 'SIN'
    wave.inputs["Scale"].default_value = 3.0
    wave.inputs["Distortion"].default_value = 4.0
    wave.inputs["Detail"].default_value = 2.0
    wave.inputs["Detail Scale"].default_value = 1.5
    noise = nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 12.0
    noise.inputs["Detail"].default_value = 4.0
    grain = nodes.new("ShaderNodeMix")
    grain.data_type = 'FLOAT'
    grain.inputs["Factor"].default_value = 0.25
    colour = kit.color_ramp(nodes, [(0.2, (0.32, 0.16, 0.06)), (0.55, (0.62, 0.38, 0.17)),
                                    (0.9, (0.8, 0.58, 0.32))])
    rough = kit.color_ramp(nodes, [(0.3, (0.25, 0.25, 0.25)), (0.8, (0.7, 0.7, 0.7))])
    links.new(coords.outputs["Object"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], wave.inputs["Vector"])
    links.new(mapping.outputs["Vector"], noise.inputs["Vector"])
    float_in = [s for s in grain.inputs if s.type == 'VALUE' and s.name in ("A", "B")]
    links.new(wave.outputs["Fac"], float_in[0])
    links.new(noise.outputs["Fac"], float_in[1])
    grain_out = next(s for s in grain.outputs if s.type == 'VALUE')
    links.new(grain_out, colour.inputs["Fac"])
    links.new(grain_out, rough.inputs["Fac"])
    links.new(colour.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(rough.outputs["Color"], bsdf.inputs["Roughness"])
    return mat


def marble_material():
    mat, nodes, links, bsdf = kit.principled("Marble", Roughness=0.15)
    coords = nodes.new("ShaderNodeTexCoord")
    noise = nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 3.0
    noise.inputs["Detail"].default_value = 8.0
    noise.inputs["Roughness"].default_value = 0.6
    noise.inputs["Distortion"].default_value = 2.5
    ramp = kit.color_ramp(nodes, [(0.35, (0.9, 0.88, 0.85)), (0.5, (0.35, 0.36, 0.4)),
                                  (0.56, (0.85, 0.84, 0.82))])
    links.new(coords.outputs["Object"], noise.inputs["Vector"])
    links.new(noise.outputs["Fac"], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], bsdf.inputs["Base Color"])
    return mat


def build():
    scene = kit.base_scene(samples=64)
    scene.photon.photons, scene.photon.final_gather_rays = 50000, 8
    grey, *_ = kit.principled("Floor", **{"Base Color": (0.45, 0.45, 0.45, 1.0),
                                          "Roughness": 0.8})
    kit.floor(grey, size=12.0)
    kit.cube("WoodCube", (-0.65, 0.1, 0.5), 1.0, wood_material(), rotation=kit.radians(0, 0, 25))
    kit.uv_sphere("MarbleSphere", (0.7, -0.1, 0.55), 0.55, marble_material())
    lamp = builders.light("Key", 'AREA', 300.0, (1.2, -1.8, 2.6), shape='SQUARE', size=1.0)
    builders.aim(lamp, (0.0, 0.0, 0.4))
    fill = builders.light("Fill", 'AREA', 80.0, (-2.0, -1.0, 1.5), shape='SQUARE', size=1.0)
    builders.aim(fill, (0.0, 0.0, 0.5))
    kit.camera_at((0.0, -4.2, 2.0), (0.0, 0.0, 0.5), lens=45.0)
    library.cycles_reference(scene, samples=REFERENCE_SAMPLES, max_bounces=8, caustics=False)
    return scene


scene = build()
kit.save(scene, "wood_marble", kit.sidecar(
    scene, REFERENCE_SAMPLES,
    f"Procedural wood on a cube (Mapping -> Wave Rings, distortion 4, mixed with Noise -> "
    f"ColorRamp Base Color, ColorRamp Roughness) and marble on a sphere (Noise detail 8, "
    f"distortion 2.5 -> ColorRamp), two area lights; Cycles reference {REFERENCE_SAMPLES} spp, "
    f"8 bounces. Image mean within 2%, each 4x4 tile within 5% "
    f"(tests/blender/test_validation_artist_scenes.py)."))
