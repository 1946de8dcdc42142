"""Light and photon settings that used to give a silently wrong image: each renders the Cornell
box small, checks the image's figures against a sane render of the same scene, asserts that no
pixel of any pass is NaN, infinite or saturated at the float limit, and that a warning says
what was changed."""

import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "test_scenes" / "cornell_box.blend"
SCRIPT = Path(__file__).resolve().parent / "scripts" / "light_limits.py"
QUICK = ["resolution=32", "photons=20000", "caustic_photons=0", "final_gather_rays=8"]
# A value no light of a sane scene reaches, far below the float limit (3.4e38) where pixel
# averages saturate: a bright lamp seen from a few metres gives radiance ~1e12 at most here.
SATURATED = 1e30


def render(blender, tmp_path, name, *settings, multilayer=False):
    """Renders the Cornell box with `settings`; returns (stdout, {channel: float64 pixels})."""
    fmt = "OPEN_EXR_MULTILAYER" if multilayer else "OPEN_EXR"
    proc = blender.run([str(CORNELL), "-E", "PHOTON", "--python", str(SCRIPT),
                        "-o", str(tmp_path / f"{name}_####"), "-F", fmt, "-x", "1", "-f", "1",
                        "--", *QUICK, *settings], check=False, timeout=900)
    assert proc.returncode == 0, proc.log
    assert "Photon: rendered frame 1 " in proc.stdout, proc.log
    path = tmp_path / f"{name}_0001.exr"
    if not multilayer:
        return proc.stdout, {"Combined": read_image(path).astype(np.float64)}
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(str(path))
    pixels = np.asarray(buf.get_pixels(oiio.FLOAT), dtype=np.float64)
    channels = list(buf.spec().channelnames)
    passes = {}
    for layer in sorted({c.rsplit(".", 1)[0] for c in channels}):
        index = [channels.index(f"{layer}.{c}") for c in "RGB" if f"{layer}.{c}" in channels]
        passes[layer.split(".")[-1]] = pixels[..., index]
    return proc.stdout, passes


def mean(image):
    return float(image[..., :3].mean())


def assert_sane(passes, label):
    """No NaN, no inf and no value at the float limit in any channel of any pass."""
    for name, image in passes.items():
        bad = int((~np.isfinite(image)).sum())
        assert bad == 0, f"{label}: {bad} NaN or infinite values in pass {name}"
        peak = float(np.abs(image).max())
        assert peak < SATURATED, f"{label}: pass {name} saturates at {peak:.3g}"


def describe(passes):
    """Mean and peak of the finite RGB values and the NaN/inf count of each pass, for the log."""
    parts = []
    for name, image in passes.items():
        rgb = image[..., :3]
        finite = rgb[np.isfinite(rgb)]
        parts.append(f"{name} mean {finite.mean():.4g} peak {finite.max():.4g} "
                     f"NaN/inf {rgb.size - finite.size}")
    return "; ".join(parts)


def clamped_to(stdout, pattern):
    """The number a warning matching `pattern` (with one group for the number) names."""
    match = re.search(pattern, stdout)
    assert match, f"no warning matching {pattern!r}\n{stdout}"
    return float(match.group(1))


@pytest.mark.parametrize("radius", ["1e-06", "1e-09"])
def test_tiny_gather_radius_is_raised_to_what_the_photons_support(blender, tmp_path, radius):
    log, auto = render(blender, tmp_path, "auto", "samples=4")
    log_tiny, tiny = render(blender, tmp_path, "tiny", "samples=4", f"gather_radius={radius}")
    print(f"gather_radius {radius}: mean {mean(tiny['Combined']):.6g}, automatic radius "
          f"{mean(auto['Combined']):.6g}")
    assert "Gather radius" not in log
    floor = clamped_to(log_tiny, rf"Photon: warning: Gather radius {radius} m is smaller than "
                                 r"the photon density supports \(global map: the median radius "
                                 r"holding 100 of its [\d,]+ photons is ([\d.e+-]+) m\)")
    assert 1e-3 < floor < 1.0
    assert log_tiny.count("Photon: warning: Gather radius") == 1, log_tiny
    assert_sane(tiny, "tiny radius")
    # Within noise of the automatic radius (the two differ by 0.1% at 64 px, 200k photons).
    assert mean(tiny["Combined"]) == pytest.approx(mean(auto["Combined"]), rel=0.03)


def test_huge_area_light_power_is_clamped_with_a_warning(blender, tmp_path):
    # 32 samples: enough that 3e38 W overflowed pixel sums (samples of ~1e37 each).
    _, base = render(blender, tmp_path, "base", "samples=32")
    log, huge = render(blender, tmp_path, "huge", "samples=32", "area_power=3e38")
    print(f"area light 3e38 W: {describe(huge)}; 40 W: {describe(base)}")
    # Blender 4.0+ scales area lights by 4/pi (Cycles 4's units): past float32, so the add-on
    # hands the largest float on.
    power = clamped_to(log, r"Photon: warning: Light 'CeilingLight': power (?:3|3\.4)e\+38 W is "
                            r"more than Photon can render; clamped to ([\d.e+-]+) W")
    assert math.isfinite(power) and 1e6 <= power < 1e30
    scaled = mean(huge["Combined"]) * 40.0 / power  # the .blend's lamp emits 40 W
    print(f"area light 3e38 W: mean {mean(huge['Combined']):.6g} (x 40 W / {power:.3g} W = "
          f"{scaled:.6g}); 40 W: {mean(base['Combined']):.6g}")
    assert_sane(huge, "3e38 W area light")
    # Light is linear in power: the clamped lamp's image is the 40 W one scaled.
    assert scaled == pytest.approx(mean(base["Combined"]), rel=0.01)


def test_huge_sun_strength_is_clamped_and_no_pass_holds_inf(blender, tmp_path):
    # The sun alone (the ceiling lamp removed), every light pass written.
    common = ["samples=8", "area_power=0", "passes=1"]
    _, unit = render(blender, tmp_path, "unit", *common, "sun_strength=1", multilayer=True)
    log, huge = render(blender, tmp_path, "huge", *common, "sun_strength=3e38", multilayer=True)
    print(f"sun 3e38: {describe(huge)}\nsun 1: {describe(unit)}")
    strength = clamped_to(log, r"Photon: warning: Light 'Sun': strength 3e\+38 W/m\^2 is more "
                               r"than Photon can render; clamped to ([\d.e+-]+) W/m\^2")
    for name in ("Combined", "Photon Direct", "Photon Indirect"):
        print(f"sun 3e38: {name} mean / {strength:.3g} = {mean(huge[name]) / strength:.6g}; "
              f"sun 1: {mean(unit[name]):.6g}")
    assert "NaN or infinite" not in log, log
    assert_sane(huge, "3e38 W/m^2 sun")
    assert set(huge) >= {"Combined", "Photon Direct", "Photon Indirect", "Photon Caustics"}
    for name in ("Combined", "Photon Direct", "Photon Indirect"):
        assert mean(huge[name]) / strength == pytest.approx(mean(unit[name]), rel=0.01), name


@pytest.mark.parametrize("strength, warning", [
    ("nan", "the Background strength is NaN; using 0"),
    ("-1", "the Background strength -1 is negative; clamped to 0"),
])
def test_nan_or_negative_world_strength_is_zero_with_a_warning(blender, tmp_path, strength,
                                                                 warning):
    _, black = render(blender, tmp_path, "black", "samples=2", "world_strength=0")
    _, grey = render(blender, tmp_path, "grey", "samples=2", "world_strength=1")
    log, bad = render(blender, tmp_path, "bad", "samples=2", f"world_strength={strength}")
    print(f"world strength {strength}: mean {mean(bad['Combined']):.6g}; strength 0: "
          f"{mean(black['Combined']):.6g}, 1: {mean(grey['Combined']):.6g}")
    assert f"Photon: warning: World 'World': {warning}" in log, log
    assert_sane(bad, f"world strength {strength}")
    assert mean(grey["Combined"]) > mean(black["Combined"]) + 0.05  # the world does show
    np.testing.assert_array_equal(bad["Combined"], black["Combined"])


def test_huge_world_strength_is_clamped_with_a_warning(blender, tmp_path):
    _, grey = render(blender, tmp_path, "grey", "samples=8", "area_power=0", "world_strength=1")
    log, huge = render(blender, tmp_path, "huge", "samples=8", "area_power=0",
                       "world_strength=3e38")
    print(f"world 3e38: {describe(huge)}; world 1: {describe(grey)}")
    # The script's background colour is 0.5 grey.
    radiance = clamped_to(log, r"Photon: warning: World 'World': background colour x strength "
                               r"1\.5e\+38 is more than Photon can render; clamped to "
                               r"([\d.e+-]+)")
    print(f"world 3e38: mean / {radiance / 0.5:.3g} = {mean(huge['Combined']) * 0.5 / radiance:.6g}"
          f"; world 1: {mean(grey['Combined']):.6g}")
    assert_sane(huge, "world strength 3e38")
    assert mean(huge["Combined"]) * 0.5 / radiance == pytest.approx(mean(grey["Combined"]),
                                                                    rel=0.01)
