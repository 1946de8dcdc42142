"""Headless Blender test harness: each test starts Blender subprocesses against the add-on staged
by the CMake build (build/stage/addons/photon), so a Blender crash fails a test instead of the run.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCRIPTS = Path(__file__).resolve().parent / "scripts"
sys.path.insert(0, str(REPO / "tools"))
from regress_lib.blender_version import blender_version, version_folder  # noqa: E402


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "serial: measures wall time or drives an X display, so it runs alone "
        "(ctest's blender_serial_tests); the others run two at a time (blender_tests)")


def pytest_addoption(parser):
    parser.addoption("--photon-stage", default=str(REPO / "build" / "stage"),
                     help="folder holding addons/photon (BLENDER_USER_SCRIPTS)")
    parser.addoption("--blender", default="blender", help="Blender executable")
    parser.addoption("--photon-out", default=str(REPO / "build" / "test_out"),
                     help="folder for rendered images and logs")


class Blender:
    def __init__(self, executable, stage, out_dir):
        self.executable = executable
        self.stage = Path(stage)
        self.out_dir = Path(out_dir)
        self.out_dir.mkdir(parents=True, exist_ok=True)
        self._version = None

    @property
    def version(self):
        """(major, minor) of this Blender."""
        if self._version is None:
            self._version = blender_version(self.executable)
        return self._version

    def reference(self, path):
        """This Blender's own rendering of the reference image `path` (stored for Blender 3.4
        beside its scene, for Blender X.Y in blender-X.Y/ there: tools/regress.py --update)."""
        path = Path(path)
        own = version_folder(path.parent, self.version) / path.name
        assert own.exists(), (f"no reference rendered by Blender {self.version[0]}."
                              f"{self.version[1]}: {own}")
        return own

    def env(self, stage=None):
        env = dict(os.environ)
        env["BLENDER_USER_SCRIPTS"] = str(stage or self.stage)
        env["PYTHONPATH"] = os.pathsep.join([str(REPO / "test_scenes"), str(SCRIPTS)])
        return env

    def run(self, args, timeout=300, stage=None, check=True):
        """Runs Blender in background mode with the photon add-on enabled."""
        # Blender 4.2+ ignores PYTHONPATH (which finds the test scripts' helpers) unless asked.
        cmd = [self.executable, "-b", "--factory-startup", "--python-use-system-env",
               "--addons", "photon", *args]
        proc = subprocess.run(cmd, env=self.env(stage), capture_output=True, text=True,
                              timeout=timeout, stdin=subprocess.DEVNULL)
        proc.log = f"$ {' '.join(cmd)}\n--- stdout ---\n{proc.stdout}\n--- stderr ---\n{proc.stderr}"
        if check and proc.returncode != 0:
            raise AssertionError(f"Blender exited with {proc.returncode}\n{proc.log}")
        return proc

    def run_script(self, script, *script_args, blend=None, timeout=300, stage=None, check=True):
        """Runs tests/blender/scripts/<script> inside Blender; returns (result dict, process).

        The script writes its findings as JSON to the path in PHOTON_TEST_RESULT.
        """
        result_path = self.out_dir / f"{Path(script).stem}-{os.getpid()}-result.json"
        if result_path.exists():
            result_path.unlink()
        args = [str(blend)] if blend else []
        args += ["--python", str(SCRIPTS / script), "--", str(result_path), *map(str, script_args)]
        proc = self.run(args, timeout=timeout, stage=stage, check=check)
        if not result_path.exists():
            if check:
                raise AssertionError(f"{script} wrote no result\n{proc.log}")
            return None, proc
        return json.loads(result_path.read_text()), proc


@pytest.fixture(scope="session")
def blender(request):
    stage = request.config.getoption("--photon-stage")
    if not (Path(stage) / "addons" / "photon" / "__init__.py").exists():
        pytest.fail(f"no staged add-on in {stage}: build first (cmake --build build)")
    return Blender(request.config.getoption("--blender"), stage,
                   request.config.getoption("--photon-out"))


@pytest.fixture(scope="session")
def native(blender):
    """The compiled _photon module, imported into this (Debian python3) process."""
    sys.path.insert(0, str(blender.stage / "addons" / "photon"))
    try:
        import _photon
    finally:
        sys.path.pop(0)
    return _photon
