"""A camera no image can be made from (a NaN location, a zero scale) stops the render with a
clear error and writes no image, instead of a frame of garbage."""

import pytest

CASES = {
    "nan_camera": "Camera 'Camera' has a non-finite transform",
    "zero_scale_camera": "Camera 'Camera' has a zero scale",
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_unusable_camera_is_an_error_not_an_image(blender, tmp_path, case):
    blend = tmp_path / f"{case}.blend"
    blender.run_script("make_bad_scene.py", case, blend)
    proc = blender.run([str(blend), "-E", "PHOTON", "-o", str(tmp_path / "out_####"),
                        "-F", "OPEN_EXR", "-x", "1", "-f", "1"], check=False)
    # Blender exits non-zero once the engine sets an error, and Blender itself survives.
    assert proc.returncode == 1, proc.log
    assert CASES[case] in proc.stdout, proc.log
    assert "Traceback" not in proc.stdout + proc.stderr, proc.log
    assert not (tmp_path / "out_0001.exr").exists() or \
        (tmp_path / "out_0001.exr").stat().st_size == 0, proc.log
