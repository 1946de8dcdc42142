"""World node trees against Cycles: a Light Path "Is Camera Ray" mix of two Backgrounds (the
camera sees one, the floor is lit by the other) and an HDRI through a rotated Environment
Texture (the background the camera sees, and the floor it lights through the importance-sampled
environment light), also wired straight into the World Output without a Background node."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

SKY = (slice(0, 14), slice(None))      # rows above the horizon
FLOOR = (slice(34, 48), slice(None))   # rows of the floor near the camera


@pytest.fixture(scope="module")
def renders(blender, tmp_path_factory):
    folder = tmp_path_factory.mktemp("world_nodes")
    result, _ = blender.run_script("world_nodes.py", folder, 64, 256, timeout=600)
    assert "exception" not in result, result.get("exception")
    return result


def region_means(paths, region):
    ours = read_image(paths["photon"])[..., :3][region].reshape(-1, 3).mean(axis=0)
    theirs = read_image(paths["cycles"])[..., :3][region].reshape(-1, 3).mean(axis=0)
    return ours, theirs


def test_camera_rays_see_one_background_and_the_floor_is_lit_by_the_other(renders):
    sky, sky_cycles = region_means(renders["camera_trick"], SKY)
    assert np.allclose(sky, [0.1, 0.2, 0.9], atol=1e-3), sky
    assert np.allclose(sky, sky_cycles, atol=1e-3), (sky, sky_cycles)
    floor, floor_cycles = region_means(renders["camera_trick"], FLOOR)
    # Lit by the white branch: grey, not blue (a blue world would make blue dominate).
    assert abs(floor[2] - floor[0]) < 0.02 * floor[0], floor
    assert np.abs(floor - floor_cycles).max() <= 0.03 * floor_cycles.max(), (floor, floor_cycles)


@pytest.mark.parametrize("case", ["hdri", "hdri_direct"])
def test_hdri_background_and_lighting_match_cycles(renders, case):
    """hdri_direct: the Environment Texture's Color straight into the World Output, which
    Cycles renders as an emission of it (a Background of strength 1)."""
    sky, sky_cycles = region_means(renders[case], SKY)
    assert np.abs(sky - sky_cycles).max() <= 0.01 * sky_cycles.max(), (sky, sky_cycles)
    floor, floor_cycles = region_means(renders[case], FLOOR)
    assert np.abs(floor - floor_cycles).max() <= 0.03 * floor_cycles.max(), (floor, floor_cycles)
