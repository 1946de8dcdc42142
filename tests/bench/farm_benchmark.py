#!/usr/bin/python3
"""The render farm's cost and the saving of a shared preparation, on a local single-node Slurm
cluster that this script starts and stops (run as root with slurm-wlm and munge installed;
it waits while another local cluster runs on the machine):

1. overhead: wall time of a 3-frame animation and of a 4-band split still through
   `tools/farm.py submit --wait` against `blender -b` rendering them directly;
2. saving: every band of the still run one after another exactly as the farm's tasks run them
   (the times one node takes), each preparing itself and then loading the frame's shared
   preparation, and the prepare task itself;
3. projection: a 64-node split of a 1920x1080 frame of the same scene, from the measured
   times (the model is printed with the figures).

    /usr/bin/python3 tests/bench/farm_benchmark.py [--width 320 --height 180] [--json FILE]

The scene (tests/bench/farm_bench_scene.py) is the Cornell box with a glass and a mirror ball,
with Photon's default photon mapping. Every farm output is checked to be bit-identical to
Blender's own render of the same frame.
"""

import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
FARM = REPO / "tools" / "farm.py"
sys.path.insert(0, str(REPO / "tools"))
from farm_lib import blend_info, cluster, stitch, tasks  # noqa: E402

FRAME = 2       # the still
BANDS = 4
NODES = 64      # the projection's split
FULL_HD = (1920, 1080)

RENDERED = re.compile(r"^Photon: (?:rendered|prepared \(no pixels[^)]*\)) frame \d+ .*"
                      r"sync ([\d.]+) s .*BVH ([\d.]+) s, render ([\d.]+) s, total ([\d.]+) s",
                      re.M)
PHOTONS = re.compile(r"^Photon: photons: .* stored in ([\d.]+) s; maps built in ([\d.]+) s, "
                     r"radiance precomputed in ([\d.]+) s", re.M)
CACHE = re.compile(r"^Photon: irradiance cache: ([\d,]+) records, .* in ([\d.]+) s", re.M)
LOADED = re.compile(r"^Photon: prepared state loaded from .* \(([\d.]+) MB in ([\d.]+) s\)", re.M)
SAVED = re.compile(r"^Photon: prepared state saved to .* \(([\d.]+) MB in ([\d.]+) s\)", re.M)
BLENDER_RAN = re.compile(r"^farm: Blender ran ([\d.]+) s", re.M)
STITCHED = re.compile(r"^farm: stitched frame .* in ([\d.]+) s", re.M)


def live_slurmctld():
    """Process ids of running (not zombie) slurmctld daemons on this machine."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        name, state = stat[stat.index("(") + 1:stat.rindex(")")], stat[stat.rindex(")") + 2]
        if name == "slurmctld" and state != "Z":
            found.append(int(entry.name))
    return found


def wait_for_other_clusters(limit=3600):
    deadline = time.monotonic() + limit
    while live_slurmctld():
        if time.monotonic() > deadline:
            sys.exit("farm_benchmark: another Slurm cluster has been running for an hour; giving up")
        print(f"farm_benchmark: another Slurm cluster runs here (slurmctld {live_slurmctld()}); "
              f"waiting for it to stop", flush=True)
        time.sleep(30)


def timed(cmd, env, timeout=3600):
    t0 = time.monotonic()
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL)
    seconds = time.monotonic() - t0
    if proc.returncode != 0:
        sys.exit(f"farm_benchmark: failed ({proc.returncode}): {' '.join(map(str, cmd))}\n"
                 f"{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}")
    return seconds, proc.stdout


def photon_times(log, loaded=False):
    """Seconds of a Blender run's Photon stages (one render)."""
    sync, bvh, render, total = map(float, RENDERED.search(log).groups())
    t = {"sync": sync, "bvh": bvh, "render": render, "total": total, "prepare": 0.0,
         "cache": 0.0, "load": 0.0, "save": 0.0, "mb": 0.0}
    if loaded:
        mb, t["load"] = map(float, LOADED.search(log).groups())
        t["mb"] = mb
    else:
        trace, maps, precompute = map(float, PHOTONS.search(log).groups())
        t["cache"] = float(CACHE.search(log).group(2))
        t["prepare"] = trace + maps + precompute  # photon maps and radiance records
    saved = SAVED.search(log)
    if saved:
        t["mb"], t["save"] = map(float, saved.groups())
    return t


def read_pixels(path):
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(str(path))
    pixels = np.ascontiguousarray(inp.read_image(oiio.FLOAT), dtype=np.float32)
    inp.close()
    return pixels.view(np.uint32)


def same_bits(a, b):
    return bool(np.array_equal(read_pixels(a), read_pixels(b)))


class Bench:
    def __init__(self, args, work):
        self.args, self.work = args, work
        self.env = dict(os.environ, BLENDER_USER_SCRIPTS=str(args.addon_dir),
                        PYTHONPATH=str(REPO / "test_scenes"))
        for name in ("PHOTON_PREPARED_SAVE", "PHOTON_PREPARED_LOAD", "PHOTON_PREPARE_ONLY"):
            self.env.pop(name, None)
        self.blend = work / "scene.blend"
        self.blender = [args.blender, "-b", "--factory-startup"]

    def make_scene(self):
        timed([*self.blender, "--addons", "photon", "--python",
               str(REPO / "tests" / "bench" / "farm_bench_scene.py"), "--", str(self.blend),
               str(self.args.width), str(self.args.height)], self.env)

    def direct(self, name, frame_args):
        seconds, log = timed([*self.blender, str(self.blend), "--addons", "photon", "-E",
                              "PHOTON", "-o", str(self.work / name / "f_"), *frame_args],
                             self.env)
        return seconds, log

    def bands_one_by_one(self):
        """Each band run as the farm's task runs it, one after another: (own-prepare runs,
        prepare run, loading runs)."""
        rows = blend_info.band_rows(self.args.height, BANDS)
        manifest = {"blender": self.args.blender, "blend": str(self.blend), "rows": rows,
                    "height": self.args.height, "band_format": "OPEN_EXR",
                    "file_format": "OPEN_EXR"}
        state = self.work / "state.photonstate"
        own, loaded = [], []
        for band in range(BANDS):
            out = self.work / "own" / f"b{band}_"
            wall, log = timed(tasks._blender_cmd(manifest, FRAME, out,
                                                 tasks._band_expr(manifest, band)), self.env)
            own.append(dict(photon_times(log), wall=wall))
        env = dict(self.env, PHOTON_PREPARED_SAVE=str(state), PHOTON_PREPARE_ONLY="1")
        wall, log = timed(tasks._blender_cmd(manifest, FRAME, self.work / "prep" / "p_"), env)
        prepare = dict(photon_times(log), wall=wall)
        env = dict(self.env, PHOTON_PREPARED_LOAD=str(state))
        band_files = []
        for band in range(BANDS):
            out = self.work / "loaded" / f"b{band}_"
            wall, log = timed(tasks._blender_cmd(manifest, FRAME, out,
                                                 tasks._band_expr(manifest, band)), env)
            loaded.append(dict(photon_times(log, loaded=True), wall=wall))
            band_files.append(next(out.parent.glob(f"b{band}_*")))
        t0 = time.monotonic()
        stitched = self.work / "loaded" / "stitched.exr"
        stitch.stitch(band_files, rows, stitched, "OPEN_EXR")
        stitch_seconds = time.monotonic() - t0
        return own, prepare, loaded, stitched, stitch_seconds

    def farm(self, name, *args):
        out = self.work / "farm" / name
        env = dict(self.env, PHOTON_FARM_POINTER=str(self.work / "cluster.json"),
                   SLURM_CONF=str(self.work / "cluster" / "slurm.conf"))
        wall, stdout = timed([sys.executable, str(FARM), "submit", str(self.blend), "--out",
                              str(out), "--blender", self.args.blender, "--addon-dir",
                              str(self.args.addon_dir), "--wait", *args], env)
        logs = {p.name: p.read_text() for p in next((out / ".farm").iterdir()).glob("logs/*")}
        return wall, out, logs


def summarize(own, prepare, loaded, stitch_seconds, width, height):
    """The projection's inputs (seconds at the measured size) and the projection (printed)."""
    k = FULL_HD[0] * FULL_HD[1] / (width * height)
    pixels = sum(b["render"] for b in own)  # the whole frame's pixel time, summed over bands
    fixed = statistics.mean(b["prepare"] for b in own)
    cache = statistics.mean(b["cache"] for b in own)
    overhead = statistics.mean(b["wall"] - b["prepare"] - b["cache"] - b["render"] for b in own)
    load = statistics.mean(b["load"] for b in loaded)
    save = prepare["save"]
    m = {"k": k, "pixels": pixels, "fixed": fixed, "cache": cache, "overhead": overhead,
         "load": load, "save": save, "stitch": stitch_seconds}
    one_node = overhead + fixed + k * cache + k * pixels
    own_band = overhead + fixed + k * cache + k * pixels / NODES
    prep_task = overhead + fixed + k * cache + k * save
    shared_band = overhead + k * load + k * pixels / NODES
    m["projection"] = {
        "one_node": one_node,
        "own": {"latency": own_band + k * stitch_seconds, "node_seconds": NODES * own_band},
        "shared": {"latency": prep_task + shared_band + k * stitch_seconds,
                   "node_seconds": prep_task + NODES * shared_band},
    }
    return m


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--blender", default=shutil.which("blender") or "blender")
    parser.add_argument("--addon-dir", type=Path, default=REPO / "build" / "stage")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=180)
    parser.add_argument("--json", type=Path, help="also write the figures here")
    parser.add_argument("--keep", action="store_true", help="keep the work folder")
    args = parser.parse_args()
    if os.geteuid() != 0 or cluster.tools_missing():
        sys.exit("farm_benchmark: needs root and slurm-wlm + munge (the local cluster's daemons)")
    work = Path(tempfile.mkdtemp(prefix="photon_farm_bench_"))
    os.chmod(work, 0o755)
    bench = Bench(args, work)
    results = {"size": [args.width, args.height], "bands": BANDS}
    try:
        bench.make_scene()
        print(f"scene: {work / 'scene.blend'} at {args.width}x{args.height}", flush=True)
        results["direct_animation"], _ = bench.direct("direct_anim", ["-a"])
        results["direct_still"], still_log = bench.direct("direct_still", ["-f", str(FRAME)])
        print(f"direct: animation {results['direct_animation']:.1f} s, still "
              f"{results['direct_still']:.1f} s", flush=True)
        own, prepare, loaded, stitched, stitch_seconds = bench.bands_one_by_one()
        direct_still = next((work / "direct_still").glob("f_*"))
        results["bands_one_by_one_bit_identical"] = same_bits(direct_still, stitched)

        wait_for_other_clusters()
        pointer = work / "cluster.json"
        os.environ["PHOTON_FARM_POINTER"] = str(pointer)
        cluster.POINTER = pointer
        cluster.start(work / "cluster")
        try:
            results["farm_animation"], anim_out, _ = bench.farm("anim")
            results["farm_split_shared"], shared_out, shared_logs = bench.farm(
                "shared", "--frames", str(FRAME), "--split", str(BANDS))
            results["farm_split_own"], own_out, own_logs = bench.farm(
                "own", "--frames", str(FRAME), "--split", str(BANDS), "--no-shared-prepare")
        finally:
            cluster.stop(work / "cluster")
        results["farm_bit_identical"] = all(
            same_bits(next((work / "direct_anim").glob(f"f_{f:04d}*")),
                      next(anim_out.glob(f"bench_{f:04d}*"))) for f in (1, 2, 3)) and all(
            same_bits(direct_still, next(out.glob(f"bench_{FRAME:04d}*")))
            for out in (shared_out, own_out))
        results["farm_task_seconds"] = {
            name: {log: [float(x) for x in BLENDER_RAN.findall(text)]
                   for log, text in logs.items() if BLENDER_RAN.search(text)}
            for name, logs in (("shared", shared_logs), ("own", own_logs))}
        results["bands_own"], results["bands_loaded"], results["prepare_task"] = \
            own, loaded, prepare
        results["model"] = summarize(own, prepare, loaded, stitch_seconds, args.width,
                                     args.height)
        report(results)
        if args.json:
            args.json.write_text(json.dumps(results, indent=1))
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)


def report(r):
    w, h = r["size"]
    print(f"\n== farm overhead ({w}x{h}, local single-node cluster, 2 tasks at a time) ==")
    print(f"3-frame animation: blender -b -a {r['direct_animation']:.1f} s, farm "
          f"{r['farm_animation']:.1f} s")
    print(f"{BANDS}-band still: blender -b -f {r['direct_still']:.1f} s, farm with shared "
          f"preparation {r['farm_split_shared']:.1f} s, each band preparing itself "
          f"{r['farm_split_own']:.1f} s")
    print(f"farm outputs bit-identical to blender -b: {r['farm_bit_identical']}; "
          f"bands run one by one and stitched: {r['bands_one_by_one_bit_identical']}")
    print("\n== per band, one at a time (seconds: Blender run; Photon's prepare / cache / "
          "load / pixels) ==")
    for i, (own, loaded) in enumerate(zip(r["bands_own"], r["bands_loaded"])):
        print(f"band {i}: preparing itself {own['wall']:.1f} "
              f"({own['prepare']:.1f} / {own['cache']:.1f} / - / {own['render']:.2f}); "
              f"loading {loaded['wall']:.1f} (- / - / {loaded['load']:.3f} / "
              f"{loaded['render']:.2f})")
    p = r["prepare_task"]
    print(f"prepare task: {p['wall']:.1f} (photon maps and radiance {p['prepare']:.1f}, "
          f"irradiance cache {p['cache']:.1f}, save {p['save']:.3f} s, {p['mb']:.1f} MB)")
    own_total = sum(b["wall"] for b in r["bands_own"])
    shared_total = p["wall"] + sum(b["wall"] for b in r["bands_loaded"])
    print(f"node-seconds for the frame: {own_total:.1f} preparing in every band, "
          f"{shared_total:.1f} shared")
    m = r["model"]
    pr = m["projection"]
    print(f"\n== projection: {NODES}-node split of a {FULL_HD[0]}x{FULL_HD[1]} frame ==")
    print(f"model: k = {m['k']:.1f} x the pixels; per task: overhead O = {m['overhead']:.1f} s "
          f"(Blender start, load, sync, BVH, write), photon maps + radiance P = "
          f"{m['fixed']:.1f} s (photon counts, not pixels), irradiance cache k C = "
          f"{m['k'] * m['cache']:.1f} s, pixels k X / {NODES} = "
          f"{m['k'] * m['pixels'] / NODES:.1f} s, state save / load k S, k L = "
          f"{m['k'] * m['save']:.2f} / {m['k'] * m['load']:.2f} s, stitch k T = "
          f"{m['k'] * m['stitch']:.1f} s")
    print(f"one node: O + P + kC + kX = {pr['one_node']:.0f} s")
    print(f"{NODES} bands preparing themselves: latency O + P + kC + kX/{NODES} + kT = "
          f"{pr['own']['latency']:.0f} s, {pr['own']['node_seconds'] / 3600:.1f} node-hours")
    print(f"{NODES} bands sharing: latency (O + P + kC + kS) + (O + kL + kX/{NODES}) + kT = "
          f"{pr['shared']['latency']:.0f} s, {pr['shared']['node_seconds'] / 3600:.2f} "
          f"node-hours")


if __name__ == "__main__":
    main()
