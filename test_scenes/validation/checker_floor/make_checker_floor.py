"""Checker floor under each light type: five scenes checker_point, checker_spot, checker_area,
checker_sun and checker_area_spread (an area light with a 40 degree spread). The floor is the
way artists texture one: UV -> Mapping (scale) -> Checker Texture -> Principled Base Color; a
plain Principled sphere casts a shadow on it.

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \\
        -P test_scenes/validation/checker_floor/make_checker_floor.py [-- CASE ...]
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import artist_kit as kit  # noqa: E402
import builders  # noqa: E402
import library  # noqa: E402

REFERENCE_SAMPLES = 1024

# name -> (type, power in W (sun: W/m^2), location, settings)
LIGHTS = {
    "point": ('POINT', 250.0, (1.2, -1.0, 2.2), {"shadow_soft_size": 0.2}),
    "spot": ('SPOT', 600.0, (1.0, -1.8, 2.8), {"spot_size": math.radians(60),
                                              "spot_blend": 0.3, "shadow_soft_size": 0.1}),
    "area": ('AREA', 300.0, (0.5, -1.0, 2.4), {"shape": 'RECTANGLE', "size": 1.2,
                                              "size_y": 0.5}),
    "sun": ('SUN', 3.0, (0.0, 0.0, 5.0), {"angle": math.radians(5)}),
    # A soft box: the area light with a 40 degree spread, a pool of light on the floor.
    "area_spread": ('AREA', 300.0, (0.5, -1.0, 2.4), {"shape": 'RECTANGLE', "size": 1.2,
                                                     "size_y": 0.5,
                                                     "spread": math.radians(40)}),
}


def checker_floor_material():
    mat, nodes, links, bsdf = kit.principled("CheckerFloor", Roughness=0.6)
    coords = nodes.new("ShaderNodeTexCoord")
    mapping = nodes.new("ShaderNodeMapping")
    mapping.inputs["Scale"].default_value = (12.0, 12.0, 1.0)
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(20))
    checker = nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 2.0
    checker.inputs["Color1"].default_value = (0.8, 0.75, 0.65, 1.0)
    checker.inputs["Color2"].default_value = (0.08, 0.12, 0.3, 1.0)
    links.new(coords.outputs["UV"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], checker.inputs["Vector"])
    links.new(checker.outputs["Color"], bsdf.inputs["Base Color"])
    return mat


def build(case):
    scene = kit.base_scene(samples=64)
    photon = scene.photon
    photon.photons, photon.final_gather_rays = 50000, 8
    kit.floor(checker_floor_material(), size=12.0)
    ball, *_ = kit.principled("Ball", **{"Base Color": (0.7, 0.25, 0.1, 1.0), "Roughness": 0.4})
    kit.uv_sphere("Ball", (-0.3, 0.3, 0.5), 0.5, ball)
    light_type, power, location, settings = LIGHTS[case]
    lamp = builders.light(f"Light_{case}", light_type, power, location, **settings)
    if light_type == 'SUN':
        lamp.rotation_euler = kit.radians(40, 0, 35)
    else:
        builders.aim(lamp, (0.0, 0.0, 0.0))
    kit.camera_at((0.0, -4.5, 3.0), (0.0, 0.2, 0.2))
    if case == "area_spread":
        # A dim grey world as fill, so the floor outside the soft box's pool is not black.
        scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (
            0.2, 0.2, 0.2, 1.0)
    # The soft box's narrow beam on the glossy ball throws a caustic onto the near floor that
    # Photon renders; Cycles with caustics off leaves those tiles 17-28% darker.
    library.cycles_reference(scene, samples=REFERENCE_SAMPLES, max_bounces=8,
                             caustics=case == "area_spread")
    return scene


# Cases named after "--" on the command line, or all of them.
for case in sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else LIGHTS:
    scene = build(case)
    sidecar = kit.sidecar(
        scene, REFERENCE_SAMPLES,
        f"Checker floor (UV -> Mapping scale 12, rotation 20 deg -> Checker scale 2 -> Principled "
        f"Base Color, roughness 0.6) and a Principled ball under one {case} light; Cycles "
        f"reference {REFERENCE_SAMPLES} spp, 8 bounces. Image mean within 2% of Cycles', each "
        f"of the 4x4 tiles ('regions') within 5% (tests/blender/test_validation_artist_scenes.py).")
    if case == "area_spread":
        # The pool of light is 20x the image mean: the checker's edges inside it, noisy at
        # Photon's 64 samples, alone make a relative RMSE of 0.10 while every tile is within
        # 2.5% of Cycles; the dim caustic-lit near floor differs per pixel by noise.
        sidecar["thresholds"].update(rel_rmse=0.15, pixel_fraction=0.1)
        sidecar["description"] += (" The soft box's pool is 20x the image mean, so per-pixel "
                                   "bounds allow the noise of its checker edges.")
    kit.save(scene, f"checker_{case}", sidecar)
