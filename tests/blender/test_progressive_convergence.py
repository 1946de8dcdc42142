"""Consistency of SPPM on the caustic validation scene (test_scenes/validation/
caustic_validation.blend: the caustic box, glass and mirror balls under a small sphere light,
against Cycles at 16384 spp): the error against Cycles falls as iterations grow, along a
log-log line of negative slope, and the image mean comes within 1% of Cycles' (one Blender
process renders 4, 16 and 64 iterations: 8 s on an idle machine).

Rendered at half resolution (64 x 64): with Photon's box filter of width 1, each pixel
estimates the mean of a 2 x 2 block of the 128 x 128 reference, which also halves Cycles' own
noise in the comparison."""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CAUSTIC = REPO / "test_scenes" / "validation" / "caustic_validation.blend"
COUNTS = (4, 16, 64)


def block_means(image, factor):
    h, w = image.shape[0] // factor, image.shape[1] // factor
    return image[:h * factor, :w * factor].reshape(h, factor, w, factor, -1).mean(axis=(1, 3))


def render_counts(blender, tmp_path, integrator, photons):
    result, proc = blender.run_script("render_iterations.py", tmp_path / f"{integrator}_",
                                      integrator, photons, 50, *COUNTS, blend=CAUSTIC,
                                      timeout=900)
    assert "exception" not in result, result.get("exception")
    assert "Photon: rendered frame" in proc.stdout, proc.log
    return result["renders"]


def test_sppm_error_against_cycles_falls_along_a_negative_log_log_slope(blender, tmp_path):
    """The error is the relative mean absolute error (mean |image - Cycles| / mean Cycles):
    the relative RMSE is made, at every iteration count, by the few pixels that see the small
    lamp through the glass ball now and then (one sample of a 64-iteration pixel that hits it
    adds 10 to a pixel whose reference is 2.7), which is sampling luck rather than the light
    transport this checks.

    Measured (50k photons per iteration): relative MAE 0.072 / 0.049 / 0.028 after 4 / 16 / 64
    iterations, a fitted slope of -0.34 per log iteration (SPPM's theory: -1/3 for the bias,
    -1/2 for the noise), the mean -1.5% / +1.5% / +0.8% off Cycles' (the +1.5% at 16 is one
    such lamp sample). The 1% bound on the mean is checked at 64 iterations;
    tests/bench/convergence_curves.py follows it further."""
    reference = block_means(read_image(CAUSTIC.with_suffix(".exr"))[..., :3], 2)
    errors, rmse, means = [], [], []
    for r in render_counts(blender, tmp_path, "SPPM", 50000):
        image = read_image(r["path"])[..., :3]
        assert image.shape == reference.shape
        errors.append(np.mean(np.abs(image - reference)) / reference.mean())
        rmse.append(np.sqrt(np.mean((image - reference) ** 2)) / reference.mean())
        means.append(image.mean() / reference.mean() - 1.0)
    slope = np.polyfit(np.log(COUNTS), np.log(errors), 1)[0]
    print(f"caustic_validation, SPPM at {COUNTS} iterations: relative MAE "
          f"{[round(e, 4) for e in errors]} (relative RMSE {[round(e, 4) for e in rmse]}), "
          f"mean {[round(m, 4) for m in means]}, fitted slope {slope:.3f}")
    assert errors[0] > errors[1] > errors[2], errors
    assert slope < -0.2, slope
    assert abs(means[2]) < 0.01, means
