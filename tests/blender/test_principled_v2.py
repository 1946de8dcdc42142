"""Principled BSDF v2 (Blender 4.0+) against that Blender's Cycles: a dielectric at Specular
IOR Level 0, 0.5 and 1, a specular tint, F82-tinted and rough (Multiscatter GGX) metals, a
tinted coat, rough transmission, emission, anisotropy, the merged Glossy BSDF and a single-
scattering GGX material, each sphere's mean colour within 2% of Cycles' (Cycles without
denoising, noise reductions off). Skipped in Blender 3.x, whose Principled BSDF is v1."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

TOLERANCE = 0.02
PHOTON_SAMPLES = 128
CYCLES_SAMPLES = 128


def disc_means(image, regions, shrink=0.8):
    yy, xx = np.mgrid[0:image.shape[0], 0:image.shape[1]] + 0.5
    means = {}
    for name, (cx, cy, r) in regions.items():
        mask = (xx - cx) ** 2 + (yy - cy) ** 2 <= (shrink * r) ** 2
        means[name] = image[mask][:, :3].mean(axis=0)
    return means


def test_principled_v2_spheres_match_cycles(blender, tmp_path):
    result, proc = blender.run_script("principled_v2_spheres.py", tmp_path, PHOTON_SAMPLES,
                                      CYCLES_SAMPLES, timeout=900)
    if "skip" in result:
        pytest.skip(result["skip"])
    assert "exception" not in result, result["exception"] + proc.log
    assert "Photon: rendered frame" in proc.stdout, proc.log
    cycles = disc_means(read_image(result["cycles"]), result["regions"])
    photon = disc_means(read_image(result["photon"]), result["regions"])
    report = {name: {"cycles": cycles[name].tolist(), "photon": photon[name].tolist(),
                     "ratio": float(photon[name].mean() / cycles[name].mean())}
              for name in cycles}
    print(json.dumps({"blender": result["version"], "spheres": report}, indent=1))
    failures = [f"{name}: photon {photon[name].mean():.4f} cycles {cycles[name].mean():.4f} "
                f"({100 * (report[name]['ratio'] - 1):+.2f}%)"
                for name in cycles
                if abs(photon[name].mean() - cycles[name].mean()) > TOLERANCE * cycles[name].mean()]
    assert not failures, "\n".join(failures) + "\n" + proc.stdout[-3000:]
