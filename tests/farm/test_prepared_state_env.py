"""The add-on's reading of PHOTON_PREPARED_SAVE / PHOTON_PREPARED_LOAD / PHOTON_PREPARE_ONLY
(addon/photon/prepared_state.py), outside Blender: the module needs neither bpy nor the native
library."""

import importlib.util
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location(
    "photon_prepared_state", REPO / "addon" / "photon" / "prepared_state.py")
prepared_state = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(prepared_state)


def test_no_variables_means_no_files():
    assert prepared_state.from_environment(3, {}) is None
    assert prepared_state.from_environment(3, {"PHOTON_PREPARE_ONLY": "0"}) is None


def test_frame_number_replaces_the_last_run_of_hashes_in_the_name_only():
    files = prepared_state.from_environment(7, {
        "PHOTON_PREPARED_SAVE": "/farm/#1/state_####.bin",
        "PHOTON_PREPARED_LOAD": "/farm/#1/plain.bin",
        "PHOTON_PREPARE_ONLY": "1"})
    assert files == {"save": "/farm/#1/state_0007.bin", "load": "/farm/#1/plain.bin",
                     "prepare_only": True}
    assert prepared_state.frame_path("a_##_b_###", 12345) == "a_##_b_12345"


def test_prepare_only_values():
    for value, expected in (("1", True), ("yes", True), ("true", True), ("0", False),
                            ("false", False), ("no", False)):
        files = prepared_state.from_environment(1, {"PHOTON_PREPARED_SAVE": "s",
                                                    "PHOTON_PREPARE_ONLY": value})
        assert files["prepare_only"] is expected, value
