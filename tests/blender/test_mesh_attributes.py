"""Mesh attributes in shader programs, Photon against Cycles per pixel on a jittered triangle
grid (tests/blender/scripts/mesh_attributes.py): colour attributes (byte on corners, float on
points), a float on faces, a vector on points, a second UV map read directly, through the
Attribute node and driving a Checker, and a missing attribute (Cycles' 0, Alpha 1, and one
warning naming material, node and attribute)."""

import pytest

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
    # Per pixel within 1e-4 (relative or absolute) plus what the engines' 0.01-pixel sample
    # offsets make of the image's gradient. Face and corner values (and the checker) jump at
    # edges: a sample on the other side of an edge than the other engine's is allowed for 0.5%
    # of the pixels; values continuous over the mesh allow none.
    continuous = case in ("point_color", "point_color_fac", "point_vector", "missing_alpha",
                          "missing_color")
    assert result["over"] <= (0 if continuous else result["pixels"] // 200), result


def test_missing_attribute_warns_once_naming_material_node_and_attribute(renders):
    stdout = renders[1]
    lines = [l for l in stdout.splitlines() if "attribute 'nope'" in l and "warning" in l]
    assert any("Material 'missing_alpha'" in l and "node 'attr'" in l for l in lines), stdout
    assert sum("Material 'missing_alpha'" in l for l in lines) == 1, lines
