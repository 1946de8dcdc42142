"""Soak tests: many renders and many bakes in one Blender process must not grow its memory.
Native scenes, photon maps, BVHs and texture caches are released after every frame and every
bake; the resident set size after warm-up and at the end must agree within 5%."""

import re
from pathlib import Path

import pytest

SCRIPTS = Path(__file__).resolve().parent / "scripts"

WARM_UP = 10  # frames (or bakes) before allocator pools and caches have settled
MAX_GROWTH = 0.05


@pytest.fixture(scope="module")
def soak_blend(blender, tmp_path_factory):
    blend = tmp_path_factory.mktemp("soak") / "soak.blend"
    blender.run_script("soak.py", "make", blend)
    return blend


def median(values):
    values = sorted(values)
    return values[len(values) // 2]


def growth(rss):
    """Median RSS of the last 10 samples against the 10 after warm-up: a single sample moves by
    a few MB as the allocator returns a frame's photon map to the system or keeps it."""
    warm, last = median(rss[WARM_UP:WARM_UP + 10]), median(rss[-10:])
    return (last - warm) / warm


def test_60_frame_animation_keeps_memory_flat(blender, soak_blend, tmp_path):
    # The script registers the per-frame handler, then -a renders (arguments after "--" go
    # to the script only).
    proc = blender.run([str(soak_blend), "-E", "PHOTON", "-o", str(tmp_path / "frame_####"),
                        "-F", "PNG", "--python", str(SCRIPTS / "soak.py"), "-a", "--",
                        str(tmp_path / "watch.json"), "render"], timeout=900)
    rss = [int(kb) for _, kb in re.findall(r"Photon soak: frame (\d+) rss (\d+)", proc.stdout)]
    assert len(rss) == 60, proc.log
    print(f"animation RSS: frames 11-20 {median(rss[WARM_UP:WARM_UP + 10]) / 1024:.1f} MB, "
          f"frames 51-60 {median(rss[-10:]) / 1024:.1f} MB, growth {100 * growth(rss):+.2f}%")
    assert growth(rss) < MAX_GROWTH, f"RSS per frame (kB): {rss}\n{proc.log}"


def test_30_bakes_keep_memory_flat(blender, soak_blend):
    result, proc = blender.run_script("soak.py", "bake", blend=soak_blend, timeout=900)
    assert result["results"] == [["FINISHED"]] * 30, proc.log
    rss = result["rss"]
    print(f"bake RSS: bakes 11-20 {median(rss[WARM_UP:WARM_UP + 10]) / 1024:.1f} MB, "
          f"bakes 21-30 {median(rss[-10:]) / 1024:.1f} MB, growth {100 * growth(rss):+.2f}%")
    assert growth(rss) < MAX_GROWTH, f"RSS per bake (kB): {rss}\n{proc.log}"
