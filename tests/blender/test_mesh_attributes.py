"""Mesh attributes in shader programs, Photon against Cycles per pixel on a jittered triangle
grid (tests/blender/scripts/mesh_attributes.py): colour attributes (byte on corners, float on
points), a float on faces, a vector on points, a second UV map read directly, through the
Attribute node and driving a Checker, and a missing attribute (Cycles' 0, Alpha 1, and one
warning naming material, node and attribute)."""

import pytest

TOLERANCE = 1e-4  # relative or absolute, per channel


@pytest.fixture(scope="module")
def renders(blender):
    out = blender.out_dir / "mesh_attributes"
    result, proc = blender.run_script("mesh_attributes.py", out, timeout=300)
    assert "exception" not in result, result["exception"]
    return result, proc.stdout


@pytest.mark.parametrize("case", ["render_color", "byte_alpha", "point_color",
                                  "point_color_fac", "face_float", "point_vector", "second_uv",
                                  "second_uv_checker", "uv_by_attribute", "missing_alpha",
                                  "missing_color"])
def test_photon_matches_cycles(renders, case):
    result = renders[0][case]
    # Not a black image on both sides: the case shows something (or, missing, exactly 0 / 1).
    if case == "missing_alpha":
        assert result["cycles_range"] == [1.0, 1.0]
    elif case == "missing_color":
        assert result["cycles_range"] == [0.0, 0.0]
    else:
        assert result["cycles_range"][1] > 0.05, result
    # Face and corner values jump across triangle edges: a pixel centre within float rounding
    # of an edge may land on the other triangle in one engine; allow 0.5% of the pixels.
    assert result["over_1e4"] <= result["pixels"] // 200, result
    if case not in ("face_float", "render_color", "byte_alpha", "second_uv_checker"):
        assert result["max_rel"] <= TOLERANCE, result


def test_missing_attribute_warns_once_naming_material_node_and_attribute(renders):
    stdout = renders[1]
    lines = [l for l in stdout.splitlines() if "attribute 'nope'" in l and "warning" in l]
    assert any("Material 'missing_alpha'" in l and "node 'attr'" in l for l in lines), stdout
    assert sum("Material 'missing_alpha'" in l for l in lines) == 1, lines
