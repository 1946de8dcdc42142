"""Depsgraph sync: modifiers, instancing, text, linked duplicates and every light type."""


def test_sync_counts(blender):
    result, _ = blender.run_script("sync_counts.py")
    assert "exception" not in result, result.get("exception")
    # Meshes: subdivided cube, arrayed plane, the scattered cube, the shared box, the text, the
    # metaball and the NURBS sphere (each converted once, not also from its Curve/MetaBall entry).
    assert result["mesh_count"] == 7
    # Instances: 1 + 1 + 100 scattered + 2 linked duplicates + text + metaball + surface.
    assert result["instance_count"] == 107
    # Unique triangles: 48 (subdivided cube) + 6 (array) + 12 (scattered cube, once) +
    # 12 (shared box, once) + the text's own triangles.
    assert result["triangle_count"] > 48 + 6 + 12 + 12
    # Point, spot, sun and the four area shapes; the zero-power light is skipped with a warning.
    assert result["light_count"] == 7
    assert any("ZeroPower" in w and "zero power" in w for w in result["warnings"])
