"""The progress bar of a render (addon/photon/progress.py) only moves forward over stages whose
own fractions each restart at 0, keeps the tiles' share for the tiles, and estimates the time
left from the current rate. Pure Python: no Blender needed."""

import importlib.util
from pathlib import Path

import pytest

SPEC = importlib.util.spec_from_file_location(
    "photon_progress", Path(__file__).resolve().parents[2] / "addon" / "photon" / "progress.py")
progress = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(progress)

# A photon-mapped render as the session reports it: (status, preparing, stage fraction).
PHOTON_MAP_RENDER = [
    ("Building BVH and lights", False, 0.0),
    ("Quick preview", False, 0.0),
    ("Estimating photon memory", True, 0.0),
    ("Tracing photons 10k / 100k (20k stored)", True, 0.1),
    ("Tracing photons 90k / 100k (180k stored)", True, 0.9),
    ("Building photon maps", True, 1.0),
    ("Precomputing radiance", True, 0.2),
    ("Precomputing radiance", True, 1.0),
    ("Irradiance cache: 0 records", True, 0.0),
    ("Irradiance cache: 500 records", True, 0.7),
    ("Rendering", False, 0.0),
    ("Rendering", False, 0.25),
    ("Rendering", False, 0.5),
    ("Rendering", False, 1.0),
]


def test_the_bar_never_goes_back_and_the_tiles_fill_the_second_half():
    bar = progress.RenderProgress(prepares=True)
    values = [bar.update(status, preparing, fraction, now=i)[0]
              for i, (status, preparing, fraction) in enumerate(PHOTON_MAP_RENDER)]
    assert values == sorted(values)
    tiles_start = values[PHOTON_MAP_RENDER.index(("Rendering", False, 0.0))]
    assert max(values[:PHOTON_MAP_RENDER.index(("Rendering", False, 0.0))]) <= 0.5
    assert tiles_start == pytest.approx(0.5)
    assert values[-3] == pytest.approx(0.5 + 0.5 * 0.25)
    assert values[-1] == pytest.approx(1.0)


def test_an_integrator_without_preparation_gives_the_whole_bar_to_the_tiles():
    bar = progress.RenderProgress(prepares=False)
    assert bar.update("Building BVH and lights", False, 0.0, now=0.0)[0] == 0.0
    assert bar.update("Rendering", False, 0.5, now=1.0)[0] == pytest.approx(0.5)


def test_time_left_is_estimated_from_the_rate_of_the_current_stage():
    bar = progress.RenderProgress(prepares=True)
    bar.update("Tracing photons 0 / 100k", True, 0.0, now=10.0)
    _, text = bar.update("Tracing photons 25k / 100k", True, 0.25, now=14.0)
    assert text == "00:12 left in this stage"
    bar.update("Rendering", False, 0.0, now=20.0)
    _, text = bar.update("Rendering", False, 0.2, now=50.0)
    assert text == "Remaining 02:00"
    # Too little done to say.
    assert bar.update("Rendering", False, 0.2, now=50.0)[1] == "Remaining 02:00"
    fresh = progress.RenderProgress(prepares=False)
    fresh.update("Rendering", False, 0.0, now=0.0)
    assert fresh.update("Rendering", False, 0.01, now=1.0)[1] == ""


def test_stage_key_ignores_counts():
    assert progress.stage_key("Tracing photons 1.2M / 3M") == "Tracing photons"
    assert progress.stage_key("Irradiance cache: 12 records") == "Irradiance cache"
