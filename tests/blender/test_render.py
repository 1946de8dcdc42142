"""Headless renders through Blender's own command line: the demo scene against its stored
reference, animations, single frames, output formats and render borders."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "test_scenes" / "cornell_box.blend"
CORNELL_REFERENCE = REPO / "test_scenes" / "cornell_box.exr"

# The reference is Photon's own output at the stored seed. Renders are deterministic, so only
# floating-point differences between CPUs (Embree picks SSE/AVX kernels at run time) are allowed.
REFERENCE_MAX_RELATIVE_RMSE = 0.005
REFERENCE_MAX_MEAN_DIFFERENCE = 0.001


# The Cornell box at a fraction of its shipped samples and photons, for tests that check an
# output path or pixel bookkeeping rather than the image itself.
QUICK = ("--python-expr", "import bpy; p = bpy.context.scene.photon; p.samples = 8; "
         "p.photons = 20000; p.caustic_photons = 10000")


def render_frames(blender, blend, out_prefix, *frame_args, fmt="OPEN_EXR", extra=()):
    proc = blender.run([str(blend), "-E", "PHOTON", "-o", f"{out_prefix}####", "-F", fmt,
                        "-x", "1", *extra, *frame_args])
    assert "Photon: rendered frame" in proc.stdout, f"Photon did not render\n{proc.log}"
    return proc


def test_cornell_box_matches_stored_reference(blender, tmp_path):
    render_frames(blender, CORNELL, tmp_path / "cornell_", "-f", "1")
    image = read_image(tmp_path / "cornell_0001.exr")
    reference = read_image(CORNELL_REFERENCE)
    assert image.shape == reference.shape
    rgb, ref = image[:, :, :3], reference[:, :, :3]
    assert ref.mean() > 0.05, "reference is black"
    rmse = float(np.sqrt(np.mean((rgb - ref) ** 2)))
    print(f"cornell vs reference: relative RMSE {rmse / ref.mean():.2e}, "
          f"mean {rgb.mean():.5f} vs {ref.mean():.5f}")
    assert rmse / ref.mean() < REFERENCE_MAX_RELATIVE_RMSE
    assert abs(rgb.mean() - ref.mean()) / ref.mean() < REFERENCE_MAX_MEAN_DIFFERENCE


def test_exr_output_is_scene_linear_float(blender, tmp_path):
    """EXR keeps linear radiance (no view transform): the world colour comes out exactly."""
    import OpenImageIO as oiio
    blend = tmp_path / "no_lights.blend"
    blender.run_script("make_bad_scene.py", "no_lights", blend)
    render_frames(blender, blend, tmp_path / "world_", "-f", "1")
    spec = oiio.ImageInput.open(str(tmp_path / "world_0001.exr")).spec()
    assert str(spec.format) in ("float", "half")
    image = read_image(tmp_path / "world_0001.exr")
    # The camera looks into the open side of the box: the corners show the world.
    assert image[0, 0, :3] == pytest.approx([0.2, 0.3, 0.4], abs=1e-3)


def test_exr_metadata_holds_the_render_statistics(blender, tmp_path):
    """As Cycles writes cycles.<view layer>.samples and its times into the image's metadata,
    Photon writes photon.<view layer>.*: integrator, samples, threads, times (Blender's
    MM:SS.cc timecodes) and peak memory."""
    import re

    import OpenImageIO as oiio
    proc = render_frames(blender, CORNELL, tmp_path / "meta_", "-f", "1", extra=QUICK)
    spec = oiio.ImageInput.open(str(tmp_path / "meta_0001.exr")).spec()
    fields = {a.name: a.value for a in spec.extra_attribs if a.name.startswith("photon.")}
    layer = "photon.ViewLayer."
    assert fields[layer + "integrator"] == "PHOTON_MAP", fields
    assert fields[layer + "samples"] == "8"
    match = re.search(r"\((\d+) spp, (\d+) threads\)", proc.stdout)
    assert match and fields[layer + "threads"] == match.group(2), proc.log
    times = {}
    for key in ("total_time", "synchronization_time", "preparation_time", "render_time"):
        value = fields[layer + key]
        assert re.fullmatch(r"\d\d:\d\d\.\d\d", value), (key, value)
        minutes, seconds = value.split(":")
        times[key] = 60 * int(minutes) + float(seconds)
    # The photon maps and the render take time; the parts add up to no more than the total.
    assert times["preparation_time"] > 0.0 and times["render_time"] > 0.0
    parts = times["synchronization_time"] + times["preparation_time"] + times["render_time"]
    assert parts <= times["total_time"] + 0.03, times
    assert re.fullmatch(r"\d+\.\dM", fields[layer + "peak_memory"])


def test_time_limit_stops_at_whole_samples_and_says_how_many(blender, tmp_path):
    """Render > Time Limit: far more samples than the budget allows stop once it is spent, each
    pixel with the same samples; the warning, the summary line and the metadata give the
    count."""
    import re

    import OpenImageIO as oiio
    limit = ("--python-expr", "import bpy; p = bpy.context.scene.photon; p.samples = 100000; "
             "p.photons = 20000; p.caustic_photons = 10000; p.time_limit = 2.0")
    proc = render_frames(blender, CORNELL, tmp_path / "limit_", "-f", "1", extra=limit)
    said = re.search(r"Time Limit reached after (\d+) of 100000 samples", proc.stdout)
    assert said, proc.log
    reached = int(said.group(1))
    assert 1 <= reached < 100000
    assert f"({reached} spp," in proc.stdout, proc.log
    spec = oiio.ImageInput.open(str(tmp_path / "limit_0001.exr")).spec()
    fields = {a.name: a.value for a in spec.extra_attribs if a.name.startswith("photon.")}
    assert fields["photon.ViewLayer.samples"] == str(reached), fields
    image = read_image(tmp_path / "limit_0001.exr")
    assert np.isfinite(image).all() and image[..., :3].mean() > 0.05


def test_adaptive_sampling_stops_converged_pixels_and_keeps_the_image(blender, tmp_path):
    """Sampling > Noise Threshold: pixels stop once converged (the summary line gives the mean
    count), and the image is the one every sample gives."""
    import re

    # At half size (128 x 128): the same test in a quarter of the time.
    base = ("import bpy; bpy.context.scene.render.resolution_percentage = 50; "
            "p = bpy.context.scene.photon; p.photons = 20000; "
            "p.caustic_photons = 10000; p.samples = 256; ")
    adaptive = ("--python-expr", base + "p.adaptive_sampling = True; p.adaptive_threshold = 0.1")
    proc = render_frames(blender, CORNELL, tmp_path / "adaptive_", "-f", "1", extra=adaptive)
    said = re.search(r"\((\d+) spp on average, adaptive,", proc.stdout)
    assert said, proc.log
    # Threshold 0.1: Cycles' automatic minimum of 32 samples, first judged after 48.
    assert 48 <= int(said.group(1)) < 256, said.group(0)
    full = ("--python-expr", base)
    proc = render_frames(blender, CORNELL, tmp_path / "full_", "-f", "1", extra=full)
    assert "(256 spp," in proc.stdout, proc.log
    a = read_image(tmp_path / "adaptive_0001.exr")[..., :3]
    b = read_image(tmp_path / "full_0001.exr")[..., :3]
    assert np.isfinite(a).all()
    assert abs(a.mean() / b.mean() - 1.0) < 0.01, (a.mean(), b.mean())


def test_png_output(blender, tmp_path):
    render_frames(blender, CORNELL, tmp_path / "cornell_", "-f", "1", fmt="PNG", extra=QUICK)
    image = read_image(tmp_path / "cornell_0001.png")
    assert image.shape[:2] == (256, 256)
    assert 0.05 < image[:, :, :3].mean() < 0.95


def test_animation_renders_every_frame_differently(blender, tmp_path):
    blend = tmp_path / "anim.blend"
    blender.run_script("make_animation.py", blend)
    proc = render_frames(blender, blend, tmp_path / "anim_", "-a")
    assert sum(line.startswith("Photon: rendered frame") for line in proc.stdout.splitlines()) == 3
    images = [read_image(tmp_path / f"anim_{f:04d}.exr") for f in (1, 2, 3)]
    means = [float(img[:, :, :3].mean()) for img in images]
    for a in range(3):
        for b in range(a + 1, 3):
            assert np.abs(images[a] - images[b]).mean() > 1e-3, (a + 1, b + 1)
    # The light's power doubles each frame (20, 40, 80 W): the image gets brighter each frame.
    assert means[0] < means[1] < means[2], means


def test_single_frame_flag_renders_that_frame_only(blender, tmp_path):
    blend = tmp_path / "anim.blend"
    blender.run_script("make_animation.py", blend)
    proc = render_frames(blender, blend, tmp_path / "frame_", "-f", "2")
    assert "rendered frame 2 " in proc.stdout
    assert (tmp_path / "frame_0002.exr").exists()
    assert not (tmp_path / "frame_0001.exr").exists()
    assert not (tmp_path / "frame_0003.exr").exists()


def test_render_border_matches_full_frame_pixels(blender, tmp_path):
    """A border render gives exactly the pixels of the full render inside the border."""
    full_proc = render_frames(blender, CORNELL, tmp_path / "full_", "-f", "1", extra=QUICK)
    assert full_proc.returncode == 0
    script = ("import bpy; r = bpy.context.scene.render; r.use_border = True; "
              "r.use_crop_to_border = True; r.border_min_x, r.border_max_x = 0.25, 0.75; "
              "r.border_min_y, r.border_max_y = 0.5, 1.0")
    render_frames(blender, CORNELL, tmp_path / "border_", "-f", "1",
                  extra=(*QUICK, "--python-expr", script))
    full = read_image(tmp_path / "full_0001.exr")
    border = read_image(tmp_path / "border_0001.exr")
    assert border.shape[:2] == (128, 128)
    # Border y is measured from the bottom: 0.5..1.0 is the top half of the image.
    np.testing.assert_array_equal(border, full[0:128, 64:192])
