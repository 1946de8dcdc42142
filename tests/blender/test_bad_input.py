"""Bad input never crashes Blender: the render finishes, writes an image and says what was
wrong through a warning."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

CASES = {
    "nan_geometry": ["vertices with NaN or infinite coordinates", "NaNBox",
                     "dropped 1 degenerate or invalid triangles"],
    "zero_area_light": ["Area light 'FlatLight' has zero size", "'DarkLight' has zero power"],
    "empty_scene": ["no renderable geometry", "no lights"],
    "no_lights": [],  # the world still lights the scene: nothing to warn about
    "unsupported_node": ["Material 'ToonMat': node 'Toon BSDF'", "not supported yet"],
    "absurd_settings": [],  # clamped silently; the render must simply finish
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_input_renders_with_warnings(blender, tmp_path, case):
    blend = tmp_path / f"{case}.blend"
    blender.run_script("make_bad_scene.py", case, blend)
    proc = blender.run([str(blend), "-E", "PHOTON", "-o", str(tmp_path / "out_####"),
                        "-F", "OPEN_EXR", "-x", "1", "-f", "1"], check=False)
    assert proc.returncode == 0, proc.log
    assert "Photon: rendered frame 1" in proc.stdout, proc.log
    image = read_image(tmp_path / "out_0001.exr")
    assert np.isfinite(image).all()
    for expected in CASES[case]:
        assert expected in proc.stdout, f"missing warning {expected!r}\n{proc.log}"
