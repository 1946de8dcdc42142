"""No light through closed geometry with PHOTON_MAP (scene: scripts/light_leak.py, black world).

A point light sealed in a closed cube lifted 0.5 m off a floor must leave the floor and the
cube's outside black; a camera sealed in the cube with the light outside must see black. Photon
estimates once gathered photons and radiance records of the cube's inner faces at its outer
faces' edges, of the floor at the cube's inner bottom face and the reverse, lighting the floor
round the cube (floor mean 0.019, max 0.16 at 64 x 48) and the cube's inside (mean 0.047, max
0.28); with final_gather_rays = 0 the floor had mean 0.021 and the cube's edges glowed (max 4.3),
and the cube's inside had mean 0.024 (max 0.11). Each case renders in about 15 s."""

import json
import re

import pytest

# Every pixel is black when nothing leaks; a leak of a thousandth of the old one still fails.
MEAN_BOUND = 1e-5
MAX_BOUND = 1e-3


@pytest.mark.parametrize("final_gather_rays", [16, 0])
@pytest.mark.parametrize("case", ["sealed_light", "sealed_camera"])
def test_no_light_leaks_through_a_closed_cube(blender, case, final_gather_rays):
    settings = json.dumps({"final_gather_rays": final_gather_rays})
    result, proc = blender.run_script("light_leak.py",
                                      blender.out_dir / f"light_leak_fg{final_gather_rays}",
                                      case, settings, timeout=300)
    assert "exception" not in result, result.get("exception")
    assert "Photon: rendered frame" in proc.stdout, proc.log
    # The light's photons were traced and stored (on the cube's inside, or the floor and the
    # cube's outside): there is light right behind the walls.
    stored = re.search(r"photons: [\d,]+ global and [\d,]+ caustic emitted, ([\d,]+) and", proc.stdout)
    assert stored and int(stored.group(1).replace(",", "")) > 10000, proc.log
    report = f"{case}, final_gather_rays {final_gather_rays}: {result}"
    if case == "sealed_light":
        assert result["floor_pixels"] > 1000, report  # the floor fills much of the frame
        assert result["floor_mean"] < MEAN_BOUND, report
        assert result["floor_max"] < MAX_BOUND, report
    assert result["mean"] < MEAN_BOUND, report
    assert result["max"] < MAX_BOUND, report
