"""Holdouts and shadow catchers (tests/blender/scripts/holdout_and_shadow_catcher.py), against
what Cycles renders for the same scenes.

Holdout: a sphere in front of a lit wall, held out by a Holdout node, by Object > Visibility >
Holdout, or by a view-layer collection marked Holdout, must leave a hole (alpha 0, colour 0)
while the wall beside it stays opaque and lit; a Mix(0.5, Diffuse, Holdout) sphere is half
transparent. Before holdouts were supported the sphere rendered opaque (alpha 1, the Holdout
node as a white diffuse with an "is not supported" warning).

Shadow catcher: a floor marked as shadow catcher under a sun-lit sphere must vanish except for
the sphere's shadow (Film > Transparent: alpha ~0.9 in the shadow, ~0 elsewhere, the sphere
opaque; opaque film: the world shows through, darkened in the shadow). Before, the floor
rendered as an ordinary grey surface with alpha 1 everywhere.
"""

import pytest

SCRIPT = "holdout_and_shadow_catcher.py"


def _render(blender, case, integrator="PHOTON_MAP", engines="photon"):
    result, proc = blender.run_script(SCRIPT, blender.out_dir / "holdout", case, engines,
                                      integrator, timeout=600)
    assert "exception" not in result, result.get("exception")
    assert "Photon: rendered frame" in proc.stdout, proc.log
    assert "not supported" not in proc.stdout, proc.log
    for engine in result.values():
        assert engine["finite"], result
    return result


@pytest.mark.parametrize("case, integrator", [
    ("holdout_node", "PHOTON_MAP"),
    ("holdout_node_opaque", "PHOTON_MAP"),  # a holdout is transparent without Film > Transparent
    ("holdout_object", "PHOTON_MAP"),
    ("holdout_object", "RAY_TRACE"),
    ("holdout_object", "RADIOSITY"),
    ("holdout_collection", "PHOTON_MAP"),
])
def test_holdout_sphere_leaves_a_hole_in_the_wall(blender, case, integrator):
    photon = _render(blender, case, integrator)["photon"]
    report = str(photon)
    assert photon["sphere"]["alpha"] < 0.02, report
    assert max(photon["sphere"]["rgb"]) < 0.02, report
    for side in ("wall_left", "wall_right"):
        assert photon[side]["alpha"] > 0.99, report
        assert min(photon[side]["rgb"]) > 0.3, report  # the wall is lit, not a hole


def test_half_holdout_matches_cycles(blender):
    result = _render(blender, "holdout_mix", engines="photon,cycles")
    photon, cycles = result["photon"], result["cycles"]
    report = f"photon {photon}\ncycles {cycles}"
    assert cycles["sphere"]["alpha"] == pytest.approx(0.5, abs=0.02), report  # the scene is right
    assert photon["sphere"]["alpha"] == pytest.approx(cycles["sphere"]["alpha"], abs=0.03), report
    assert photon["sphere"]["rgb"][0] == pytest.approx(cycles["sphere"]["rgb"][0], rel=0.08), report
    assert photon["wall_left"]["alpha"] > 0.99, report


@pytest.mark.parametrize("integrator", ["PHOTON_MAP", "RAY_TRACE", "RADIOSITY"])
def test_shadow_catcher_keeps_only_the_shadow_in_alpha(blender, integrator):
    engines = "photon,cycles" if integrator == "PHOTON_MAP" else "photon"
    result = _render(blender, "catcher", integrator, engines)
    photon = result["photon"]
    report = str(result)
    if "cycles" in result:
        cycles = result["cycles"]
        assert cycles["shadow"]["alpha"] > 0.8 and cycles["away"]["alpha"] < 0.05, report
        # Cycles also counts the sphere's indirect light into its ratio; Photon direct light only.
        assert photon["shadow"]["alpha"] == pytest.approx(cycles["shadow"]["alpha"], abs=0.08), \
            report
    assert photon["shadow"]["alpha"] > 0.85, report
    assert photon["away"]["alpha"] < 0.02, report  # the floor itself is transparent
    assert max(photon["away"]["rgb"]) < 0.01, report
    assert photon["sphere"]["alpha"] > 0.99, report  # the sphere is drawn as usual
    assert photon["sphere"]["rgb"][0] > 0.3, report


def test_shadow_catcher_over_the_world_without_transparent_film(blender):
    result = _render(blender, "catcher_opaque", engines="photon,cycles")
    photon, cycles = result["photon"], result["cycles"]
    report = f"photon {photon}\ncycles {cycles}"
    world = (0.06, 0.09, 0.15)  # the world's colour x strength, seen through the catcher
    for region in ("sphere", "shadow", "away"):
        assert photon[region]["alpha"] > 0.99, report
    for c in range(3):
        assert photon["away"]["rgb"][c] == pytest.approx(world[c], rel=0.05), report
        assert photon["away"]["rgb"][c] == pytest.approx(cycles["away"]["rgb"][c], rel=0.05), \
            report
    # In the shadow the world is darkened (blue: least touched by the red sphere's bounce light,
    # which Cycles adds and Photon does not).
    assert photon["shadow"]["rgb"][2] < 0.3 * photon["away"]["rgb"][2], report
    assert cycles["shadow"]["rgb"][2] < 0.3 * cycles["away"]["rgb"][2], report
