"""photon_cli's arguments: sizes parsed strictly, images that cannot fit refused, clamped settings
said before the render, and every failure a message with a non-zero exit (never an abort)."""

import os
import selectors
import subprocess
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
CLI = Path(os.environ.get("PHOTON_CLI", REPO / "build" / "photon_cli"))

pytestmark = pytest.mark.skipif(not CLI.exists(), reason=f"{CLI} is not built")


def run(*args, timeout=120):
    return subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True,
                          timeout=timeout, stdin=subprocess.DEVNULL)


@pytest.mark.parametrize("size", ["0", "-5", "1e9", "12x", "3.5", "", "65537"])
def test_sizes_that_are_not_whole_pixel_counts_are_refused(tmp_path, size):
    proc = run("--width", size, "--height", "16", "--samples", "1", "--out", tmp_path / "a.exr")
    assert proc.returncode == 2, proc
    assert "is not a whole number of pixels" in proc.stderr
    assert not (tmp_path / "a.exr").exists()


def test_an_image_larger_than_memory_is_refused_with_a_message(tmp_path):
    proc = run("--width", 65536, "--height", 65536, "--samples", 1, "--out", tmp_path / "a.exr",
               timeout=30)
    # An uncaught std::bad_alloc would abort (a negative return code: SIGABRT).
    assert proc.returncode == 1, proc
    assert "needs about" in proc.stderr and "available" in proc.stderr


def test_clamped_settings_are_said_before_the_render(tmp_path):
    """A render of many seconds: the warning must show while it runs, not once it is over."""
    proc = subprocess.Popen([str(CLI), "--width", "256", "--height", "256", "--samples", "4096",
                             "--integrator", "ray_trace", "--gather-count", "0",
                             "--out", str(tmp_path / "a.exr")],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            stdin=subprocess.DEVNULL)
    try:
        selector = selectors.DefaultSelector()
        selector.register(proc.stderr, selectors.EVENT_READ)
        seen, deadline = "", time.monotonic() + 10.0
        while "gather_count = 0 is outside" not in seen and time.monotonic() < deadline:
            if selector.select(timeout=0.2):
                line = proc.stderr.readline()
                if not line:
                    break
                seen += line
        assert "gather_count = 0 is outside" in seen, seen
        assert proc.poll() is None, "the render ended before the check: make it longer"
    finally:
        proc.kill()
        proc.wait()


def test_a_full_disk_leaves_no_damaged_image(tmp_path):
    """An image that does not fit its disk: exit 1 with the reason, and no file (damaged or
    temporary) under the output's folder. Before, the writer's error left a truncated file."""
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs (a disk that fills) needs root")
    disk = tmp_path / "disk"
    disk.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(disk)],
                             capture_output=True, text=True)
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {mounted.stderr.strip()}")
    try:
        # 256 x 256 RGBA floats: about 1 MB of EXR, far more than 64 kB.
        proc = run("--width", 256, "--height", 256, "--samples", 1, "--integrator", "ray_trace",
                   "--out", disk / "a.exr")
        assert proc.returncode == 1, proc
        assert "cannot write" in proc.stderr, proc.stderr
        assert list(disk.iterdir()) == []
        # A frame that fits is written whole under its own name.
        proc = run("--width", 8, "--height", 8, "--samples", 1, "--integrator", "ray_trace",
                   "--out", disk / "b.exr")
        assert proc.returncode == 0, proc
        assert [p.name for p in disk.iterdir()] == ["b.exr"]
    finally:
        subprocess.run(["umount", "-l", str(disk)], capture_output=True)


def test_an_output_path_that_is_a_folder_is_refused(tmp_path):
    folder = tmp_path / "a.exr"
    folder.mkdir()
    proc = run("--width", 8, "--height", 8, "--samples", 1, "--out", folder)
    assert proc.returncode == 1, proc
    assert "is not a regular file" in proc.stderr
    assert folder.is_dir() and list(folder.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.exr"]
