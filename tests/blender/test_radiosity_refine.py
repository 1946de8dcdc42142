"""RADIOSITY refines its mesh where the light changes: under a sun with a sharp shadow, the
floor patches along the shadow's edge are split (a first solve marks them), so the rendered
edge is a narrower ramp than the area-sized mesh gives, with no more patches in all."""

import re


def test_shadow_edge_is_sharper_with_refinement(blender):
    result, proc = blender.run_script("radiosity_refine.py", blender.out_dir / "radiosity_refine",
                                      "8000", timeout=300)
    assert "exception" not in result, result.get("exception")
    assert "Photon: rendered frame" in proc.stdout, proc.log
    stats = [line for line in proc.stdout.splitlines() if "radiosity" in line]
    report = f"{result}\n{stats}"
    assert result["lit"] > 0.05, report
    assert result["shadow"] < 0.3 * result["lit"], report
    # 10%-90% ramp across the edge at 8M rays: measured 26.8 px with 11,330 patches (the area
    # sizing alone: 40.2 px with 19,618 patches).
    assert result["width_px"] < 34.0, report
    # No more patches than the ray budget allows (rays / 256).
    patches = [int(m.replace(",", "")) for line in stats
               for m in re.findall(r"radiosity: ([\d,]+) patches", line)]
    assert patches and patches[0] <= 8000000 // 256, report
