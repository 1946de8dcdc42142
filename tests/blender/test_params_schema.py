"""Render parameters declared once in the native schema: scene.photon's properties are generated
from it (names, defaults, ranges unchanged), _photon and the staged JSON agree, the add-on still
registers them from the JSON when _photon does not load, and out-of-range values that bypass
Blender's clamping are clamped natively with a warning and the frame renders."""

import json
import math
import shutil
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "test_scenes" / "cornell_box.blend"

# The properties as the add-on declared them by hand before the schema (name: default, min,
# max): saved .blend files and scripts rely on these names and defaults.
HAND_WRITTEN = {
    "samples": (64, 1, 1 << 20), "max_depth": (8, 0, 1024), "seed": (0, 0, 2**31 - 1),
    "photons": (200000, 0, 100000000), "caustic_photons": (100000, 0, 100000000),
    "gather_count": (100, 1, 1000), "caustic_gather_count": (50, 1, 1000),
    "gather_radius": (0.0, 0.0, None), "final_gather_rays": (16, 0, 4096),
    "photon_time": (0.0, 0.0, 86400.0), "memory_limit": (0.75, None, 1.0),
    "radiosity_patch_size": (0.0, 0.0, 1e6), "radiosity_rays": (8000, 10, 10000000),
    "radiosity_threshold": (0.01, 1e-4, 1.0), "radiosity_iterations": (4, 0, 100),
    "threads": (0, 0, 4096), "tile_size": (64, None, 4096),
}


def close(a, b):
    return math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-9)


def check_generated(result):
    assert result["load_error"] is None
    rna = result["rna"]
    assert rna["integrator"]["default"] == "PHOTON_MAP"
    assert rna["integrator"]["items"] == ["PHOTON_MAP", "RAY_TRACE", "RADIOSITY", "SPPM", "VCM"]
    assert rna["irradiance_cache"] == {"type": "BOOLEAN", "default": True}
    for name, (default, lo, hi) in HAND_WRITTEN.items():
        assert close(rna[name]["default"], default), (name, rna[name])
        if lo is not None:
            assert close(rna[name]["min"], lo), (name, rna[name])
        if hi is not None:
            assert close(rna[name]["max"], hi), (name, rna[name])
    for group in result["schema"]:
        for p in group["params"]:
            if p["type"] in ("bool", "enum"):
                continue
            info, scale = rna[p["name"]], p["ui_scale"]
            assert close(info["default"], p["default"] / scale), p["name"]
            assert close(info["min"], max(p["min"] / scale, -2**31)), p["name"]
            assert close(info["max"], min(p["max"] / scale, 2**31 - 1)), p["name"]
            if "soft_max" in p:
                assert close(info["soft_max"], p["soft_max"] / scale), p["name"]
            assert info["subtype"] == (p["subtype"] or "NONE"), p["name"]
    assert rna["photon_time"]["unit"].startswith("TIME")  # TIME_ABSOLUTE with that subtype
    assert rna["gather_radius"]["unit"] == "LENGTH"


def test_properties_are_generated_from_the_schema(blender):
    result, proc = blender.run_script("params_schema.py")
    assert "exception" not in result, proc.log
    check_generated(result)
    assert result["native_schema"] == result["json_schema"] == result["schema"]


def test_properties_register_from_the_json_without_the_native_module(blender, tmp_path):
    stage = tmp_path / "stage"
    shutil.copytree(blender.stage / "addons" / "photon", stage / "addons" / "photon",
                    ignore=shutil.ignore_patterns("_photon*.so", "__pycache__"))
    result, proc = blender.run_script("params_schema.py", stage=stage)
    assert "exception" not in result, proc.log
    assert result["native_schema"] is None
    check_generated(result)


def test_out_of_range_values_are_clamped_with_a_warning_and_render(blender, tmp_path):
    out = tmp_path / "frame_####"
    result_path = tmp_path / "result.json"
    # The script (run before the frame) writes the values into the ID properties; -f renders.
    proc = blender.run([str(CORNELL), "-E", "PHOTON", "--python",
                        str(Path(__file__).resolve().parent / "scripts" / "params_schema.py"),
                        "-o", str(out), "-F", "OPEN_EXR", "-x", "1", "-f", "1", "--",
                        str(result_path), "gather_count=5000", "final_gather_rays=-3",
                        "memory_limit=7.5", "photons=20000", "caustic_photons=5000",
                        "samples=4"], timeout=600)
    result = json.loads(result_path.read_text())
    assert "exception" not in result, proc.log
    assert result["read_back"]["gather_count"] == 5000, result["read_back"]  # RNA let it in
    log = proc.stdout
    assert "Photon: warning: Photon Mapping: gather_count = 5000 is outside [1, 1000]: " \
           "clamped to 1000" in log, proc.log
    assert "Photon: warning: Photon Mapping: final_gather_rays = -3 is outside [0, 4096]: " \
           "clamped to 0" in log, proc.log
    assert "Photon: warning: Photon Mapping: memory_limit = 7.5 is outside [0.0001, 1]: " \
           "clamped to 1" in log, proc.log
    image = read_image(tmp_path / "frame_0001.exr")
    assert np.isfinite(image).all() and image[..., :3].mean() > 0.01
