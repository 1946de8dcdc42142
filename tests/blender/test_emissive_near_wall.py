"""A small emissive sphere mesh (no lights) almost touching a wall: Photon against a Cycles
render of the same scene made in the test (64 x 48 pixels). The image means and the means of
all lit pixels (the sphere's own left out) agree within 4%,
the wall round the sphere within 6% (both renders are noisy there), and that wall is far
brighter than the wall beside it. Shadow rays that ended inside the emitter's own surface once
left a dark halo there (near region 46% low, mean 22% low)."""

import pytest


@pytest.mark.parametrize("integrator", ["PHOTON_MAP", "RAY_TRACE"])
def test_emissive_sphere_lights_the_wall_like_cycles(blender, integrator):
    # RAY_TRACE has no indirect light: compared with Cycles at 0 bounces.
    result, proc = blender.run_script("emissive_near_wall.py", blender.out_dir / integrator.lower(),
                                      "photon,cycles", 256, "", integrator,
                                      *(["0"] if integrator == "RAY_TRACE" else []),
                                      timeout=600)
    assert "exception" not in result, result.get("exception")
    assert "Photon: rendered frame" in proc.stdout, proc.log
    photon, cycles = result["photon"], result["cycles"]
    report = f"photon {photon}\ncycles {cycles}"
    assert cycles["near"] > 5 * cycles["far"], report  # the scene is what it should be
    assert 10 <= photon["sphere_pixels"] <= 100, report
    assert sum(photon["mean"]) == pytest.approx(sum(cycles["mean"]), rel=0.04), report
    assert photon["wall"] == pytest.approx(cycles["wall"], rel=0.04), report
    assert photon["near"] == pytest.approx(cycles["near"], rel=0.06), report
    assert photon["near"] > 5 * photon["far"], report
