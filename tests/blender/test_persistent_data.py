"""Render > Performance > Persistent Data: over `-a` the engine keeps meshes whose data did not
change (their arrays and BVHs) and re-syncs the rest, and every frame equals, bit for bit, the
same frame rendered with Persistent Data off. Scene: scripts/persistent_scene.py (Cornell box,
moving camera, a sphere that only moves, a plane whose shape key animates)."""

import re
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

FRAMES = (1, 2, 3)
MESHES = 9  # five walls, two boxes, the sphere, the shape-keyed plane
# Fewer photons than the default keep the photon-mapping frames quick; the photon maps, the
# final gathering are still computed every frame.
FAST = ("s.photon.photons = 20000; s.photon.final_gather_rays = 16; "
        "s.photon.irradiance_cache = False")
REUSED = re.compile(r"^Photon: persistent data: reused (\d+) of (\d+) meshes, (\d+) of (\d+) BVHs",
                    re.MULTILINE)


@pytest.fixture(scope="module")
def scene_blend(blender, tmp_path_factory):
    path = tmp_path_factory.mktemp("persistent") / "persistent.blend"
    result, proc = blender.run_script("persistent_scene.py", path)
    assert "exception" not in result, result.get("exception")
    assert len(result["meshes"]) == MESHES, result
    return path


def render_animation(blender, blend, tag, persistent, expr=""):
    """Renders every frame with `-a`; returns ({frame: pixels}, Blender's stdout)."""
    prefix = blend.parent / f"{tag}_"
    setup = (f"import bpy; s = bpy.context.scene; {FAST}; "
             f"s.render.use_persistent_data = {persistent}; {expr}")
    proc = blender.run([str(blend), "-E", "PHOTON", "--python-expr", setup,
                        "-o", f"{prefix}####", "-F", "OPEN_EXR", "-x", "1", "-a"], timeout=600)
    rendered = re.findall(r"^Photon: rendered frame (\d+)", proc.stdout, re.MULTILINE)
    assert [int(f) for f in rendered] == list(FRAMES), f"Photon did not render\n{proc.log}"
    return {f: read_image(f"{prefix}{f:04d}.exr") for f in FRAMES}, proc


def assert_bit_identical(image, reference, what):
    assert image.shape == reference.shape, what
    if not np.array_equal(image.view(np.uint32), reference.view(np.uint32)):
        differ = np.any(image != reference, axis=2)
        pytest.fail(f"{what}: {differ.sum()} pixels differ, max |diff| "
                    f"{np.nanmax(np.abs(image - reference)):.3g}")


def test_persistent_frames_equal_fresh_frames_and_reuse_static_meshes(blender, scene_blend):
    fresh, fresh_proc = render_animation(blender, scene_blend, "fresh", False)
    kept, kept_proc = render_animation(blender, scene_blend, "kept", True)
    assert not REUSED.search(fresh_proc.stdout), "no cache without Persistent Data"
    for frame in FRAMES:
        assert fresh[frame][:, :, :3].mean() > 0.01, f"frame {frame} is black"
        assert_bit_identical(kept[frame], fresh[frame], f"frame {frame}")
    assert not np.array_equal(fresh[1], fresh[3]), "the animation does not change the image"

    counts = [tuple(map(int, m)) for m in REUSED.findall(kept_proc.stdout)]
    assert len(counts) == len(FRAMES), kept_proc.log
    # Frame 1 reads every mesh; later frames reuse all but the shape-keyed plane (the sphere
    # only moves: a transform update keeps its mesh and BVH).
    assert counts[0] == (0, MESHES, 0, MESHES), kept_proc.log
    for later in counts[1:]:
        assert later == (MESHES - 1, MESHES, MESHES - 1, MESHES), kept_proc.log


def test_shape_key_edit_is_resynced(blender, scene_blend):
    """With only the shape key animated (camera and sphere still), the plane is re-synced each
    frame and the frames show it rising, exactly as fresh renders do."""
    still = ("[bpy.data.objects[n].animation_data_clear() for n in ('Camera', 'Ball')]")
    fresh, _ = render_animation(blender, scene_blend, "sheet_fresh", False, still)
    kept, proc = render_animation(blender, scene_blend, "sheet_kept", True, still)
    counts = [tuple(map(int, m)) for m in REUSED.findall(proc.stdout)]
    assert counts[1:] == [(MESHES - 1, MESHES, MESHES - 1, MESHES)] * 2, proc.log
    changed = np.any(kept[3] != kept[1], axis=2)
    assert changed.sum() > 50, "the rising plane does not show in frame 3"
    for frame in FRAMES:
        assert_bit_identical(kept[frame], fresh[frame], f"frame {frame}")
