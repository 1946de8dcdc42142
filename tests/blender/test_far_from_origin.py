"""Far from the origin: the same small scene (tests/blender/scripts/far_from_origin.py: floor,
wall, box, smooth ball, a Curves hair tuft, sun and point light) rendered at the origin and moved
1e5 m and 1e7 m away, camera moved along, gives the same image within noise and no
far-from-origin warning. Float32 resolves 1 m at 1e7 m: without rebasing the native scene
around a world origin offset chosen in double precision (addon/photon/sync_origin.py), the
far renders band, lose the ball's shape and the hair, and Photon warns instead."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

# Same seed and sampler: only float rounding can make paths differ, so the means of the 64x64
# images agree far within 1% when positions keep their precision.
MEAN_TOLERANCE = 0.01
# Per pixel: the mean absolute difference as a share of the image mean (banding or a shifted
# shadow moves many pixels), and no pixel off by more than this share of the brightest one.
PIXEL_MEAN_TOLERANCE = 0.01
PIXEL_MAX_TOLERANCE = 0.1


def render(blender, tag, offset, mode="render"):
    result, proc = blender.run_script("far_from_origin.py", blender.out_dir / "far", tag,
                                      offset, mode, timeout=300)
    assert "exception" not in result, result.get("exception")
    assert result["finite"]
    assert "Photon" in proc.stdout  # Photon rendered it, not a built-in engine
    return result, proc


@pytest.fixture(scope="module")
def at_origin(blender):
    result, proc = render(blender, "origin", 0.0)
    assert result["mean"] > 0.05, result  # lit, not a black image
    assert "from the origin" not in proc.stdout, proc.stdout
    return result


@pytest.mark.parametrize("offset", [1e5, 1e7])
def test_scene_far_from_origin_renders_like_at_the_origin(blender, at_origin, offset):
    result, proc = render(blender, f"offset_{offset:g}", offset)
    near = read_image(at_origin["path"])[:, :, :3]
    far = read_image(result["path"])[:, :, :3]
    rel = abs(result["mean"] - at_origin["mean"]) / at_origin["mean"]
    diff = np.abs(far - near)
    pixel_mean = float(diff.mean()) / at_origin["mean"]
    pixel_max = float(diff.max()) / float(near.max())
    warned = [line for line in proc.stdout.splitlines()
              if line.startswith("Photon: warning:") and "from the origin" in line]
    print(f"offset {offset:g}: mean {result['mean']:.5f} vs {at_origin['mean']:.5f} "
          f"({rel:.3%}), mean |pixel difference| {pixel_mean:.3%} of the mean, worst pixel "
          f"{pixel_max:.3%} of the brightest, warned {bool(warned)}")
    assert not warned, warned
    assert rel < MEAN_TOLERANCE, (result["mean"], at_origin["mean"], result["path"])
    assert pixel_mean < PIXEL_MEAN_TOLERANCE, (pixel_mean, result["path"])
    assert pixel_max < PIXEL_MAX_TOLERANCE, (pixel_max, result["path"])


def test_bake_far_from_origin_matches_the_bake_at_the_origin(blender):
    """The lighting bake syncs the same rebased scene; its lightmap texel corners, computed in
    the add-on, are rebased the same way, so the baked colour attributes and lightmaps agree."""
    near, _ = render(blender, "origin", 0.0, "bake")
    far, proc = render(blender, "offset_1e7", 1e7, "bake")
    assert not [line for line in proc.stdout.splitlines()
                if line.startswith("Photon: warning:") and "from the origin" in line]
    near_arrays, far_arrays = np.load(near["path"]), np.load(far["path"])
    assert sorted(near_arrays.files) == sorted(far_arrays.files)
    for name in sorted(near_arrays.files):
        a, b = near_arrays[name], far_arrays[name]
        scale = max(float(np.abs(a).max()), 1e-6)
        worst = float(np.abs(a - b).max()) / scale
        print(f"bake {name}: mean {b.mean():.5f} vs {a.mean():.5f}, worst {worst:.3%}")
        assert a.mean() > 0.0, name
        assert abs(float(b.mean()) - float(a.mean())) <= MEAN_TOLERANCE * float(a.mean()), name
        assert worst < PIXEL_MAX_TOLERANCE, name
