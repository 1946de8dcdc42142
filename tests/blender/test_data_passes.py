"""Blender's data passes (Depth, Mist, Normal, Position, UV, Object and Material Index) and the
colour passes (Diffuse / Glossy / Transmission Color, Emit) from Photon match Cycles' on the
same scene (scripts/data_passes_scene.py: one sample through the pixel centre in both engines),
and enabled passes Photon cannot write are reported."""

import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio
import pytest

SCENE = Path(__file__).resolve().parent / "scripts" / "data_passes_scene.py"
DATA_PASSES = ("Depth", "Mist", "Normal", "Position", "UV", "IndexOB", "IndexMA")


def render(blender, out_prefix, engine, *extra):
    args = ["-o", f"{out_prefix}####", "-F", "OPEN_EXR_MULTILAYER", "--python", str(SCENE),
            "-f", "1", "--", engine, *extra]
    proc = blender.run(args, timeout=300)
    if engine == "PHOTON":
        assert "Photon: rendered frame 1" in proc.stdout, f"Photon did not render\n{proc.log}"
    return proc


def read_passes(path):
    """{pass: (H, W, channels) array} of the single view layer of a multilayer EXR (channels
    in the file's order)."""
    buf = oiio.ImageBuf(str(path))
    pixels = np.asarray(buf.get_pixels(oiio.FLOAT))
    passes = {}
    for index, name in enumerate(buf.spec().channelnames):
        _layer, render_pass, _channel = name.rsplit(".", 2)
        passes.setdefault(render_pass, []).append(pixels[..., index])
    return {p: np.stack(c, axis=-1) for p, c in passes.items()}


def jitter_tolerance(reference):
    """Per pixel: 1e-3 plus what the engines' different random offsets within the 0.01-pixel
    filter can change. Each sample lies within +-0.005 px of the centre, so two engines' samples
    are at most 0.01 px apart per axis: the value can differ by 0.01 (|d/dx| + |d/dy|), bounded
    by twice the largest step to a neighbouring pixel (large only at grazing angles)."""
    pad = np.pad(reference, ((1, 1), (1, 1), (0, 0)), mode="edge")
    h, w = reference.shape[:2]
    step = np.zeros((h, w))
    for dy, dx in ((0, 1), (2, 1), (1, 0), (1, 2)):
        step = np.maximum(step, np.abs(pad[dy:dy + h, dx:dx + w] - reference).max(-1))
    return 1e-3 + 0.02 * step


def interior(index):
    """Pixels whose 3 x 3 neighbourhood sees the same object: a silhouette's pixels are left
    out, since there the surface is seen edge-on and its normal and position change without
    bound within the jitter's 0.01 pixel."""
    pad = np.pad(index[..., 0], 1, mode="edge")
    h, w = index.shape[:2]
    same = np.ones((h, w), dtype=bool)
    for dy in range(3):
        for dx in range(3):
            same &= pad[dy:dy + h, dx:dx + w] == index[..., 0]
    return same


@pytest.mark.parametrize("camera", ["persp", "ortho"])
def test_data_passes_match_cycles(blender, tmp_path, camera):
    extra = ["ortho"] if camera == "ortho" else []
    render(blender, tmp_path / "photon_", "PHOTON", *extra)
    render(blender, tmp_path / "cycles_", "CYCLES", *extra)
    photon = read_passes(tmp_path / "photon_0001.exr")
    cycles = read_passes(tmp_path / "cycles_0001.exr")
    for name in DATA_PASSES:
        assert name in photon, f"Photon wrote no {name} pass: {sorted(photon)}"
        assert photon[name].shape == cycles[name].shape, name
    # The scene exercises every pass: background and three objects with their own indices.
    assert set(np.unique(cycles["IndexOB"])) == {0.0, 2.0, 7.0}
    assert set(np.unique(cycles["IndexMA"])) == {0.0, 3.0, 5.0, 9.0, 11.0}
    assert (cycles["Depth"] == 1e10).any() and (cycles["Mist"] < 0.5).any()
    # Which object a pixel sees: exactly Cycles'.
    for name in ("IndexOB", "IndexMA"):
        assert np.array_equal(photon[name], cycles[name]), name
    inside = interior(cycles["IndexOB"])
    assert inside.mean() > 0.8
    for name in ("Depth", "Mist", "Normal", "Position", "UV"):
        diff = np.abs(photon[name] - cycles[name]).max(-1)
        tol = jitter_tolerance(cycles[name])
        over = (diff > tol) & inside
        assert not over.any(), (
            f"{name}: {over.sum()} pixels differ from Cycles beyond the tolerance, max "
            f"{diff.max():.4g}; first at {np.argwhere(over)[:3].tolist()}")
        # Most pixels agree to 1e-3 outright (the tolerance widens only at grazing angles, as
        # on the orthographic view's floor).
        assert (diff <= 1e-3).mean() > 0.6, f"{name}: {(diff > 1e-3).mean():.1%} over 1e-3"


def test_unsupported_enabled_passes_are_reported_once(blender, tmp_path):
    proc = render(blender, tmp_path / "photon_", "PHOTON", "all")
    lines = [line for line in proc.stdout.splitlines()
             if line.startswith("Photon: warning: ") and "not rendered by Photon" in line]
    assert len(lines) == 1, proc.log
    assert "Ambient Occlusion" in lines[0] and "Environment" in lines[0], lines[0]
    assert "Mist" not in lines[0] and "Normal" not in lines[0], lines[0]
    passes = read_passes(tmp_path / "photon_0001.exr")
    assert (passes["Depth"] < 1e9).any()


def test_color_passes_match_cycles(blender, tmp_path):
    render(blender, tmp_path / "photon_", "PHOTON", "shaders")
    render(blender, tmp_path / "cycles_", "CYCLES", "shaders")
    photon = read_passes(tmp_path / "photon_0001.exr")
    cycles = read_passes(tmp_path / "cycles_0001.exr")
    inside = interior(cycles["IndexOB"])
    for name in ("DiffCol", "GlossCol", "TransCol", "Emit"):
        assert name in photon, f"Photon wrote no {name} pass: {sorted(photon)}"
        assert cycles[name].max() > 0.1, f"the scene does not exercise {name}"
        diff = np.abs(photon[name] - cycles[name]).max(-1)
        tol = jitter_tolerance(cycles[name])
        over = (diff > tol) & inside
        assert not over.any(), (
            f"{name}: {over.sum()} pixels differ from Cycles beyond the tolerance, max "
            f"{diff[inside].max():.4g}; first at {np.argwhere(over)[:3].tolist()}")


def test_alpha_threshold_matches_cycles(blender, tmp_path):
    """Single-sample passes (Depth, Position, indices, Normal, UV) come from the first hit at
    least Alpha Threshold opaque: through the Alpha 0 veil, at the Alpha 0.7 one. Mist and the
    colour passes add up along the path through the Alpha 0 veil (Cycles continues through
    the 0.7 one at random, so its pixels are left out there)."""
    render(blender, tmp_path / "photon_", "PHOTON", "veil")
    render(blender, tmp_path / "cycles_", "CYCLES", "veil")
    photon = read_passes(tmp_path / "photon_0001.exr")
    cycles = read_passes(tmp_path / "cycles_0001.exr")
    index = cycles["IndexOB"][..., 0]
    assert (index == 13).sum() > 50, "the Alpha 0.7 veil is not in view"
    assert (index == 12).sum() == 0, "Cycles stopped at the Alpha 0 veil"
    assert np.array_equal(photon["IndexOB"], cycles["IndexOB"])
    assert np.array_equal(photon["IndexMA"], cycles["IndexMA"])
    inside = interior(cycles["IndexOB"])
    for name in ("Depth", "Position", "Normal", "UV", "Mist", "DiffCol", "GlossCol", "Emit"):
        diff = np.abs(photon[name] - cycles[name]).max(-1)
        check = inside if name in ("Depth", "Position", "Normal", "UV") else inside & (index != 13)
        over = (diff > jitter_tolerance(cycles[name])) & check
        assert not over.any(), (
            f"{name}: {over.sum()} pixels differ from Cycles beyond the tolerance, max "
            f"{diff[check].max():.4g}; first at {np.argwhere(over)[:3].tolist()}")


def test_render_layers_node_shows_the_passes(blender):
    """update_render_passes registers the enabled passes: the compositor's Render Layers node
    offers them as outputs."""
    expr = ("import bpy; scene = bpy.context.scene; scene.render.engine = 'PHOTON'; "
            "layer = scene.view_layers[0]; "
            "[setattr(layer, p, True) for p in ('use_pass_z', 'use_pass_mist', "
            "'use_pass_normal', 'use_pass_position', 'use_pass_uv', 'use_pass_object_index', "
            "'use_pass_material_index', 'use_pass_diffuse_color', 'use_pass_glossy_color', "
            "'use_pass_transmission_color', 'use_pass_emit')]; "
            "scene.use_nodes = True; node = scene.node_tree.nodes['Render Layers']; "
            "print('SOCKETS', sorted(s.name for s in node.outputs if s.enabled))")
    proc = blender.run(["--python-expr", expr], timeout=120)
    line = next(line for line in proc.stdout.splitlines() if line.startswith("SOCKETS"))
    for name in DATA_PASSES + ("DiffCol", "GlossCol", "TransCol", "Emit"):
        assert f"'{name}'" in line, f"{name} missing: {line}"


def test_denoising_passes_match_cycles(blender, tmp_path):
    """Denoising Normal, Albedo and Depth (View Layer > Passes > Data > Denoising Data) follow
    Cycles' feature paths: through the specular-looking surfaces to the first rough one, with
    the albedo of its diffuse-like closures and the light met on the way (the emitting ball, the
    area light the camera sees, the world). The cube's glass top sends Cycles' single sample and
    Photon's different ways at random, so its pixels are compared as a mean only."""
    render(blender, tmp_path / "photon_", "PHOTON", "shaders", "denoise")
    render(blender, tmp_path / "cycles_", "CYCLES", "shaders", "denoise")
    photon = read_passes(tmp_path / "photon_0001.exr")
    cycles = read_passes(tmp_path / "cycles_0001.exr")
    index = cycles["IndexOB"][..., 0]
    inside = interior(cycles["IndexOB"])
    random_ways = index == 7
    for name, slack in (("Denoising Normal", 0.0), ("Denoising Depth", 0.0),
                        ("Denoising Albedo", 0.02)):
        assert name in photon, f"Photon wrote no {name} pass: {sorted(photon)}"
        assert np.abs(cycles[name]).max() > 0.5, f"the scene does not exercise {name}"
        diff = np.abs(photon[name] - cycles[name]).max(-1)
        # Principled's albedo: Photon's Fresnel of its specular, sheen and glass lobes at the
        # view is Schlick's where Cycles interpolates its own (about 1% of the albedo).
        tol = jitter_tolerance(cycles[name]) + slack
        over = (diff > tol) & inside & ~random_ways
        assert not over.any(), (
            f"{name}: {over.sum()} pixels differ from Cycles beyond the tolerance, max "
            f"{diff[inside & ~random_ways].max():.4g}; first at {np.argwhere(over)[:3].tolist()}")
    # The world (0.05, 0.05, 0.08) is the background's albedo; the emitting ball's and the
    # lamp's light add to the albedo of the surfaces behind them.
    sky = cycles["Depth"][..., 0] >= 1e9
    assert np.allclose(photon["Denoising Albedo"][sky], (0.05, 0.05, 0.08), atol=1e-6)
    assert photon["Denoising Albedo"].max() > 10.0
    ours = photon["Denoising Albedo"][random_ways].mean()
    theirs = cycles["Denoising Albedo"][random_ways].mean()
    assert abs(ours - theirs) < 0.2 * theirs, (ours, theirs)

