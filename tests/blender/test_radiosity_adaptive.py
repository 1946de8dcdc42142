"""RADIOSITY on an unbalanced scene: a ~200k-triangle sphere over a 20 m floor of 2 triangles
under a sun, with the automatic patch size and 2M rays. One patch per sphere triangle gave
~10 rays per patch (a speckled sphere) and left the floor 2 patches (no shadow). Adaptive
sizing clusters the sphere's triangles and subdivides the floor, so the sphere's shadow shows
and the sphere is smooth."""


def test_unbalanced_scene_shows_the_shadow_and_a_smooth_sphere(blender):
    result, proc = blender.run_script("radiosity_adaptive.py", blender.out_dir / "radiosity_adaptive",
                                      "2000", "448", timeout=300)
    assert "exception" not in result, result.get("exception")
    assert "Photon: rendered frame" in proc.stdout, proc.log
    stats = [line for line in proc.stdout.splitlines() if "radiosity:" in line]
    report = f"{result}\n{stats}"
    assert result["triangles"] > 190000, report
    assert result["disc_pixels"] > 1000, report
    assert result["lit"] > 0.05, report  # the sun lights the floor
    # The floor in the sphere's shadow gets only indirect light: far darker than in the sun.
    assert result["shadow"] < 0.5 * result["lit"], report
    # Neighbouring pixels on the sphere differ by little (smooth shading, not per-patch noise):
    # measured 0.017 (one patch per triangle: 2.0).
    assert result["noise"] < 0.05, report
