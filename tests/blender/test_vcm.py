"""The VCM integrator through Blender: selectable from the schema's enum with its vcm_mode, its
settings in a panel of their own (not SPPM's), and the Cornell box rendered with the brightness
photon mapping gives it in each of its modes."""

import re
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "test_scenes" / "cornell_box.blend"
SMALL = "import bpy; s = bpy.context.scene; s.render.resolution_percentage = 25; "


def render(blender, out_prefix, python_expr, timeout=600):
    args = [str(CORNELL), "-E", "PHOTON", "--python-expr", python_expr,
            "-o", f"{out_prefix}####", "-F", "OPEN_EXR", "-x", "1", "-f", "1"]
    proc = blender.run(args, timeout=timeout)
    assert "Photon: rendered frame" in proc.stdout, f"Photon did not render\n{proc.log}"
    return proc


@pytest.mark.parametrize("mode", ["VCM", "BPT", "PPM"])
def test_vcm_matches_photon_mapping_on_the_cornell_box(blender, tmp_path, mode):
    proc = render(blender, tmp_path / "vcm_",
                  SMALL + f"s.photon.integrator = 'VCM'; s.photon.vcm_mode = '{mode}'; "
                  "s.photon.vcm_iterations = 16; s.photon.vcm_light_paths = 20000")
    match = re.search(r"Photon: vcm: (\d+) iterations, 320,000 light paths", proc.stdout)
    assert match and int(match.group(1)) == 16, proc.log
    assert "rendering with SPPM instead" not in proc.stdout, proc.log
    render(blender, tmp_path / "pm_", SMALL + "s.photon.samples = 16")
    vcm = read_image(tmp_path / "vcm_0001.exr")[..., :3]
    pm = read_image(tmp_path / "pm_0001.exr")[..., :3]
    assert vcm.shape == pm.shape
    assert vcm.mean() > 0.05, "a black image"
    for c in range(3):
        np.testing.assert_allclose(vcm[..., c].mean(), pm[..., c].mean(), rtol=0.05)


def test_vcm_is_in_the_enum_and_shows_the_iteration_settings(blender):
    expr = (
        "import bpy\n"
        "s = bpy.context.scene\n"
        "s.render.engine = 'PHOTON'\n"
        "items = [i.identifier for i in s.photon.bl_rna.properties['integrator'].enum_items]\n"
        "modes = [i.identifier for i in s.photon.bl_rna.properties['vcm_mode'].enum_items]\n"
        "s.photon.integrator = 'VCM'\n"
        "print('vcm:', 'VCM' in items, modes, bpy.types.PHOTON_PT_vcm.poll(bpy.context),\n"
        "      bpy.types.PHOTON_PT_sppm.poll(bpy.context))\n")
    proc = blender.run(["--python-expr", expr])
    assert "vcm: True ['VCM', 'BPT', 'PPM'] True False" in proc.stdout, proc.log
