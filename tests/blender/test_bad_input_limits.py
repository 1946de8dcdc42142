"""Settings at the edge of what the machine can do: absurd thread counts render and bake
(twice in one process, which crashed) with a warning, and Ctrl-C in background mode during a
long preparation stage ends Blender within seconds (it used to wait for the stage to finish)."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "test_scenes" / "cornell_box.blend"
SCRIPT = Path(__file__).resolve().parent / "scripts" / "limits_settings.py"
QUICK = ["resolution=48", "samples=4", "photons=20000", "caustic_photons=5000",
         "final_gather_rays=4"]


@pytest.mark.parametrize("threads", [100000, 2**31 - 1])
def test_huge_thread_counts_render_twice_with_a_warning(blender, tmp_path, threads):
    out = tmp_path / "frame_####"
    proc = blender.run([str(CORNELL), "-E", "PHOTON", "--python", str(SCRIPT),
                        "-o", str(out), "-F", "OPEN_EXR", "-x", "1", "-f", "1", "-f", "1", "--",
                        f"threads={threads}", *QUICK], check=False, timeout=600)
    assert proc.returncode == 0, proc.log
    rendered = [line for line in proc.stdout.splitlines()
                if line.startswith("Photon: rendered frame 1 ")]
    assert len(rendered) == 2, proc.log
    # The property stops at 4096 and the native side at 4 threads per core.
    assert "limits_settings: threads property = 4096" in proc.stdout, proc.log
    assert "Photon: warning: threads = 4096 is more than this machine can use" in proc.stdout, \
        proc.log
    assert "TBB Warning" not in proc.stdout + proc.stderr, proc.log
    image = read_image(tmp_path / "frame_0001.exr")
    assert np.isfinite(image).all() and image[..., :3].mean() > 0.01


@pytest.mark.parametrize("threads", [100000, 2**31 - 1])
def test_huge_thread_counts_bake_twice_with_a_warning(blender, tmp_path, threads):
    proc = blender.run([str(CORNELL), "--python", str(SCRIPT), "--", f"threads={threads}",
                        "bake=1", "bake_samples=2", *QUICK], check=False, timeout=600)
    assert proc.returncode == 0, proc.log
    assert proc.stdout.count("limits_settings: bake ['FINISHED']") == 2, proc.log
    assert "Photon: warning: threads = 4096 is more than this machine can use" in proc.stdout, \
        proc.log


@pytest.mark.serial  # a wall-time bound
def test_sigint_during_radiance_precompute_ends_blender_promptly(blender, tmp_path):
    # 500k photons: ~230k radiance estimates, several seconds of precompute (minutes before
    # the fix, which waited for it, the irradiance cache and the pixels).
    cmd = [blender.executable, "-b", "--factory-startup", "--python-use-system-env", "--addons", "photon", str(CORNELL),
           "-E", "PHOTON", "--python", str(SCRIPT), "-o", str(tmp_path / "frame_####"),
           "-F", "OPEN_EXR", "-x", "1", "-f", "1", "--", "resolution=64", "samples=1",
           "photons=500000", "caustic_photons=0"]
    proc = subprocess.Popen(cmd, env=blender.env(), stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, text=True)
    log, sent = [], None
    deadline = time.monotonic() + 600
    try:
        for line in proc.stdout:
            log.append(line)
            if sent is None and "Precomputing radiance" in line:
                time.sleep(0.3)
                sent = time.monotonic()
                proc.send_signal(signal.SIGINT)
            if time.monotonic() > deadline:
                break
        proc.wait(timeout=60)
        ended = time.monotonic()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    text = "".join(line for line in log if not line.startswith("Fra:"))
    assert sent is not None, "the render never reached the radiance precompute\n" + text
    print(f"SIGINT during the radiance precompute: Blender exited after {ended - sent:.2f} s")
    assert ended - sent < 3.0, f"exit took {ended - sent:.1f} s after SIGINT\n{text}"
    assert "Photon: rendered frame" not in text  # cancelled, not rendered
