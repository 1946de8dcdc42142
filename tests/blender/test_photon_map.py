"""The PHOTON_MAP integrator through Blender: light passes, the time budget, and agreement
with stored Cycles references (diffuse global illumination and caustics)."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "test_scenes" / "cornell_box.blend"
VALIDATION = REPO / "test_scenes" / "validation"


def render(blender, blend, out_prefix, python_expr="", fmt="OPEN_EXR", timeout=600):
    args = [str(blend), "-E", "PHOTON"]
    if python_expr:
        args += ["--python-expr", python_expr]
    args += ["-o", f"{out_prefix}####", "-F", fmt, "-x", "1", "-f", "1"]
    proc = blender.run(args, timeout=timeout)
    assert "Photon: rendered frame" in proc.stdout, f"Photon did not render\n{proc.log}"
    return proc


def test_photon_map_is_the_default_integrator(blender, tmp_path):
    proc = render(blender, CORNELL, tmp_path / "c_",
                  "import bpy; s = bpy.context.scene; "
                  "s.render.resolution_percentage = 25; "
                  "print('integrator:', s.photon.integrator)")
    assert "integrator: PHOTON_MAP" in proc.stdout
    assert "Photon: photons: 200,000 global" in proc.stdout, proc.log


def test_light_passes_sum_to_combined(blender, tmp_path):
    # 16 spp: the Photon Map pass averages dots over a pixel's samples, and at 64x64 pixels
    # more samples only measure each dot's coverage of the pixel (about 0.4 at most).
    expr = ("import bpy; s = bpy.context.scene; s.render.resolution_percentage = 25; "
            "s.photon.samples = 16; v = s.view_layers[0].photon; v.use_pass_direct = v.use_pass_indirect = "
            "v.use_pass_caustics = v.use_pass_photon_map = True")
    render(blender, CORNELL, tmp_path / "passes_", expr, fmt="OPEN_EXR_MULTILAYER")
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(str(tmp_path / "passes_0001.exr"))
    names = list(buf.spec().channelnames)
    pixels = buf.get_pixels(oiio.FLOAT)

    def channel(layer_pass, c):
        return pixels[..., names.index(f"ViewLayer.{layer_pass}.{c}")]

    for c in "RGB":
        light = sum(channel(f"Photon {p}", c) for p in ("Direct", "Indirect", "Caustics"))
        np.testing.assert_allclose(light, channel("Combined", c), rtol=1e-5, atol=1e-6)
    # Indirect light is a real share of the Cornell box; the photon-map view shows photons.
    indirect = np.mean([channel("Photon Indirect", c).mean() for c in "RGB"])
    direct = np.mean([channel("Photon Direct", c).mean() for c in "RGB"])
    assert 0.3 < indirect / direct < 2.0
    assert channel("Photon Map", "R").max() > 0.5


@pytest.mark.serial  # a wall-time bound
def test_photon_time_budget_traces_for_its_time(blender, tmp_path):
    proc = render(blender, CORNELL, tmp_path / "t_",
                  "import bpy; s = bpy.context.scene; s.render.resolution_percentage = 25; "
                  "s.photon.photon_time = 1.0; s.photon.photons = 1000")
    line = next(l for l in proc.stdout.splitlines() if l.startswith("Photon: photons:"))
    emitted = int(line.split("photons: ")[1].split(" global")[0].replace(",", ""))
    seconds = float(line.split(" stored in ")[1].split(" s")[0])
    print(line)
    assert emitted > 1000, "the budget, not the count, decides how many photons are traced"
    assert 1.0 <= seconds < 3.0


def compare_with_cycles(blender, tmp_path, name, expr=""):
    render(blender, VALIDATION / f"{name}.blend", tmp_path / f"{name}_", expr)
    image = read_image(tmp_path / f"{name}_0001.exr")[..., :3]
    reference = read_image(VALIDATION / f"{name}.exr")[..., :3]
    assert image.shape == reference.shape
    return image, reference


def test_cornell_global_illumination_matches_cycles(blender, tmp_path):
    """Full GI against Cycles (4096 spp, 32 bounces): mean within 2%, relative RMSE stated."""
    image, reference = compare_with_cycles(blender, tmp_path, "cornell_gi",
                                           "import bpy; bpy.context.scene.photon.samples = 64")
    mean_diff = image.mean() / reference.mean() - 1.0
    rel_rmse = np.sqrt(np.mean((image - reference) ** 2)) / reference.mean()
    per_channel = image.reshape(-1, 3).mean(0) / reference.reshape(-1, 3).mean(0) - 1.0
    print(f"cornell_gi vs Cycles: mean {mean_diff:+.4f}, per channel {per_channel}, "
          f"relative RMSE {rel_rmse:.4f}")
    assert abs(mean_diff) < 0.02
    assert np.all(np.abs(per_channel) < 0.03), "colour bleeding is off"
    assert rel_rmse < 0.08


def test_caustic_under_the_glass_ball_matches_cycles(blender, tmp_path):
    """The caustic box: the focused light under the glass ball is where Cycles puts it and
    carries the same power (sum over the floor region around it)."""
    sidecar = json.loads((VALIDATION / "caustic_validation.json").read_text())
    x0, y0, x1, y1 = sidecar["regions"]["caustic"]  # pixel rows/columns, top-left origin
    image, reference = compare_with_cycles(blender, tmp_path, "caustic_validation")
    region, ref_region = image[y0:y1, x0:x1].mean(-1), reference[y0:y1, x0:x1].mean(-1)
    power_ratio = region.sum() / ref_region.sum()
    # Location: the centroid of the brightest tenth of the region's pixels.
    def centroid(a):
        mask = a >= np.quantile(a, 0.9)
        ys, xs = np.nonzero(mask)
        return np.array([xs.mean(), ys.mean()])
    offset = np.linalg.norm(centroid(region) - centroid(ref_region))
    # Present and focused: the brightest pixels of the region stand well above its median.
    peak = np.quantile(region, 0.95) / np.median(region)
    ref_peak = np.quantile(ref_region, 0.95) / np.median(ref_region)
    print(f"caustic region: power ratio Photon/Cycles {power_ratio:.3f}, centroid offset "
          f"{offset:.2f} px, peak/median {peak:.2f} (Cycles {ref_peak:.2f})")
    assert peak > 1.8 and ref_peak > 1.8
    assert abs(power_ratio - 1.0) < 0.1
    assert offset < 2.0
    mean_diff = image.mean() / reference.mean() - 1.0
    print(f"caustic_validation vs Cycles: image mean {mean_diff:+.4f}")
    assert abs(mean_diff) < 0.03
