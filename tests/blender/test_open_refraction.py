"""A floor under one refracting surface (tests/blender/scripts/open_refraction.py): Photon's
photon map, SPPM and VCM against that Blender's Cycles. Photons cross the sheet with the adjoint
BSDF's 1 / eta^2; without it the floor is eta^2 = 1.77 times as bright as Cycles'. The floor's
mean must agree within 5%."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

TOLERANCE = 0.05
INTEGRATORS = ["PHOTON_MAP", "SPPM", "VCM"]


@pytest.fixture(scope="module")
def renders(blender, tmp_path_factory):
    folder = tmp_path_factory.mktemp("open_refraction")
    result, _ = blender.run_script("open_refraction.py", folder, 16, 512, timeout=900)
    assert "exception" not in result, result.get("exception")
    return result


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_floor_under_water_matches_cycles(renders, integrator):
    theirs = read_image(renders["cycles"])[..., :3].mean()
    ours = read_image(renders[integrator])[..., :3].mean()
    print(f"{integrator:10s} photon {ours:.4f} cycles {theirs:.4f} ratio {ours / theirs:.4f}")
    assert theirs > 0.05, theirs
    assert abs(ours / theirs - 1.0) <= TOLERANCE, (integrator, ours, theirs)
