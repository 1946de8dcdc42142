"""Shading normals of smooth, mixed smooth/flat, subdivided, n-gon and Auto Smooth meshes:
they agree with Blender's own loop normals, and two Blender processes syncing the same meshes
get the same bits (Blender 3.4 sums vertex normals on several threads in no fixed order, so
reading them would not)."""

import pytest


@pytest.fixture(scope="module")
def runs(blender):
    results = []
    for run in range(2):
        result, _ = blender.run_script("shading_normals.py", timeout=300)
        assert "exception" not in result, result.get("exception")
        results.append(result)
    return results


CASES = ["smooth_uv", "smooth_subsurf_no_uv", "mixed", "smooth_ngons", "auto_smooth"]


@pytest.mark.parametrize("case", CASES)
def test_normals_agree_with_blenders(runs, case):
    row = runs[0][case]
    assert row["triangles"] > 0 and row["rows"] == row["expected_rows"], row
    # Within 0.03 degrees: only the order of float additions differs (and the 2^-16 snap).
    assert row["min_cosine"] > 1 - 1.5e-7, row


@pytest.mark.parametrize("case", CASES)
def test_same_bits_in_two_processes(runs, case):
    assert runs[0][case]["input_hash"] == runs[1][case]["input_hash"], "the meshes differ"
    assert runs[0][case]["hash"] == runs[1][case]["hash"], case


def test_no_warnings(runs):
    assert runs[0]["warnings"] == [], runs[0]["warnings"]
