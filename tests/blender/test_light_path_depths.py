"""Light Path depth outputs against Cycles, read through delta bounces: an emitter seen through
two Transparent panes (Transparent Depth 2, Ray Depth 0: Cycles leaves transparent bounces out)
and through a sharp glass slab (Ray and Transmission Depth 2, Glossy Depth from the Fresnel
paths reflected inside it)."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

PANES = (slice(6, 18), slice(4, 20))   # left half: the emitter behind two Transparent panes
SLAB = (slice(6, 18), slice(28, 44))   # right half: the emitter under the glass slab


@pytest.fixture(scope="module")
def renders(blender, tmp_path_factory):
    folder = tmp_path_factory.mktemp("light_path_depths")
    result, _ = blender.run_script("light_path_depths.py", folder, 256, timeout=300)
    assert "exception" not in result, result.get("exception")
    return result


def depths(paths, engine, region):
    """The region's mean of the three outputs the emitter shows (it shows depth / 4)."""
    return read_image(paths[engine])[..., :3][region].reshape(-1, 3).mean(axis=0) * 4.0


def test_transparent_panes_count_as_transparent_depth_not_ray_depth(renders):
    for engine in ("cycles", "photon"):
        ray_glossy_transmission = depths(renders["depth_glossy_transmission"], engine, PANES)
        transparent_diffuse = depths(renders["transparent_diffuse"], engine, PANES)
        assert np.allclose(ray_glossy_transmission, 0.0, atol=1e-3), (engine, ray_glossy_transmission)
        assert np.allclose(transparent_diffuse, [2.0, 0.0, 0.0], atol=1e-3), (engine, transparent_diffuse)


def test_glass_slab_depths_match_cycles(renders):
    ours = depths(renders["depth_glossy_transmission"], "photon", SLAB)
    theirs = depths(renders["depth_glossy_transmission"], "cycles", SLAB)
    print(f"slab (ray, glossy, transmission) depth x throughput: photon {np.round(ours, 4)} "
          f"cycles {np.round(theirs, 4)}")
    # Two refractions with Fresnel transmittance 0.96 each: 2 x 0.9216, plus the rare inner
    # reflections (Ray Depth 4, Glossy Depth 2).
    assert 1.80 < theirs[0] < 1.90 and 1.80 < theirs[2] < 1.90, theirs
    assert np.abs(ours[[0, 2]] - theirs[[0, 2]]).max() <= 0.02 * theirs[0], (ours, theirs)
    assert abs(ours[1] - theirs[1]) <= 0.003, (ours, theirs)
    transparent = depths(renders["transparent_diffuse"], "photon", SLAB)
    assert np.allclose(transparent, 0.0, atol=1e-3), transparent
