"""Light through a pane that lets part of it straight through (a window made as Mix(Glass,
Transparent), on a slab and on a single sheet, a tinted Transparent BSDF, Principled Alpha)
against that Blender's Cycles (tests/blender/scripts/transparent_shadows.py): shadow rays cross
the pane's Transparent share in both engines, and the light is counted once. The floor's mean colour must agree within 2% of
its brightest channel."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

TOLERANCE = 0.02
CASES = ["window", "sheet", "tinted", "alpha"]


@pytest.fixture(scope="module")
def renders(blender, tmp_path_factory):
    folder = tmp_path_factory.mktemp("transparent_shadows")
    result, _ = blender.run_script("transparent_shadows.py", folder, 64, 512, timeout=900)
    assert "exception" not in result, result.get("exception")
    return result


@pytest.mark.parametrize("case", CASES)
def test_floor_through_pane_matches_cycles(renders, case):
    paths = renders[case]
    ours = read_image(paths["photon"])[..., :3].reshape(-1, 3).mean(axis=0)
    theirs = read_image(paths["cycles"])[..., :3].reshape(-1, 3).mean(axis=0)
    rel = (ours - theirs) / max(theirs.max(), 1e-6)
    print(f"{case:8s} photon {np.round(ours, 4)} cycles {np.round(theirs, 4)} rel {np.round(rel, 4)}")
    assert theirs.max() > 0.05, (case, theirs)
    assert np.abs(rel).max() <= TOLERANCE, (case, ours, theirs, rel)
