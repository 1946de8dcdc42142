"""Shader AOVs (View Layer > Shader AOV and the AOV Output node) from Photon match Cycles' on
the same scene (scripts/data_passes_scene.py with `aov`: one sample through the pixel centre in
both engines), and an AOV named like another pass is skipped and reported."""

import numpy as np

from test_data_passes import interior, jitter_tolerance, read_passes, render


def test_shader_aovs_match_cycles(blender, tmp_path):
    """Shader AOVs (View Layer > Shader AOV) as Cycles writes them: each AOV Output node writes
    the AOV of its name and kind (a noise colour and the height through the material's program,
    a constant, from inside a node group; a colour AOV node with only its Value set writes its
    Color, black), at every hit up to the first at least Alpha Threshold opaque: through the
    Alpha 0 veil both the veil's 100 and the height behind it, at the Alpha 0.7 veil its 100
    alone. The world writes a gradient of the direction and 50 where the camera sees it. Muted
    nodes and names the view layer does not list write nothing."""
    render(blender, tmp_path / "photon_", "PHOTON", "aov", "veil")
    render(blender, tmp_path / "cycles_", "CYCLES", "aov", "veil")
    photon = read_passes(tmp_path / "photon_0001.exr")
    cycles = read_passes(tmp_path / "cycles_0001.exr")
    index = cycles["IndexOB"][..., 0]
    inside = interior(cycles["IndexOB"])
    for name, channels in (("tint", 4), ("height", 1), ("unused", 1)):
        assert name in photon, f"Photon wrote no {name} pass: {sorted(photon)}"
        assert photon[name].shape == cycles[name].shape, (name, photon[name].shape)
        assert photon[name].shape[-1] == channels, name
        diff = np.abs(photon[name] - cycles[name]).max(-1)
        over = (diff > jitter_tolerance(cycles[name])) & inside
        assert not over.any(), (
            f"{name}: {over.sum()} pixels differ from Cycles beyond the tolerance, max "
            f"{diff[inside].max():.4g}; first at {np.argwhere(over)[:3].tolist()}")
        assert (diff <= 1e-3).mean() > 0.9, f"{name}: {(diff > 1e-3).mean():.1%} over 1e-3"
    # The scene exercises what the docstring says, in Cycles' image as in Photon's.
    assert not photon["unused"].any() and not cycles["unused"].any()
    for passes in (photon, cycles):
        sphere = inside & (index == 2)
        assert np.allclose(passes["tint"][sphere], (0.2, 0.4, 0.6, 1.0), atol=1e-6)
        assert (passes["height"][sphere][..., 0] > 0.0).all()
        assert (passes["height"][inside & (index == 13)] == 100.0).all()
        through = inside & (cycles["Depth"][..., 0] < 1e9) & (index != 13) & (index != 12)
        assert (passes["height"][through] >= 100.0).any(), "nothing seen through the veil"
        sky = inside & (cycles["Depth"][..., 0] >= 1e9)
        assert sky.sum() > 50 and (passes["tint"][sky][..., 3] == 1.0).all()
        assert passes["tint"][sky][..., :3].std() > 0.01, "the world's gradient is flat"
        assert np.isin(passes["height"][sky], (50.0, 150.0)).all()
    top = inside & (cycles["IndexMA"][..., 0] == 11)  # the cube's top face
    assert top.sum() > 20 and (photon["tint"][top] == (0.0, 0.0, 0.0, 1.0)).all()


def test_shader_aov_named_like_a_pass_is_skipped_and_reported(blender, tmp_path):
    """An AOV called Mist beside the Mist pass (a script can add one: Blender checks names only
    when the list is edited in its UI): as in Cycles, the Mist pass stays the mist, and Photon
    names the skipped AOV in its one warning about passes it does not write."""
    proc = render(blender, tmp_path / "photon_", "PHOTON", "aov", "clash")
    render(blender, tmp_path / "cycles_", "CYCLES", "aov", "clash")
    photon = read_passes(tmp_path / "photon_0001.exr")
    cycles = read_passes(tmp_path / "cycles_0001.exr")
    lines = [line for line in proc.stdout.splitlines()
             if line.startswith("Photon: warning: ") and "not rendered by Photon" in line]
    assert len(lines) == 1 and "AOV 'Mist'" in lines[0], proc.log
    diff = np.abs(photon["Mist"] - cycles["Mist"]).max(-1)
    inside = interior(cycles["IndexOB"])
    assert not ((diff > jitter_tolerance(cycles["Mist"])) & inside).any()
    assert photon["Mist"].min() < 0.5 < photon["Mist"].max()
    assert np.abs(photon["height"] - cycles["height"]).max() < 0.05
