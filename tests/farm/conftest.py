"""Options of the farm tests (the same as tests/blender's): the staged add-on, Blender, and a
folder for outputs."""

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def pytest_addoption(parser):
    parser.addoption("--photon-stage", default=str(REPO / "build" / "stage"),
                     help="folder holding addons/photon (BLENDER_USER_SCRIPTS)")
    parser.addoption("--blender", default="blender", help="Blender executable")
    parser.addoption("--photon-out", default=str(REPO / "build" / "test_out"),
                     help="folder for rendered images and logs")
