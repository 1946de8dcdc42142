"""Photon's lights mean the same watts as Cycles': a diffuse plane lit by each light type, direct
light only, has the same mean brightness in both engines (within 2%)."""

import pytest

CASES = ["point", "point_radius", "spot", "sun", "area_square", "area_rectangle", "area_disk",
         "area_ellipse", "point_unnormalized", "spot_temperature", "sun_unnormalized",
         "area_unnormalized"]


@pytest.mark.parametrize("case", CASES)
def test_light_units_match_cycles(blender, case):
    result, proc = blender.run_script("units_scene.py", case, blender.out_dir)
    assert "exception" not in result, result.get("exception")
    if "skipped" in result:
        pytest.skip(result["skipped"])
    assert "Photon: rendered frame" in proc.stdout, "Photon did not render"
    for channel, (photon, cycles) in enumerate(zip(result["photon"], result["cycles"])):
        assert cycles > 1e-3, f"Cycles image is black in channel {channel}"
        assert photon == pytest.approx(cycles, rel=0.02), (case, channel, result)
