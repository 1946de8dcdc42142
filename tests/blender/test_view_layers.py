"""Several view layers and stereo 3D through Blender's render pipeline: each view layer is
rendered with its own collections and passes into its own layer of the result, and each stereo
view from its own eye's camera (scene: scripts/view_layers_scene.py)."""

import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

SCENE = Path(__file__).resolve().parent / "scripts" / "view_layers_scene.py"
# As in view_layers_scene.py.
WIDTH, HEIGHT = 160, 96
LENS, SENSOR = 50.0, 36.0
INTEROCULAR, CONVERGENCE, DEPTH = 0.3, 1.95, 4.0


def render(blender, out_prefix, mode, *options, fmt="OPEN_EXR"):
    args = ["-o", f"{out_prefix}####", "-F", fmt, "--python", str(SCENE), "-f", "1",
            "--", mode, *options]
    proc = blender.run(args, timeout=300)
    assert "Photon: rendered frame 1" in proc.stdout, f"Photon did not render\n{proc.log}"
    return proc


def read_layers(path):
    """{layer: {pass: (H, W, channels) array}} of a multilayer EXR."""
    buf = oiio.ImageBuf(str(path))
    pixels = np.asarray(buf.get_pixels(oiio.FLOAT))
    layers = {}
    for index, name in enumerate(buf.spec().channelnames):
        layer, render_pass, _channel = name.rsplit(".", 2)
        layers.setdefault(layer, {}).setdefault(render_pass, []).append(pixels[..., index])
    return {layer: {p: np.stack(c, axis=-1) for p, c in passes.items()}
            for layer, passes in layers.items()}


def red_mask(rgb):
    """The red sphere: red well above green and blue (the floor is grey, the cube blue)."""
    return (rgb[..., 0] > 0.02) & (rgb[..., 0] > 4.0 * rgb[..., 1]) & (rgb[..., 0] > 4.0 * rgb[..., 2])


def blue_mask(rgb):
    return (rgb[..., 2] > 0.02) & (rgb[..., 2] > 4.0 * rgb[..., 0]) & (rgb[..., 2] > 4.0 * rgb[..., 1])


def test_each_view_layer_renders_its_own_collections_and_passes(blender, tmp_path):
    proc = render(blender, tmp_path / "layers_", "layers", fmt="OPEN_EXR_MULTILAYER")
    layers = read_layers(tmp_path / "layers_0001.exr")
    assert set(layers) == {"OnlyLeft", "OnlyRight"}, list(layers)
    only_left = layers["OnlyLeft"]["Combined"]
    only_right = layers["OnlyRight"]["Combined"]
    for name, image in (("OnlyLeft", only_left), ("OnlyRight", only_right)):
        assert image[..., :3].mean() > 0.02, f"{name} is black\n{proc.log}"
        assert image[..., 3].min() == 1.0, f"{name} has uncovered pixels"
    # Each layer shows its own collection's object and not the other's.
    assert red_mask(only_left).sum() > 200 and blue_mask(only_left).sum() == 0
    assert blue_mask(only_right).sum() > 200 and red_mask(only_right).sum() == 0
    # The red sphere is on the left of the frame, the blue cube on the right.
    assert np.nonzero(red_mask(only_left))[1].mean() < WIDTH / 2
    assert np.nonzero(blue_mask(only_right))[1].mean() > WIDTH / 2

    # Passes are per view layer: only OnlyLeft enabled Photon Direct.
    assert "Photon Direct" in layers["OnlyLeft"]
    assert "Photon Direct" not in layers["OnlyRight"]
    direct = layers["OnlyLeft"]["Photon Direct"]
    assert direct.mean() > 0.02
    assert np.all(direct <= only_left[..., :3] + 1e-5)

    # Each layer is the image of a one-layer scene excluding the same collection (same seed).
    for layer, excluded in (("OnlyLeft", "RightSet"), ("OnlyRight", "LeftSet")):
        render(blender, tmp_path / f"mono_{layer}_", "mono", f"exclude={excluded}")
        mono = read_image(tmp_path / f"mono_{layer}_0001.exr")
        diff = np.abs(mono - layers[layer]["Combined"]).max()
        assert diff < 1e-5, f"{layer} differs from its one-layer render by {diff}"


def test_indirect_only_collection_hides_from_camera_but_casts_shadow(blender, tmp_path):
    render(blender, tmp_path / "ind_", "mono", "exclude=RightSet", "indirect_only=LeftSet")
    render(blender, tmp_path / "none_", "mono", "exclude=RightSet,LeftSet")
    indirect = read_image(tmp_path / "ind_0001.exr")
    without = read_image(tmp_path / "none_0001.exr")
    assert red_mask(indirect).sum() == 0, "an indirect-only sphere was seen by the camera"
    # Its shadow on the floor remains.
    darker = (without[..., 0] - indirect[..., 0]) > 0.02
    assert darker.sum() > 50, f"no shadow of the indirect-only sphere ({darker.sum()} pixels)"


def test_holdout_collection_cuts_its_objects_out_of_the_layer(blender, tmp_path):
    render(blender, tmp_path / "plain_", "mono")
    proc = render(blender, tmp_path / "hold_", "mono", "holdout=LeftSet")
    warnings = [line for line in proc.stdout.splitlines() if line.startswith("Photon: warning")]
    assert not [w for w in warnings if "holdout" in w.lower()], proc.log  # supported: no warning
    plain = read_image(tmp_path / "plain_0001.exr")
    held = read_image(tmp_path / "hold_0001.exr")
    sphere = red_mask(plain)
    # Inside the sphere's outline (edge pixels are partly wall).
    inner = sphere.copy()
    for axis in (0, 1):
        for step in (1, -1):
            inner &= np.roll(sphere, step, axis=axis)
    assert inner.sum() > 200
    # The sphere's pixels are transparent black; the blue cube of the other collection stays.
    # (Mean, not max: the pixel filter spreads a little of the wall into the outline's rim.)
    assert held[inner][:, 3].mean() < 0.02 and held[inner][:, :3].mean() < 0.02, (
        held[inner][:, 3].mean(), held[inner][:, :3].mean())
    assert np.percentile(held[inner][:, 3], 90) < 0.01
    assert blue_mask(held).sum() == blue_mask(plain).sum() > 200


def expected_disparity_px():
    """Right-eye minus left-eye image x of a point DEPTH metres ahead, for off-axis stereo:
    each eye, half the interocular distance off centre, converges on CONVERGENCE, so a point
    at depth d moves by (I / 2) (1 / C - 1 / d) of the image-plane width sensor / lens."""
    per_eye = 0.5 * INTEROCULAR * (1.0 / CONVERGENCE - 1.0 / DEPTH)
    return 2.0 * per_eye * WIDTH / (SENSOR / LENS)


def centroid_x(image):
    cols = np.nonzero(red_mask(image))[1]
    assert cols.size > 200, f"the red sphere covers only {cols.size} pixels"
    return cols.mean()


def test_stereo_views_render_from_each_eye(blender, tmp_path):
    render(blender, tmp_path / "st_", "stereo")
    left = read_image(tmp_path / "st_0001_L.exr")
    right = read_image(tmp_path / "st_0001_R.exr")
    assert left[..., :3].mean() > 0.02 and right[..., :3].mean() > 0.02
    disparity = centroid_x(right) - centroid_x(left)
    expected = expected_disparity_px()  # 17.5 px
    print(f"stereo disparity {disparity:.2f} px, expected {expected:.2f} px")
    assert abs(disparity - expected) < 1.0, (disparity, expected)

    # Each view is the mono image of that eye's camera: moved half the interocular distance
    # along the camera's x, with the lens shift that converges the eyes (Blender's off-axis
    # stereo: shift += (I / sensor) (lens / C) / 2, plus for the left eye).
    shift = 0.5 * (INTEROCULAR / SENSOR) * (LENS / CONVERGENCE)
    monos = {}
    for eye, sign in (("L", -1.0), ("R", 1.0)):
        render(blender, tmp_path / f"eye{eye}_", "mono",
               f"cam_x={sign * INTEROCULAR / 2}", f"shift_x={-sign * shift}")
        monos[eye] = read_image(tmp_path / f"eye{eye}_0001.exr")
    for eye, view in (("L", left), ("R", right)):
        own = np.abs(view - monos[eye]).mean()
        other = np.abs(view - monos["R" if eye == "L" else "L"]).mean()
        print(f"view {eye}: mean |diff| to its eye's mono render {own:.2e}, to the other {other:.2e}")
        assert own < 1e-3 and other > 10.0 * own, (eye, own, other)


def test_material_override_of_a_view_layer(blender, tmp_path):
    render(blender, tmp_path / "own_", "mono")
    render(blender, tmp_path / "over_", "mono", "material_override=Grey")
    own = read_image(tmp_path / "own_0001.exr")
    over = read_image(tmp_path / "over_0001.exr")
    assert red_mask(own).sum() > 200 and blue_mask(own).sum() > 200
    # Every surface is the grey floor material: no red sphere, no blue cube, still lit.
    assert red_mask(over).sum() == 0 and blue_mask(over).sum() == 0
    assert over[..., :3].mean() > 0.02
    np.testing.assert_allclose(over[..., 0], over[..., 2], atol=1e-4)


def test_stereo_pivot_left_keeps_the_left_eye_on_the_camera(blender, tmp_path):
    # Blender's default pivot: the left eye is the camera itself, the right eye is a whole
    # interocular distance to its right with the whole convergence shift.
    render(blender, tmp_path / "pl_", "stereo", "pivot=LEFT")
    render(blender, tmp_path / "cam_", "mono")
    shift = (INTEROCULAR / SENSOR) * (LENS / CONVERGENCE)
    render(blender, tmp_path / "far_", "mono", f"cam_x={INTEROCULAR}", f"shift_x={-shift}")
    left = read_image(tmp_path / "pl_0001_L.exr")
    right = read_image(tmp_path / "pl_0001_R.exr")
    assert np.abs(left - read_image(tmp_path / "cam_0001.exr")).max() < 1e-5
    own = np.abs(right - read_image(tmp_path / "far_0001.exr")).mean()
    other = np.abs(right - left).mean()
    assert own < 1e-3 and other > 10.0 * own, (own, other)
