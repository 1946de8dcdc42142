"""A floor under one refracting surface (tests/blender/scripts/open_refraction.py): Photon's
photon map, SPPM and VCM against that Blender's Cycles. Photons cross the sheet with the adjoint
BSDF's 1 / eta^2; without it the floor is eta^2 = 1.77 times as bright as Cycles'. Through a
rough sheet VCM weighs its techniques with the densities of both sides (2.2 times too bright
without). The floor's mean must agree within 5%. SPPM is left out of the rough case: its
visible points on the sheet converge slowly on the light behind it (docs/sppm.md)."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

TOLERANCE = 0.05
CASES = [("sharp", "PHOTON_MAP"), ("sharp", "SPPM"), ("sharp", "VCM"), ("rough", "PHOTON_MAP"),
         ("rough", "VCM")]


@pytest.fixture(scope="module")
def renders(blender, tmp_path_factory):
    folder = tmp_path_factory.mktemp("open_refraction")
    result, _ = blender.run_script("open_refraction.py", folder, 16, 512, timeout=900)
    assert "exception" not in result, result.get("exception")
    return result


@pytest.mark.parametrize("case,integrator", CASES)
def test_floor_under_water_matches_cycles(renders, case, integrator):
    theirs = read_image(renders[case]["cycles"])[..., :3].mean()
    ours = read_image(renders[case][integrator])[..., :3].mean()
    print(f"{case} {integrator:10s} photon {ours:.4f} cycles {theirs:.4f} "
          f"ratio {ours / theirs:.4f}")
    assert theirs > 0.05, theirs
    assert abs(ours / theirs - 1.0) <= TOLERANCE, (case, integrator, ours, theirs)
