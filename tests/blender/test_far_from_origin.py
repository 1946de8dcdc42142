"""Far from the origin: the same small scene (tests/blender/scripts/far_from_origin.py: floor,
wall, box, smooth ball, a Curves hair tuft, sun and point light) rendered at the origin and moved
1e5 m and 1e7 m away, camera moved along, gives the same image within noise and no
far-from-origin warning. Float32 resolves 1 m at 1e7 m: without rebasing the native scene
around a world origin offset chosen in double precision (addon/photon/sync/origin.py), the
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


@pytest.fixture(scope="module")
def sync_origin(blender):
    """The staged add-on's sync_origin module (numpy only, no bpy), loaded outside Blender."""
    import importlib.util
    path = blender.stage / "addons" / "photon" / "sync" / "origin.py"
    spec = importlib.util.spec_from_file_location("photon_sync_origin", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_origin_is_zero_near_the_origin_and_exact_far_from_it(sync_origin):
    zero = np.zeros(3)
    # Near the origin (centre within 8 extents) and without geometry: exactly zero.
    for lo, hi in [((-3, -3, 0), (3, 3, 3)), ((40, 40, 0), (46, 46, 3)), ((1e-7, 0, 0),
                                                                          (3e-7, 1e-7, 1e-7))]:
        assert np.array_equal(sync_origin.choose_origin(np.array(lo, float), np.array(hi, float)),
                              zero)
    assert np.array_equal(sync_origin.choose_origin(None, None), zero)
    assert np.array_equal(sync_origin.choose_origin(np.array([np.nan] * 3), np.ones(3)), zero)
    # 1e7 m out, a 9 m scene: a multiple of a power of two >= the extent, within half of it of
    # the centre, so float32 coordinates of the scene minus it are exact in float32.
    lo, hi = np.array([1e7 - 3.3, 1e7 - 3, 0.0]), np.array([1e7 + 3, 1e7 + 3, 3.0])
    origin = sync_origin.choose_origin(lo, hi)
    grid = 16.0
    assert np.array_equal(origin, np.round(origin / grid) * grid) and origin[2] == 0.0
    assert np.abs(0.5 * (lo + hi) - origin).max() <= grid / 2
    points = np.random.default_rng(0).uniform(lo, hi, (1000, 3)).astype(np.float32)
    rebased = points.astype(np.float64) - origin
    assert np.array_equal(rebased.astype(np.float32).astype(np.float64), rebased)
    # Matrices: translation moved, rotation untouched; origin 0 gives the float32 cast.
    matrix = np.identity(4)
    matrix[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
    matrix[:3, 3] = [1e7 + 1, 1e7 - 2, 1.5]
    moved = sync_origin.rebased_matrix(matrix, origin)
    assert moved.dtype == np.float32
    assert np.array_equal(moved[:3, :3], matrix[:3, :3].astype(np.float32))
    assert np.array_equal(moved[:3, 3].astype(np.float64), matrix[:3, 3] - origin)
    assert np.array_equal(sync_origin.rebased_matrix(matrix, zero), matrix.astype(np.float32))
