"""IES Texture nodes on lamps against the same Blender's Cycles: a turned point lamp whose
profile is a text datablock, a spot whose profile file (one quadrant, mirrored) is scaled by a
Math Multiply node, an area light (profile read along its axis) and a point lamp whose file is
missing (Cycles renders 100 in every direction; Photon too, and says so). The floor's mean
within 2% of Cycles', and each of its 4 x 4 blocks within 3%, so a profile turned the wrong way
fails, and so does one read with another Blender's interpolation (Cycles changed how it treats
a table's edges in 4.1 and 5.1, and an area light's direction in 4.0). About 10 s."""

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

PHOTON_SAMPLES = 16
CYCLES_SAMPLES = 256


def block_means(image, blocks=4):
    h, w = image.shape[:2]
    luminance = image[..., :3].mean(axis=2)
    return luminance.reshape(blocks, h // blocks, blocks, w // blocks).mean(axis=(1, 3))


def test_ies_lamps_match_cycles(blender, tmp_path):
    result, proc = blender.run_script("ies_scene.py", tmp_path, PHOTON_SAMPLES, CYCLES_SAMPLES,
                                      timeout=600)
    assert "exception" not in result, result["exception"] + proc.log
    assert "Photon: rendered frame" in proc.stdout, proc.log
    cycles = read_image(result["cycles"])[..., :3]
    photon = read_image(result["photon"])[..., :3]
    cb, pb = block_means(cycles), block_means(photon)
    print(json.dumps({"blender": result["version"], "cycles_mean": float(cycles.mean()),
                      "photon_mean": float(photon.mean()),
                      "block_ratio": np.round(pb / np.maximum(cb, 1e-9), 4).tolist()}))
    assert abs(photon.mean() / cycles.mean() - 1.0) < 0.02
    lit = cb > 0.05 * cb.max()
    assert lit.sum() >= 8
    ratio = pb[lit] / cb[lit]
    assert np.all(np.abs(ratio - 1.0) < 0.03), (pb / np.maximum(cb, 1e-9)).round(3)
    # The missing file is named, and what Photon renders for it said.
    assert "'ies_missing': its IES profile (" in proc.log
    assert "missing.ies: No such file or directory) could not be read; rendered as Cycles" \
        in proc.log and "100 times the strength" in proc.log
    # The profiles that were read are not warned about.
    assert proc.log.count("its IES profile") == proc.log.count("'ies_missing': its IES profile")
