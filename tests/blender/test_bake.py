"""Lighting bake: the native bake API from plain Python, the photon.bake_lighting
operator on the Cornell box against a render of the same scene, and bad input."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402


# ---- Native API, no Blender ----

def plane_under_point_light(native, flipped=False):
    scene = native.Scene()
    material = scene.add_material("grey", [{"type": "DIFFUSE", "params": {"color": [0.5, 0.5, 0.5]}}])
    positions = np.array([[-10, -10, 0], [10, -10, 0], [10, 10, 0], [-10, 10, 0]], np.float32)
    triangles = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    if flipped:
        triangles = triangles[:, ::-1].copy()
    mesh = scene.add_mesh("plane", positions, triangles)["index"]
    scene.add_instance(mesh, np.eye(4, dtype=np.float32), [material])
    light = np.eye(4, dtype=np.float32)
    light[2, 3] = 1.0
    scene.add_light("lamp", "POINT", light, [1, 1, 1], 100.0)
    return scene


def settings_for(native, samples=8):
    settings = native.RenderSettings()
    settings.samples = samples
    settings.photons = 20000
    settings.integrator = native.Integrator.PHOTON_MAP
    return settings


def barycentrics_on_first_triangle(xy):
    # Triangle (p0, p1, p2) = ((-10,-10), (10,-10), (10,10)): x = -10 + 20(u + v), y = -10 + 20 v.
    v = (xy[:, 1] + 10.0) / 20.0
    u = (xy[:, 0] + 10.0) / 20.0 - v
    return np.stack([u, v], axis=1).astype(np.float32)


def test_native_bake_matches_inverse_square_law(native):
    xy = np.array([[0, 0], [0.3, 0.0], [0.5, -0.5], [2.0, -1.0]], np.float32)
    intensity = 100.0 / (4.0 * np.pi)
    d2 = 1.0 + (xy ** 2).sum(axis=1)
    expected = 0.5 / np.pi * intensity / np.sqrt(d2) / d2
    for flipped in (False, True):
        scene = plane_under_point_light(native, flipped)
        bary = barycentrics_on_first_triangle(xy)
        if flipped:  # corners (2, 1, 0): new (u, v) = old (b1, b0)
            bary = np.stack([bary[:, 0], 1.0 - bary[:, 0] - bary[:, 1]], axis=1)
        n = len(xy)
        result = native.bake(scene, settings_for(native), np.zeros(n, np.int32),
                             np.zeros(n, np.int32), bary)
        assert result["radiance"].shape == (n, 3) and result["radiance"].dtype == np.float32
        assert (result["status"] == native.BAKE_OK).all()
        np.testing.assert_allclose(result["position"][:, :2], xy, atol=1e-5)
        np.testing.assert_allclose(result["radiance"][:, 0], expected, rtol=0.01)
        assert (result["normal"][:, 2] > 0.99).all()  # the lit side, whatever the winding


def test_native_bake_session_is_thread_independent_and_reports_bad_points(native):
    scene = plane_under_point_light(native)
    xy = np.random.default_rng(1).uniform(-3, 3, size=(200, 2)).astype(np.float32)
    bary = barycentrics_on_first_triangle(xy)
    n = len(xy)
    instances = np.zeros(n, np.int32)
    triangles = np.zeros(n, np.int32)
    instances[5] = 7      # no such instance
    triangles[6] = 9      # no such triangle
    results = []
    for threads in (1, 2):
        settings = settings_for(native, samples=4)
        settings.threads = threads
        session = native.BakeSession(scene, settings, instances, triangles, bary)
        session.start()
        session.wait()
        assert session.finished and not session.cancelled
        results.append(session.result())
    a, b = results
    np.testing.assert_array_equal(a["radiance"], b["radiance"])
    assert a["status"][5] == native.BAKE_INVALID_POINT
    assert a["status"][6] == native.BAKE_INVALID_POINT
    assert any("2 point(s)" in w for w in a["warnings"])


def test_native_bake_errors_when_the_integrator_cannot_bake(native):
    scene = plane_under_point_light(native)
    settings = settings_for(native)
    settings.integrator = native.Integrator.RAY_TRACE
    try:
        native.bake(scene, settings, np.zeros(1, np.int32), np.zeros(1, np.int32),
                    np.full((1, 2), 0.2, np.float32))
    except RuntimeError as exc:
        assert "RAY_TRACE" in str(exc)
    else:
        raise AssertionError("baking with RAY_TRACE did not raise")


# ---- Through Blender ----

@pytest.mark.parametrize("source", ["PHOTON_MAP", "RADIOSITY"])
def test_bake_matches_render_on_cornell_box(blender, tmp_path, source):
    exr = tmp_path / "cornell.exr"
    result, proc = blender.run_script("bake_cornell.py", exr, 6, source, timeout=900)
    assert "exception" not in result, result.get("exception")
    assert result["bake"] == ["FINISHED"], proc.log
    for name, info in result["objects"].items():
        assert info is not None, f"{name} has no PhotonLighting attribute"
        assert info["domain"] == "CORNER" and info["data_type"] == "FLOAT_COLOR"
        assert info["count"] == info["loops"]
    image = read_image(exr)[:, :, :3]
    # 3 x 3 box filter (less render noise; little lighting change over ~2 cm), then bilinear
    # interpolation at the point's exact image position.
    padded = np.pad(image, ((1, 1), (1, 1), (0, 0)), mode="edge")
    smooth = sum(padded[dy:dy + image.shape[0], dx:dx + image.shape[1]]
                 for dy in range(3) for dx in range(3)) / 9.0
    baked, rendered, objects = [], [], []
    for point in result["points"]:
        assert point["corner_spread"] == 0.0  # corners of a flat interior vertex are averaged
        fx, fy = point["pixel"][0] - 0.5, point["pixel"][1] - 0.5
        x, y = int(np.floor(fx)), int(np.floor(fy))
        tx, ty = fx - x, fy - y
        rendered.append((1 - ty) * ((1 - tx) * smooth[y, x] + tx * smooth[y, x + 1])
                        + ty * ((1 - tx) * smooth[y + 1, x] + tx * smooth[y + 1, x + 1]))
        baked.append(point["value"])
        objects.append(point["object"])
    baked, rendered = np.array(baked), np.array(rendered)
    assert len(baked) >= 100, f"only {len(baked)} comparable points"
    assert set(objects) >= {"Floor", "Back", "Left", "Right", "Ceiling"}
    # Luminance-like sum over channels; relative error per point.
    b, r = baked.sum(axis=1), rendered.sum(axis=1)
    rel = np.abs(b - r) / r
    summary = {"points": int(len(rel)), "mean_rel_error": float(rel.mean()),
               "median_rel_error": float(np.median(rel)),
               "p90_rel_error": float(np.percentile(rel, 90)),
               "mean_bias": float((b.sum() - r.sum()) / r.sum())}
    print("bake vs render:", json.dumps(summary))
    (tmp_path / "bake_vs_render.json").write_text(json.dumps(summary, indent=1))
    assert summary["mean_rel_error"] < 0.05, summary
    assert abs(summary["mean_bias"]) < 0.05, summary


def test_bake_bad_input_warns_and_does_not_crash(blender):
    result, proc = blender.run_script("bake_bad_input.py", timeout=600)
    assert "exception" not in result, result.get("exception")
    assert result["no_meshes"] == ["CANCELLED"]
    assert "no mesh object with faces to bake into" in proc.stdout + proc.stderr
    assert result["mixed"] == ["FINISHED"]
    assert result["attributes"]["Good"] == ["CORNER", "FLOAT_COLOR"]
    assert result["attributes"]["NaNVertex"] == ["CORNER", "FLOAT_COLOR"]
    assert result["attributes"]["NoFaces"] is None
    assert result["attributes"]["Subdivided"] is None
    assert result["finite"]["NaNVertex"] and result["finite"]["Good"]
    assert result["good_max"] > 0.0
    out = proc.stdout
    assert "Object 'NoFaces': no faces to bake; skipped" in out
    assert "Object 'NaNVertex': 1 vertices with NaN" in out
    assert "Object 'Subdivided': its modifiers change the mesh topology" in out
    # The lightmap path on the same scene.
    assert result["lightmap"] == ["FINISHED"]
    assert result["lightmap_image"]["size"] == [32, 32]
    assert result["lightmap_image"]["packed"]
    assert result["lightmap_image"]["covered_fraction"] > 0.3
