"""Principled inputs above the range of the core's one material table
(_photon.material_parameters()) are clamped to the same bound whether the value is a constant
(a Value / RGB node) or an image texture: both renders are the same image."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402


def table_max(native, closure, key):
    for c in native.material_parameters():
        if c["closure"] == closure:
            return next(p["max"] for p in c["params"] if p["key"] == key)
    raise KeyError(closure)


def render(blender, tmp_path, input_name, mode, value):
    blend = tmp_path / f"{mode}.blend"
    result, _ = blender.run_script("tables_clamp_scene.py", input_name, mode, value, blend)
    assert "exception" not in result, result["exception"]
    assert result["pixel"] == pytest.approx(value, rel=1e-3)  # the image holds the value
    proc = blender.run([str(blend), "-E", "PHOTON", "-o", str(tmp_path / f"{mode}_####"),
                        "-F", "OPEN_EXR", "-x", "1", "-f", "1"])
    assert "Photon: rendered frame 1" in proc.stdout, proc.log
    return read_image(tmp_path / f"{mode}_0001.exr"), proc


@pytest.mark.parametrize("input_name,key,factor", [
    ("Emission Strength", "strength", 5.0),
    ("Base Color", "color", 5.0),
])
def test_constant_and_texture_above_the_table_max_clamp_alike(blender, native, tmp_path,
                                                              input_name, key, factor):
    top = table_max(native, "PRINCIPLED", key)
    value = factor * top
    constant, c_proc = render(blender, tmp_path, input_name, "constant", value)
    textured, t_proc = render(blender, tmp_path, input_name, "texture", value)
    assert np.isfinite(constant).all() and np.isfinite(textured).all()
    np.testing.assert_array_equal(constant, textured, err_msg=c_proc.log + t_proc.log)
    # Both say which bound they clamped to (the add-on for the constant, the core for the
    # texture), and it is the table's.
    assert f"outside [0, {top:g}]; using {top:g}" in c_proc.stdout, c_proc.log
    assert f"outside [0, {top:g}]; clamped to {top:g}" in t_proc.stdout, t_proc.log
    centre = constant[6:10, 6:10, :3]
    if key == "strength":
        # Emission colour 1e-6 x the clamped strength, seen head-on (no lights).
        np.testing.assert_allclose(centre, 1e-6 * top, rtol=1e-4, err_msg=c_proc.log)
    else:
        # A white (albedo 1) surface under a sun of strength 1: about 1/pi, not 5/pi.
        assert 0.1 < centre.mean() < 1.0, f"mean {centre.mean()}\n{c_proc.log}"
