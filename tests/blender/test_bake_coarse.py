"""A lighting bake into colour attributes of meshes too coarse to hold it (the Cornell box's
walls have four corners each: no shadows survive) says so in one line, with what to do."""

import pytest


@pytest.mark.parametrize("cuts,warned", [(0, True), (8, False)])
def test_colour_attribute_bake_of_a_coarse_mesh_says_what_to_do(blender, cuts, warned):
    result, proc = blender.run_script("bake_coarse.py", cuts, timeout=300)
    assert "exception" not in result, result.get("exception")
    assert result["bake"] == ["FINISHED"], proc.log
    lines = [line for line in proc.stdout.splitlines()
             if line.startswith("Photon: warning:") and "points to hold baked lighting" in line]
    if warned:
        assert len(lines) == 1, proc.log
        assert "subdivide them or set Bake Target to Lightmap" in lines[0]
        assert lines[0].startswith("Photon: warning: 7 object(s)"), lines[0]
        assert "'Floor' 4" in lines[0], lines[0]
    else:
        assert not lines, proc.log
