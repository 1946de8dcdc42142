"""The fast mesh sync (evaluated mesh read without a to_mesh() copy, indices through uint32
foreach_get) gives exactly the arrays of the copying path, and takes the fast path only where
it is safe."""


def test_fast_mesh_path_matches_the_copy(blender):
    result, _ = blender.run_script("first_pixel_mesh_paths.py")
    assert "exception" not in result, result.get("exception")
    for label, row in result.items():
        assert row["same"], label
        assert row["indices_equal"], label
    # Plain meshes, with or without modifiers, skip the copy ...
    assert result["smooth_uv"]["fast_path"]
    assert result["flat_subsurf"]["fast_path"]
    # (smooth and flat polygons mixed: their normals are computed natively from the polygons)
    assert result["mixed"]["fast_path"]
    # ... meshes whose split normals Blender must compute keep it (the depsgraph's data is
    # not written).
    assert not result["auto_smooth_two_materials"]["fast_path"]
    assert result["auto_smooth_two_materials"]["method"] == "add_loop_mesh"
