"""Artist-style node setups against Cycles (test_scenes/validation/<name>/make_<name>.py): a
checker floor under each light type, bump and normal mapping, procedural wood and marble, and
the 3.4 Mix node driven by a Layer Weight. Each scene's image mean must be within 2% of the
stored Cycles reference and each of the sidecar's 4x4 tiles ('regions') within 5%."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
VALIDATION = REPO / "test_scenes" / "validation"
SCENES = ["checker_point", "checker_spot", "checker_area", "checker_sun", "checker_area_spread",
          "bump_normal", "wood_marble", "mix_monkey", "hdri_row"]
MEAN_TOLERANCE = 0.02
REGION_TOLERANCE = 0.05


def region_errors(image, reference, regions):
    """{name: (relative error per channel, ours, theirs)} for rectangles [x0, y0, x1, y1].

    A channel is compared on the scale of the tile's brightest reference channel (at least a
    fifth of it) and of the whole image (at least a tenth of its mean), so 5% means 5% of what
    is seen there, not of a near-black value."""
    floor = 0.1 * reference.mean()
    out = {}
    for name, (x0, y0, x1, y1) in regions.items():
        ours = image[y0:y1, x0:x1].reshape(-1, 3).mean(axis=0)
        theirs = reference[y0:y1, x0:x1].reshape(-1, 3).mean(axis=0)
        scale = np.maximum(np.maximum(theirs, 0.2 * theirs.max()), floor)
        out[name] = ((ours - theirs) / scale, ours, theirs)
    return out


def test_regions_tile_the_image():
    for name in SCENES:
        sidecar = json.loads((VALIDATION / f"{name}.json").read_text())
        assert sidecar["reference_engine"] == "CYCLES"
        assert sidecar["thresholds"]["mean_diff"] <= MEAN_TOLERANCE
        height, width = read_image(VALIDATION / f"{name}.exr").shape[:2]
        covered = np.zeros((height, width), dtype=int)
        for x0, y0, x1, y1 in sidecar["regions"].values():
            covered[y0:y1, x0:x1] += 1
        assert (covered == 1).all(), name


@pytest.mark.parametrize("name", SCENES)
def test_scene_matches_cycles(blender, tmp_path, name):
    blend = VALIDATION / f"{name}.blend"
    proc = blender.run([str(blend), "-E", "PHOTON", "-o", str(tmp_path / f"{name}_####"),
                        "-F", "OPEN_EXR", "-x", "1", "-f", "1"], timeout=600)
    assert "Photon: rendered frame" in proc.stdout, proc.log
    assert "not supported" not in proc.stdout, proc.log
    image = read_image(tmp_path / f"{name}_0001.exr")[..., :3].astype(np.float64)
    reference = read_image(blender.reference(blend.with_suffix(".exr")))[..., :3]
    reference = reference.astype(np.float64)
    assert image.shape == reference.shape
    mean_error = abs(image.mean() - reference.mean()) / reference.mean()
    regions = json.loads(blend.with_suffix(".json").read_text())["regions"]
    errors = region_errors(image, reference, regions)
    report = [f"image mean photon {image.mean():.5f} cycles {reference.mean():.5f} "
              f"({mean_error:+.2%})"]
    report += [f"{key:9s} photon {np.round(ours, 4)} cycles {np.round(theirs, 4)} "
               f"rel {np.round(rel, 3)}" for key, (rel, ours, theirs) in errors.items()]
    print("\n".join(report))
    bad = [key for key, (rel, _, _) in errors.items() if np.abs(rel).max() > REGION_TOLERANCE]
    assert mean_error <= MEAN_TOLERANCE and not bad, \
        f"{name}: tiles off by more than 5%: {bad}\n" + "\n".join(report)
