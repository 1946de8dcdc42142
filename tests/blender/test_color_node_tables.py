"""addon/photon/sync/node_tables.py: the ramp and curve tables Photon's colour nodes read.
The C++ conformance test (shading/color_nodes_test.cpp) checks tables stored in
test_scenes/nodes/color.json against Cycles' renders; this checks that the add-on bakes those
same tables from Blender today, and the documented layouts on Blender's default nodes."""

import pytest


@pytest.fixture(scope="module")
def tables(blender):
    result, _ = blender.run_script("color_node_tables.py", timeout=120)
    assert "exception" not in result, result["exception"]
    return result


# Cases whose table Blender itself evaluates differently from 3.4 (the manifest's): in 4.x an
# RGB Curves node driven far outside [0, 1] (its conformance case is left out there too).
DIFFERENT_IN_4X = {"rgb_curves_wide_range"}


def test_manifest_tables_are_what_the_addon_bakes(blender, tables):
    assert len(tables["cases"]) >= 20
    for name, case in tables["cases"].items():
        if blender.version >= (4, 0) and name in DIFFERENT_IN_4X:
            continue
        manifest, baked = case["manifest"], case["baked"]
        assert len(manifest) == len(baked), name
        worst = max(abs(a - b) for a, b in zip(manifest, baked))
        assert worst < 1e-6, f"{name}: table differs from the manifest by {worst}"


def test_default_ramp_is_linear_black_to_white(tables):
    size = tables["table_size"]
    ramp = tables["defaults"]["ShaderNodeValToRGB"]
    assert len(ramp) == 1 + 4 * size
    assert ramp[0] == 1.0  # LINEAR interpolates
    for i in range(size):
        r, g, b, a = ramp[1 + 4 * i:5 + 4 * i]
        assert r == pytest.approx(i / (size - 1), abs=1e-6)
        assert r == g == b and a == 1.0
    assert tables["constant_ramp"][0] == 0.0


def test_default_curves_are_identity_over_their_range(tables):
    size = tables["table_size"]
    for idname, channels, lo, hi in (("ShaderNodeRGBCurve", 3, 0.0, 1.0),
                                     ("ShaderNodeVectorCurve", 3, -1.0, 1.0),
                                     ("ShaderNodeFloatCurve", 1, 0.0, 1.0)):
        table = tables["defaults"][idname]
        assert len(table) == 3 + channels * size, idname
        extrapolate = 1.0 if tables["extend"][idname] == 'EXTRAPOLATED' else 0.0
        assert table[:3] == [lo, hi, extrapolate], idname
        for i in range(size):
            x = lo + i / (size - 1) * (hi - lo)
            for c in range(channels):
                assert table[3 + i * channels + c] == pytest.approx(x, abs=1e-5), (idname, i)


def test_nodes_without_blender_data_have_no_table(tables):
    assert tables["defaults"]["ShaderNodeMath"] is None
