"""Benchmark: a colour-attribute lighting bake of a dense mesh (500k triangles, 1M corners by
default) in background Blender; prints the corners baked per second and the bake's stages.

    /usr/bin/python3 tests/bench/bake_scale.py [--triangles N] [--stage build/stage]

About 15 s on an idle 2-core machine (the per-point final gather this replaced took over ten
minutes). The test suite bakes a smaller mesh and checks the result, not the time."""

import argparse
import json
import os
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = ROOT / "tests" / "blender" / "scripts"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--triangles", type=int, default=500000)
    parser.add_argument("--stage", default=str(ROOT / "build" / "stage"))
    parser.add_argument("--blender", default="/usr/bin/blender")
    args = parser.parse_args()
    env = dict(os.environ, BLENDER_USER_SCRIPTS=args.stage,
               PYTHONPATH=f"{SCRIPTS}:{ROOT / 'test_scenes'}")
    with tempfile.TemporaryDirectory() as tmp:
        result_path = Path(tmp) / "result.json"
        t0 = time.perf_counter()
        proc = subprocess.run(
            [args.blender, "-b", "--factory-startup", "--addons", "photon", "--python",
             str(SCRIPTS / "bake_scale.py"), "--", str(result_path), str(args.triangles)],
            env=env, capture_output=True, text=True, stdin=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        if proc.returncode != 0 or not result_path.exists():
            raise SystemExit(f"the bake failed:\n{proc.stdout}\n{proc.stderr}")
        result = json.loads(result_path.read_text())
    if "exception" in result:
        raise SystemExit(result["exception"])
    rate = result["corners"] / result["seconds"]
    print(f"{result['triangles']:,} triangles, {result['corners']:,} corners baked in "
          f"{result['seconds']:.1f} s: {rate:,.0f} corners/s (Blender process {wall:.1f} s)")
    for line in proc.stdout.splitlines():
        if line.startswith("Photon: baked"):
            print(line)


if __name__ == "__main__":
    main()
