"""A room lit by 40 small point and spot lights: Photon picks one light per shading point with
its light tree (more than 8 lights), and its image must match, within noise, the sum of renders
of the same room with at most 8 lights each, where Photon samples every light (light adds up,
so that sum is the every-light image)."""

import pytest


@pytest.mark.parametrize("integrator", ["RAY_TRACE", "PHOTON_MAP"])
def test_light_tree_image_matches_every_light_sum(blender, integrator):
    result, proc = blender.run_script("many_lights.py", blender.out_dir / f"many_lights_{integrator}",
                                      40, 8, 64, integrator, timeout=900)
    assert "exception" not in result, result.get("exception")
    assert proc.stdout.count("Photon: rendered frame") >= result["renders"], proc.log
    report = str(result)
    for tree, every in zip(result["mean_tree"], result["mean_every"]):
        assert every > 0.01, report  # the room is lit
        assert tree == pytest.approx(every, rel=0.02), report
    assert result["block_rel_rmse"] < 0.05, report
