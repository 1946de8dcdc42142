"""Tests of tools/regress.py without Blender: a fake `blender` executable written into tmp_path
imitates Blender's command line. Each fake .blend is a JSON file telling the fake what to do
(write an image, crash, hang, skip the Photon line ...)."""

import json
import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio
import pytest

REPO = Path(__file__).resolve().parents[2]
TOOL = REPO / "tools" / "regress.py"
sys.path.insert(0, str(REPO / "tools"))
from regress_lib import compare, report  # noqa: E402

FAKE_BLENDER = textwrap.dedent('''\
    #!{python}
    """Fake Blender: -b --factory-startup --addons photon X.blend -E ENGINE [--python-expr E]
    -o PREFIX#### -F OPEN_EXR -x 1 -f N[,M...]"""
    import json, os, re, resource, shutil, signal, subprocess, sys, time
    args = sys.argv[1:]
    version = os.environ.get("FAKE_BLENDER_VERSION", "3.4.1")
    if "--version" in args:
        print(f"Blender {{version}} (fake)")
        sys.exit(0)
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "calls.jsonl"), "a") as f:
        f.write(json.dumps({{"args": args, "scripts": os.environ.get("BLENDER_USER_SCRIPTS")}})
                + "\\n")
    blend = next(a for a in args if a.endswith(".blend"))
    def value(flag):
        return args[args.index(flag) + 1] if flag in args else None
    print(f"Blender {{version}} (fake)")
    try:
        spec = json.load(open(blend))
    except (OSError, ValueError):
        print(f"Error: File format is not supported in file '{{blend}}'")
        sys.exit(1)
    print(f"Read blend: {{blend}}")
    engine, prefix = value("-E"), value("-o")
    frames = [int(f) for f in value("-f").split(",")]
    expr = value("--python-expr")
    if expr:
        samples = re.search(r"samples = (\\d+)", expr)
        print(f"regress: engine {{engine}} samples {{samples.group(1) if samples else None}}")
    mode = spec.get("mode", "ok")
    if mode == "hang":
        child = subprocess.Popen(["sleep", "300"])
        open(spec["child_pid_file"], "w").write(str(child.pid))
        time.sleep(300)
    for frame in frames:
        out = prefix.replace("####", f"{{frame:04d}}") + ".exr"
        if mode in ("crash_exit", "crash_signal"):
            open(out, "w").close()          # Blender leaves a 0-byte file when it crashes
            if mode == "crash_exit":
                sys.exit(139)
            resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
            os.kill(os.getpid(), signal.SIGSEGV)
        images = spec.get("cycles_images" if engine == "CYCLES" else "images", {{}})
        if mode != "no_file":
            shutil.copyfile(images.get(str(frame), images.get("*")), out)
        if engine == "PHOTON" and mode != "no_photon":
            print(f"Photon: rendered frame {{frame}} 8x8 (4 spp, 1 threads): total 0.001 s")
        print(f"Saved: '{{out}}'")
    print("Blender quit")
''')


def write_exr(path, pixels):
    """Writes a float32 (h, w, 4) array as an RGBA EXR through OpenImageIO."""
    pixels = np.ascontiguousarray(pixels, dtype=np.float32)
    h, w, c = pixels.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, c, oiio.FLOAT))
    buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, c), pixels)
    assert buf.write(str(path)), buf.geterror()
    return path


def gradient(h=8, w=8, scale=1.0):
    """A smooth test image with alpha 1."""
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    rgb = np.stack([0.2 + xx / w, 0.1 + yy / h, 0.5 + 0.0 * xx], axis=2) * scale
    return np.concatenate([rgb, np.ones((h, w, 1), np.float32)], axis=2)


class Suite:
    """A scene folder, image store and fake Blender inside tmp_path."""

    def __init__(self, tmp_path):
        self.root = tmp_path
        self.scenes = tmp_path / "scenes"
        self.images = tmp_path / "images"
        self.out = tmp_path / "out"
        self.bin = tmp_path / "bin"
        for d in (self.scenes, self.images, self.bin):
            d.mkdir()
        self.blender = self.bin / "blender"
        self.blender.write_text(FAKE_BLENDER.format(python=sys.executable))
        self.blender.chmod(0o755)
        self.addon_dir = tmp_path / "stage"

    def image(self, name, pixels):
        return str(write_exr(self.images / f"{name}.exr", pixels))

    def scene(self, name, render=None, reference=None, mode="ok", sidecar=None, frames=None,
              cycles=None, folder=None):
        """Adds NAME.blend (a JSON spec for the fake) with its reference(s) and sidecar."""
        folder = folder or self.scenes
        folder.mkdir(exist_ok=True)
        spec = {"mode": mode, "child_pid_file": str(self.root / f"{name}.child")}
        if render is not None:
            spec["images"] = ({str(f): self.image(f"{name}_r{f}", p) for f, p in render.items()}
                              if isinstance(render, dict) else {"*": self.image(name, render)})
        if cycles is not None:
            spec["cycles_images"] = {"*": self.image(f"{name}_cycles", cycles)}
        (folder / f"{name}.blend").write_text(json.dumps(spec))
        if isinstance(reference, dict):
            for frame, pixels in reference.items():
                write_exr(folder / f"{name}_{frame:04d}.exr", pixels)
        elif reference is not None:
            write_exr(folder / f"{name}.exr", reference)
        if sidecar is not None or frames is not None:
            data = dict(sidecar or {})
            if frames is not None:
                data["frames"] = frames
            (folder / f"{name}.json").write_text(json.dumps(data))

    def run(self, *extra, folders=None, timeout=60, version=None):
        cmd = [sys.executable, str(TOOL), *(str(f) for f in (folders or [self.scenes])),
               "--blender", str(self.blender), "--addon-dir", str(self.addon_dir),
               "--out", str(self.out), *extra]
        env = dict(os.environ, **({"FAKE_BLENDER_VERSION": version} if version else {}))
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
        proc.log = f"$ {' '.join(cmd)}\n{proc.stdout}\n{proc.stderr}"
        return proc

    def report(self):
        data = json.loads((self.out / "report.json").read_text())
        return {s["name"]: s for s in data["scenes"]}, data

    def calls(self):
        path = self.bin / "calls.jsonl"
        return [json.loads(line) for line in path.read_text().splitlines()] if path.exists() \
            else []


@pytest.fixture
def suite(tmp_path):
    return Suite(tmp_path)


# ---- End to end through the fake Blender ----

def test_identical_render_passes(suite):
    image = gradient()
    suite.scene("same", render=image, reference=image)
    proc = suite.run()
    assert proc.returncode == 0, proc.log
    scenes, data = suite.report()
    assert scenes["same"]["status"] == "PASS"
    metrics = scenes["same"]["frames"][0]["metrics"]
    assert metrics["rmse"] == 0.0 and metrics["max_error"] == 0.0
    assert data["summary"]["ok"] is True
    assert (suite.out / "report.html").exists()
    assert f"report {(suite.out / 'report.html').resolve()}" in proc.stdout
    call = suite.calls()[0]
    assert call["scripts"] == str(suite.addon_dir)
    args = call["args"]
    for flag in ("-b", "--factory-startup", "--addons", "photon", "-F", "OPEN_EXR"):
        assert flag in args
    assert args[args.index("-E") + 1] == "PHOTON"
    assert args[args.index("-f") + 1] == "1"


def test_changed_render_fails_with_report_and_images(suite):
    suite.scene("a_ok", render=gradient(), reference=gradient())
    suite.scene("b_changed", render=gradient(scale=1.2), reference=gradient())
    proc = suite.run()
    assert proc.returncode == 1, proc.log
    scenes, data = suite.report()
    changed = scenes["b_changed"]
    assert changed["status"] == "FAIL"
    assert "rel_rmse" in changed["reason"] and "mean_diff" in changed["reason"]
    assert changed["frames"][0]["metrics"]["mean_diff"] == pytest.approx(0.2, rel=1e-5)
    assert scenes["a_ok"]["status"] == "PASS"
    # Failures first, in the JSON and in the HTML.
    assert [s["name"] for s in data["scenes"]] == ["b_changed", "a_ok"]
    page = (suite.out / "report.html").read_text()
    assert page.index("b_changed") < page.index("a_ok")
    for kind in ("reference", "render", "diff"):
        png = suite.out / "images" / f"b_changed_0001_{kind}.png"
        assert png.exists(), png
        assert f"images/b_changed_0001_{kind}.png" in page
    diff = oiio.ImageBuf(str(suite.out / "images" / "b_changed_0001_diff.png"))
    assert diff.get_pixels(oiio.UINT8).max() > 0, "the difference image is black"
    assert "FAIL" in proc.stdout and "b_changed" in proc.stdout


def test_sidecar_thresholds_are_respected(suite):
    reference, render = gradient(), gradient(scale=1.005)   # 0.5% brighter everywhere
    suite.scene("strict", render=render, reference=reference)
    suite.scene("loose", render=render, reference=reference, sidecar={"thresholds": {
        "rel_rmse": 0.02, "mean_rel": 0.01, "mean_diff": 0.01, "pixel_threshold": 0.05,
        "pixel_fraction": 0.01}})
    suite.scene("tighter", render=render, reference=reference, sidecar={"thresholds": {
        "rel_rmse": 0.02, "mean_rel": 0.01, "mean_diff": 0.001, "pixel_threshold": 0.05}})
    proc = suite.run()
    scenes, _ = suite.report()
    assert scenes["strict"]["status"] == "FAIL", proc.log
    assert scenes["loose"]["status"] == "PASS", proc.log
    assert scenes["loose"]["frames"][0]["thresholds"]["rel_rmse"] == 0.02
    assert scenes["tighter"]["status"] == "FAIL"
    assert scenes["tighter"]["reason"].startswith("mean_diff")


def test_bad_sidecar_is_an_error(suite):
    suite.scene("typo", render=gradient(), reference=gradient(),
                sidecar={"thresholds": {"rel_rmes": 0.1}})
    proc = suite.run()
    scenes, _ = suite.report()
    assert proc.returncode == 1
    assert scenes["typo"]["status"] == "ERROR"
    assert "rel_rmes" in scenes["typo"]["reason"]


def test_missing_reference_is_a_failure_with_reason(suite):
    suite.scene("no_ref", render=gradient())
    proc = suite.run()
    assert proc.returncode == 1
    scenes, _ = suite.report()
    assert scenes["no_ref"]["status"] == "ERROR"
    assert "missing reference no_ref.exr" in scenes["no_ref"]["reason"]
    assert "missing reference" in proc.stdout
    assert (suite.out / "images" / "no_ref_0001_render.png").exists()


@pytest.mark.parametrize("mode, reason", [("crash_exit", "exited with status 139"),
                                          ("crash_signal", "killed by signal SIGSEGV")])
def test_crash_fails_and_the_next_scene_still_runs(suite, mode, reason):
    suite.scene("a_crash", render=gradient(), reference=gradient(), mode=mode)
    suite.scene("b_fine", render=gradient(), reference=gradient())
    proc = suite.run()
    assert proc.returncode == 1, proc.log
    scenes, _ = suite.report()
    assert scenes["a_crash"]["status"] == "ERROR"
    assert reason in scenes["a_crash"]["reason"]
    assert scenes["b_fine"]["status"] == "PASS"
    assert len(suite.calls()) == 2


def test_hanging_render_times_out_and_its_process_group_dies(suite):
    suite.scene("hang", render=gradient(), reference=gradient(), mode="hang")
    suite.scene("next", render=gradient(), reference=gradient())
    start = time.monotonic()
    proc = suite.run("--timeout", "2")
    assert time.monotonic() - start < 30
    scenes, _ = suite.report()
    assert scenes["hang"]["status"] == "ERROR"
    assert "timeout" in scenes["hang"]["reason"]
    assert scenes["next"]["status"] == "PASS"
    assert proc.returncode == 1
    child = int((suite.root / "hang.child").read_text())
    for _ in range(50):   # the grandchild (Blender's own children) must be killed too
        try:
            os.kill(child, 0)
        except ProcessLookupError:
            break
        time.sleep(0.1)
    else:
        os.kill(child, 9)
        pytest.fail("the hanging render's child process survived the timeout")


def test_sidecar_timeout_overrides_the_default(suite):
    suite.scene("hang", render=gradient(), reference=gradient(), mode="hang",
                sidecar={"timeout": 1})
    start = time.monotonic()
    suite.run("--timeout", "100")
    assert time.monotonic() - start < 20
    scenes, _ = suite.report()
    assert "timeout: no result after 1 s" in scenes["hang"]["reason"]


def test_missing_photon_line_means_another_engine_ran(suite):
    suite.scene("fallback", render=gradient(), reference=gradient(), mode="no_photon")
    proc = suite.run()
    assert proc.returncode == 1
    scenes, _ = suite.report()
    assert scenes["fallback"]["status"] == "ERROR"
    assert "Photon did not render" in scenes["fallback"]["reason"]


def test_missing_output_file_is_an_error_even_with_a_stale_one(suite):
    suite.scene("nofile", render=gradient(), reference=gradient())
    assert suite.run().returncode == 0
    assert (suite.out / "renders" / "nofile_0001.exr").exists()
    # Same output folder, and now Blender writes nothing: the old file must not count.
    suite.scene("nofile", render=gradient(), reference=gradient(), mode="no_file")
    suite.run()
    scenes, _ = suite.report()
    assert scenes["nofile"]["status"] == "ERROR"
    assert "no output file nofile_0001.exr" in scenes["nofile"]["reason"]


def test_corrupt_blend_is_an_error(suite):
    (suite.scenes / "corrupt.blend").write_text("not a blend file")
    write_exr(suite.scenes / "corrupt.exr", gradient())
    suite.scene("fine", render=gradient(), reference=gradient())
    proc = suite.run()
    scenes, _ = suite.report()
    assert scenes["corrupt"]["status"] == "ERROR"
    assert "exited with status 1" in scenes["corrupt"]["reason"]
    assert "File format is not supported" in scenes["corrupt"]["reason"]
    assert scenes["fine"]["status"] == "PASS"
    assert proc.returncode == 1


def test_nan_in_render_fails(suite):
    bad = gradient()
    bad[2, 3, 1] = np.nan
    suite.scene("nan", render=bad, reference=gradient())
    suite.run()
    scenes, _ = suite.report()
    assert scenes["nan"]["status"] == "FAIL"
    assert "1 NaN/infinite" in scenes["nan"]["reason"]


def test_size_mismatch_fails(suite):
    suite.scene("size", render=gradient(8, 8), reference=gradient(8, 16))
    suite.run()
    scenes, _ = suite.report()
    assert scenes["size"]["status"] == "FAIL"
    assert "size mismatch: render 8x8, reference 16x8" in scenes["size"]["reason"]


def test_animation_compares_every_frame(suite):
    frames = {f: gradient(scale=1.0 + 0.1 * f) for f in (1, 2, 3)}
    suite.scene("anim", render=frames, reference=frames, frames=[1, 2, 3])
    wrong = dict(frames)
    wrong[2] = gradient(scale=2.0)
    suite.scene("anim_bad", render=wrong, reference=frames, frames=[1, 2, 3])
    suite.run()
    scenes, _ = suite.report()
    assert scenes["anim"]["status"] == "PASS"
    assert [f["frame"] for f in scenes["anim"]["frames"]] == [1, 2, 3]
    bad = scenes["anim_bad"]
    assert bad["status"] == "FAIL"
    assert [f["status"] for f in bad["frames"]] == ["PASS", "FAIL", "PASS"]
    assert bad["reason"].startswith("frame 2:")
    args = suite.calls()[0]["args"]
    assert args[args.index("-f") + 1] == "1,2,3"


def test_only_selects_scenes(suite):
    suite.scene("a", render=gradient(), reference=gradient())
    suite.scene("b", render=gradient(scale=3), reference=gradient())
    proc = suite.run("--only", "a")
    assert proc.returncode == 0, proc.log
    scenes, _ = suite.report()
    assert list(scenes) == ["a"]
    assert suite.run("--only", "nope").returncode == 2


def test_update_replaces_references_and_reports_changes(suite):
    suite.scene("same", render=gradient(), reference=gradient())
    suite.scene("changed", render=gradient(scale=1.1), reference=gradient())
    suite.scene("new", render=gradient(scale=0.5))
    proc = suite.run("--update")
    assert proc.returncode == 0, proc.log
    scenes, _ = suite.report()
    assert scenes["same"]["status"] == "IDENTICAL"
    assert scenes["changed"]["status"] == "CHANGED"
    assert "rel_rmse" in scenes["changed"]["reason"]
    assert scenes["new"]["status"] == "NEW"
    out = proc.stdout
    assert "IDENTICAL" in out and "CHANGED" in out and "NEW" in out
    assert "changed.exr changed: rel_rmse" in out
    np.testing.assert_array_equal(compare.read_rgba(suite.scenes / "changed.exr"),
                                  gradient(scale=1.1))
    np.testing.assert_array_equal(compare.read_rgba(suite.scenes / "new.exr"),
                                  gradient(scale=0.5))
    # After the update, a normal run passes.
    assert suite.run().returncode == 0


def test_update_renders_validation_scenes_with_the_reference_engine(suite):
    suite.scene("val", render=gradient(), cycles=gradient(scale=0.9),
                sidecar={"reference_engine": "CYCLES", "reference_samples": 64,
                         "thresholds": {"mean_diff": 0.2, "rel_rmse": 0.2, "mean_rel": 0.2,
                                        "pixel_threshold": 0.2}})
    proc = suite.run("--update")
    assert proc.returncode == 0, proc.log
    args = suite.calls()[0]["args"]
    assert args[args.index("-E") + 1] == "CYCLES"
    assert "s.cycles.samples = 64" in args[args.index("--python-expr") + 1]
    np.testing.assert_array_equal(compare.read_rgba(suite.scenes / "val.exr"),
                                  gradient(scale=0.9))
    # The check renders with Photon and compares with the looser validation thresholds.
    proc = suite.run()
    args = suite.calls()[1]["args"]
    assert args[args.index("-E") + 1] == "PHOTON"
    scenes, _ = suite.report()
    assert scenes["val"]["status"] == "PASS", proc.log
    assert scenes["val"]["validation"] is True


def test_another_blender_uses_its_own_references(suite):
    # Blender 3.4's reference beside the scene; Blender 4.3 renders and reads blender-4.3/.
    sidecar = {"reference_engine": "CYCLES", "reference_samples": 64}
    suite.scene("val", render=gradient(), reference=gradient(scale=2.0),
                cycles=gradient(scale=1.0001), sidecar=sidecar)
    proc = suite.run(version="4.3.2")
    assert proc.returncode == 1, proc.log
    assert "Blender 4.3, references in blender-4.3/" in proc.stdout
    assert "missing reference" in suite.report()[0]["val"]["reason"]
    proc = suite.run("--update", version="4.3.2")
    assert proc.returncode == 0, proc.log
    np.testing.assert_array_equal(
        compare.read_rgba(suite.scenes / "blender-4.3" / "val.exr"), gradient(scale=1.0001))
    np.testing.assert_array_equal(compare.read_rgba(suite.scenes / "val.exr"),
                                  gradient(scale=2.0))
    assert suite.run(version="4.3.2").returncode == 0
    # Blender 3.4 still compares with its own (here far off) reference.
    assert suite.run().returncode == 1


def test_update_keeps_references_when_the_render_fails(suite):
    suite.scene("crashy", render=gradient(scale=2), reference=gradient(), mode="crash_exit")
    proc = suite.run("--update")
    assert proc.returncode == 1
    np.testing.assert_array_equal(compare.read_rgba(suite.scenes / "crashy.exr"), gradient())


# ---- Metrics on hand-made arrays ----

def test_metrics_uniform_offset():
    reference = np.ones((4, 4, 4), np.float32)
    image = reference.copy()
    image[:, :, :3] += 0.2
    m = compare.compute_metrics(image, reference, pixel_threshold=0.1)
    assert m["mean_abs"] == pytest.approx(0.2)
    assert m["rmse"] == pytest.approx(0.2)
    assert m["rel_rmse"] == pytest.approx(0.2)
    assert m["mean_rel"] == pytest.approx(0.2 / (1.0 + compare.EPS))
    assert m["mean_image"] == pytest.approx(1.2)
    assert m["mean_reference"] == pytest.approx(1.0)
    assert m["mean_diff"] == pytest.approx(0.2)
    assert m["pixel_fraction"] == 1.0
    assert m["max_error"] == pytest.approx(0.2)
    assert m["alpha_max"] == 0.0


def test_metrics_single_pixel_error():
    reference = np.full((4, 4, 4), 0.5, np.float32)
    image = reference.copy()
    image[1, 2, 0] += 0.4        # one channel of one pixel of 16
    image[3, 3, 3] = 0.25        # alpha differs elsewhere
    m = compare.compute_metrics(image, reference, pixel_threshold=0.5)
    n = 16 * 3
    assert m["mean_abs"] == pytest.approx(0.4 / n)
    assert m["rmse"] == pytest.approx(np.sqrt(0.16 / n))
    assert m["rel_rmse"] == pytest.approx(np.sqrt(0.16 / n) / 0.5)
    assert m["mean_rel"] == pytest.approx(0.4 / 0.51 / n)
    assert m["mean_diff"] == pytest.approx((0.4 / n) / 0.5)
    assert m["pixel_fraction"] == pytest.approx(1 / 16)   # 0.4 / 0.51 = 0.78 > 0.5
    assert m["max_error"] == pytest.approx(0.4)
    assert m["alpha_max"] == pytest.approx(0.25)  # reference alpha is 0.5 here


def test_metrics_black_reference():
    black = np.zeros((2, 2, 4), np.float32)
    assert compare.compute_metrics(black, black)["rel_rmse"] == 0.0
    lit = black.copy()
    lit[0, 0, :3] = 0.01
    assert compare.compute_metrics(lit, black)["rel_rmse"] > 1.0


def test_check_metrics_and_thresholds():
    thresholds = compare.merged_thresholds({"rel_rmse": 0.1, "max_error": None})
    assert thresholds["mean_rel"] == compare.DEFAULT_THRESHOLDS["mean_rel"]
    metrics = {key: 0.0 for key in compare.CHECKED}
    assert compare.check_metrics(metrics, thresholds) == []
    metrics["rel_rmse"] = 0.2
    metrics["max_error"] = 1e9          # unchecked (None)
    assert compare.check_metrics(metrics, thresholds) == ["rel_rmse 0.2 > 0.1"]
    metrics["mean_rel"] = float("nan")  # NaN never passes
    assert len(compare.check_metrics(metrics, thresholds)) == 2
    with pytest.raises(ValueError):
        compare.merged_thresholds({"bogus": 1})


def test_compare_arrays_reasons():
    t = compare.merged_thresholds()
    a = gradient()
    assert compare.compare_arrays(a, a, t)["ok"]
    assert "size mismatch" in compare.compare_arrays(a, gradient(4, 8), t)["reason"]
    bad = a.copy()
    bad[0, 0, 0] = np.inf
    assert "reference has 1 NaN" in compare.compare_arrays(a, bad, t)["reason"]


def test_read_rgba_fills_missing_alpha_and_rejects_garbage(tmp_path):
    rgb = gradient()[:, :, :3]
    write_exr(tmp_path / "rgb.exr", rgb)
    pixels = compare.read_rgba(tmp_path / "rgb.exr")
    assert pixels.shape == (8, 8, 4)
    np.testing.assert_array_equal(pixels[:, :, :3], rgb)
    assert (pixels[:, :, 3] == 1).all()
    (tmp_path / "junk.exr").write_text("junk")
    with pytest.raises(compare.ImageError):
        compare.read_rgba(tmp_path / "junk.exr")


def test_srgb_tone_mapping():
    values = np.array([[[0.0, 1.0, 0.5], [2.0, -1.0, 0.0031308]]], np.float32)
    out = report.to_srgb8(values)
    assert out.tolist() == [[[0, 255, 188], [255, 0, 10]]]
    reference = np.zeros((10, 10, 4), np.float32)
    reference[..., :3] = 4.0
    assert report.exposure_scale(reference) == pytest.approx(0.25)
    assert report.exposure_scale(np.zeros((2, 2, 4), np.float32)) == 1.0


def test_parallel_jobs_run_every_scene(suite):
    for name in ("p1", "p2", "p3"):
        suite.scene(name, render=gradient(), reference=gradient())
    suite.scene("p4", render=gradient(scale=2), reference=gradient())
    proc = suite.run("-j", "2")
    scenes, _ = suite.report()
    assert [scenes[n]["status"] for n in ("p1", "p2", "p3", "p4")] == ["PASS"] * 3 + ["FAIL"]
    assert proc.returncode == 1
