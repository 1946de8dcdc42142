"""The SPPM integrator through Blender: selectable from the schema's enum, renders the Cornell box
with the brightness photon mapping gives it, writes light passes that sum to Combined, and stops
at its time limit with the iterations done so far."""

import re
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "test_scenes" / "cornell_box.blend"
SMALL = "import bpy; s = bpy.context.scene; s.render.resolution_percentage = 25; "


def render(blender, out_prefix, python_expr, fmt="OPEN_EXR", timeout=600):
    args = [str(CORNELL), "-E", "PHOTON", "--python-expr", python_expr,
            "-o", f"{out_prefix}####", "-F", fmt, "-x", "1", "-f", "1"]
    proc = blender.run(args, timeout=timeout)
    assert "Photon: rendered frame" in proc.stdout, f"Photon did not render\n{proc.log}"
    return proc


def sppm_iterations(proc):
    match = re.search(r"Photon: sppm: (\d+) iterations", proc.stdout)
    assert match, proc.log
    return int(match.group(1))


def test_sppm_matches_photon_mapping_on_the_cornell_box(blender, tmp_path):
    proc = render(blender, tmp_path / "sppm_",
                  SMALL + "s.photon.integrator = 'SPPM'; s.photon.sppm_iterations = 16; "
                  "s.photon.sppm_photons_per_iteration = 50000")
    assert sppm_iterations(proc) == 16
    assert "bytes per pixel" in proc.stdout
    render(blender, tmp_path / "pm_", SMALL + "s.photon.samples = 16")
    sppm = read_image(tmp_path / "sppm_0001.exr")[..., :3]
    pm = read_image(tmp_path / "pm_0001.exr")[..., :3]
    assert sppm.shape == pm.shape
    assert sppm.mean() > 0.05, "a black image"
    for c in range(3):
        np.testing.assert_allclose(sppm[..., c].mean(), pm[..., c].mean(), rtol=0.05)


def test_sppm_light_passes_sum_to_combined(blender, tmp_path):
    render(blender, tmp_path / "passes_",
           SMALL + "s.photon.integrator = 'SPPM'; s.photon.sppm_iterations = 4; "
           "s.photon.sppm_photons_per_iteration = 20000; v = s.view_layers[0].photon; "
           "v.use_pass_direct = v.use_pass_indirect = v.use_pass_caustics = True",
           fmt="OPEN_EXR_MULTILAYER")
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(str(tmp_path / "passes_0001.exr"))
    names = list(buf.spec().channelnames)
    pixels = buf.get_pixels(oiio.FLOAT)

    def channel(layer_pass, c):
        return pixels[..., names.index(f"ViewLayer.{layer_pass}.{c}")]

    for c in "RGB":
        light = sum(channel(f"Photon {p}", c) for p in ("Direct", "Indirect", "Caustics"))
        np.testing.assert_allclose(light, channel("Combined", c), rtol=1e-5, atol=1e-6)
    # The photons' share (indirect light and caustics) is a real part of the Cornell box.
    indirect = np.mean([channel("Photon Indirect", c).mean() for c in "RGB"])
    direct = np.mean([channel("Photon Direct", c).mean() for c in "RGB"])
    assert 0.3 < indirect / direct < 2.0


def test_sppm_time_limit_ends_the_render_with_the_iterations_done(blender, tmp_path):
    proc = render(blender, tmp_path / "t_",
                  SMALL + "s.photon.integrator = 'SPPM'; s.photon.sppm_iterations = 100000; "
                  "s.photon.sppm_photons_per_iteration = 5000; s.photon.sppm_time = 1.5")
    done = sppm_iterations(proc)
    assert 1 <= done < 100000
    seconds = float(re.search(r"render ([0-9.]+) s, total", proc.stdout).group(1))
    assert 1.5 <= seconds < 6.0, proc.log
    assert read_image(tmp_path / "t_0001.exr")[..., :3].mean() > 0.05
