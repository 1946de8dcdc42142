"""Lighting bakes of dense meshes: a 50k-triangle colour-attribute bake lights every corner and
reports its progress; Ctrl-C (SIGINT) in background mode cancels a bake within a second, from
the signal to Blender's exit, and leaves the mesh unchanged. The bake's speed on 500k
triangles is a benchmark (tests/bench/bake_scale.py), not a test."""

import json
import os
import re
import signal
import subprocess
import threading
import time

import pytest

from conftest import SCRIPTS

TRIANGLES = 50000  # 100k corners: every stage of a dense bake, in a few seconds


def test_dense_colour_attribute_bake_lights_every_corner(blender):
    result, proc = blender.run_script("bake_scale.py", TRIANGLES, timeout=900)
    assert "exception" not in result, result.get("exception")
    assert result["bake"] == ["FINISHED"], proc.log
    assert result["triangles"] >= 0.95 * TRIANGLES
    assert result["has_attribute"] and result["finite"]
    assert result["lit_fraction"] > 0.99 and result["mean"] > 0.01
    rate = result["corners"] / result["seconds"]
    print(f"{result['corners']:,} corners baked in {result['seconds']:.1f} s: {rate:,.0f} "
          f"corners/s")
    # The progress line states the rate and the time left (printed once a second, so only a
    # shading stage of over 1.5 s is sure to show it).
    shading = float(re.search(r"shading ([\d.]+) s", proc.stdout).group(1))
    if shading > 1.5:
        assert re.search(r"Baking [\d,]+ / [\d,]+ points, [\d,]+ points/s, about \d+ s left",
                         proc.stdout), proc.stdout


def run_until(blender, pattern, bake_samples):
    """Starts a dense bake, sends SIGINT when a stdout line matches `pattern`; returns
    (seconds from the signal to the exit, stdout, result dict or None)."""
    result_path = blender.out_dir / f"bake_scale-sigint-{os.getpid()}.json"
    if result_path.exists():
        result_path.unlink()
    cmd = [blender.executable, "-b", "--factory-startup", "--python-use-system-env", "--addons", "photon", "--python",
           str(SCRIPTS / "bake_scale.py"), "--", str(result_path), str(TRIANGLES),
           str(bake_samples)]
    proc = subprocess.Popen(cmd, env=blender.env(), stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, stdin=subprocess.DEVNULL)
    lines, sent = [], threading.Event()
    signalled_at = [None]

    def read():
        for line in proc.stdout:
            lines.append(line)
            if not sent.is_set() and re.search(pattern, line):
                signalled_at[0] = time.perf_counter()
                proc.send_signal(signal.SIGINT)
                sent.set()

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        proc.wait(timeout=900)
    finally:
        if proc.poll() is None:
            proc.kill()
    exited_at = time.perf_counter()
    reader.join(timeout=10)
    out = "".join(lines)
    assert signalled_at[0] is not None, f"never saw {pattern!r}\n{out}"
    result = json.loads(result_path.read_text()) if result_path.exists() else None
    return exited_at - signalled_at[0], out, result


@pytest.mark.parametrize("stage", ["Irradiance cache", "Baking "])
@pytest.mark.serial  # a wall-time bound
def test_sigint_cancels_a_background_bake_within_a_second(blender, stage):
    latency, out, result = run_until(blender, r"Photon: bake: " + stage, bake_samples=64)
    print(f"SIGINT during '{stage.strip()}': Blender exited {latency:.2f} s later")
    assert "Bake cancelled" in out, out
    assert result is not None and result["bake"] == ["CANCELLED"], out
    assert not result["has_attribute"], "a cancelled bake wrote the attribute"
    assert latency < 1.5, out
