#!/usr/bin/python3
"""Makes the SDS scenes' references (test_scenes/sds/NAME.exr) and checks them against
independent renders, recording how in test_scenes/sds/references.json.

For each scene of native/src/photon/testing/sds_scenes.h (96 x 96):
  reference   SPPM, --sppm-iterations x --photons photons (photon_cli, seed 1);
  VCM         the VCM integrator (all strategies), --vcm-iterations, seed 2: an independent
              estimator (vertex connections and merging, light subpaths with the adjoint BSDF);
  PHOTON_MAP  Jensen's two-pass photon mapping (caustic map, final gathering): another
              independent estimator, biased by its gather radius;
  Cycles      the Blender scene (test_scenes/sds.py) in Cycles, --cycles-samples: path tracing
              with next-event estimation, which finds these paths only when a diffuse bounce
              happens to hit the small light through the glass (a noisy but unbiased estimate);
  Blender     the Blender scene in Photon (SPPM, 32 iterations) against photon_cli with the same
              settings and seed: the bpy builder and the native builder make the same scene;
  noise       two SPPM renders of an eighth of the reference's iterations (seeds 21, 22): their
              difference measures their own noise n, and their error e against the reference
              then bounds the reference's: sqrt(e^2 - n^2) is its noise plus the change of
              SPPM's bias between the two iteration counts (--noise-only adds this to existing
              references).
Each comparison gives the image mean's relative difference, the relative RMSE and MAE (per
pixel, every channel) and the largest and RMS relative difference of the means of 8 x 8 tiles
against the reference. The reference is accepted when VCM's mean is within
--mean-tolerance of it.

    /usr/bin/python3 test_scenes/sds/make_references.py --build build [--blender blender]
        [--only NAME ...] [--sppm-iterations 2048] [--vcm-iterations 1024]
        [--cycles-samples 8192] [--noise-only]
"""

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
SCENES = ("glass_light", "mirror_caustic", "pool")
SIZE = 96


def read_rgb(path):
    return oiio.ImageBuf(str(path)).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)


def write_rgb(path, rgb):
    spec = oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, oiio.FLOAT)
    spec.channelnames = ("R", "G", "B")
    spec.attribute("compression", "zip")
    out = oiio.ImageBuf(spec)
    out.set_pixels(oiio.ROI(), rgb.astype(np.float32))
    if not out.write(str(path)):
        raise SystemExit(f"cannot write {path}: {out.geterror()}")


TILE = 12  # pixels: 8 x 8 tiles of a 96 x 96 image


def compare(image, reference):
    """Image mean and per-pixel RMSE relative to the reference's mean, and how far the means of
    the 64 tiles of 12 x 12 pixels are from the reference's (relative to each tile's mean):
    the largest and the root mean square."""
    h, w = reference.shape[0] // TILE, reference.shape[1] // TILE

    def tiles(x):
        return x[:h * TILE, :w * TILE].reshape(h, TILE, w, TILE, -1).mean(axis=(1, 3, 4))

    tile_rel = tiles(image) / np.maximum(tiles(reference), 1e-9) - 1.0
    return {"mean_rel": float(image.mean() / reference.mean() - 1.0),
            "rel_rmse": float(np.sqrt(np.mean((image - reference) ** 2)) / reference.mean()),
            "rel_mae": float(np.mean(np.abs(image - reference)) / reference.mean()),
            "tile_rel_max": float(np.abs(tile_rel).max()),
            "tile_rel_rms": float(np.sqrt(np.mean(tile_rel ** 2)))}


def photon_cli(build, scene, out, *options):
    cmd = [str(build / "photon_cli"), "--scene", scene, "--width", str(SIZE), "--height",
           str(SIZE), "--out", str(out), *map(str, options)]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, check=True)
    seconds = time.perf_counter() - t0
    print(f"  {' '.join(cmd[3:])}: {seconds:.0f} s", flush=True)
    return read_rgb(out), seconds


def blender_render(blender, addon_dir, blend, engine, out_prefix, expr):
    cmd = [blender, "-b", "--factory-startup", str(blend), "-E", engine, "--python-expr", expr,
           "-o", f"{out_prefix}####", "-F", "OPEN_EXR", "-x", "1", "-f", "1"]
    if engine == "PHOTON":
        cmd[3:3] = ["--addons", "photon"]
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    times = re.findall(r"Time: (\d+):(\d+\.\d+)", proc.stdout)
    seconds = int(times[-1][0]) * 60 + float(times[-1][1]) if times else time.perf_counter() - t0
    print(f"  {engine} {blend.name} ({expr}): {seconds:.0f} s", flush=True)
    return read_rgb(f"{out_prefix}0001.exr"), seconds


def reference_noise(build, name, tmp, iterations, photons):
    """The noise estimate described above, for the stored reference of `name`."""
    reference = read_rgb(HERE / f"{name}.exr")
    runs = [photon_cli(build, name, tmp / f"{name}_noise{seed}.exr", "--integrator", "sppm",
                       "--sppm-iterations", max(iterations // 8, 1), "--seed", seed,
                       "--sppm-photons-per-iteration", photons)[0] for seed in (21, 22)]
    m = reference.mean()
    own = float(np.sqrt(np.mean((runs[0] - runs[1]) ** 2) / 2.0) / m)
    against = float(np.mean([np.sqrt(np.mean((r - reference) ** 2)) / m for r in runs]))
    # The same in mean absolute error (|a - b| of two independent errors of equal spread is
    # about sqrt(2) times either's, for normal errors).
    own_mae = float(np.mean(np.abs(runs[0] - runs[1])) / np.sqrt(2.0) / m)
    against_mae = float(np.mean([np.mean(np.abs(r - reference)) / m for r in runs]))
    return {"iterations": max(iterations // 8, 1), "own_rel_rmse": own,
            "rel_rmse_against_reference": against,
            "reference_rel_rmse_bound": float(np.sqrt(max(against ** 2 - own ** 2, 0.0))),
            "own_rel_mae": own_mae, "rel_mae_against_reference": against_mae,
            "reference_rel_mae_bound": float(np.sqrt(max(against_mae ** 2 - own_mae ** 2,
                                                         0.0)))}


def make_blends(blender, addon_dir, folder, names):
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    subprocess.run([blender, "-b", "--factory-startup", "--addons", "photon", "-P",
                    str(ROOT / "test_scenes" / "sds.py"), "--", "--out", str(folder), "--only",
                    *names], env=env, capture_output=True, text=True, check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--only", nargs="+", choices=SCENES, default=list(SCENES))
    parser.add_argument("--sppm-iterations", type=int, default=2048)
    parser.add_argument("--vcm-iterations", type=int, default=1024)
    parser.add_argument("--photons", type=int, default=100000, help="photons per iteration")
    parser.add_argument("--cycles-samples", type=int, default=8192)
    parser.add_argument("--mean-tolerance", type=float, default=0.01)
    parser.add_argument("--noise-only", action="store_true",
                        help="only estimate the stored references' noise")
    parser.add_argument("--checks-only", action="store_true",
                        help="check the stored references again (VCM, photon mapping, Cycles, "
                        "Blender) without rendering them")
    args = parser.parse_args()
    build = args.build.resolve()
    addon_dir = build / "stage"
    record_path = HERE / "references.json"
    record = json.loads(record_path.read_text()) if record_path.exists() else {}
    failed = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        if args.noise_only:
            for name in args.only:
                ref = record[name]["reference"]
                record[name]["noise"] = reference_noise(build, name, tmp, ref["iterations"],
                                                        ref["photons_per_iteration"])
                print(f"{name}: noise {record[name]['noise']}", flush=True)
                record_path.write_text(json.dumps(record, indent=2) + "\n")
            return 0
        make_blends(args.blender, addon_dir, tmp, args.only)
        for name in args.only:
            print(f"{name}:", flush=True)
            common = ["--sppm-photons-per-iteration", args.photons]
            if args.checks_only:
                reference = read_rgb(HERE / f"{name}.exr")
                ref_seconds = record[name]["reference"]["seconds"]
            else:
                reference, ref_seconds = photon_cli(
                    build, name, tmp / f"{name}_sppm.exr", "--integrator", "sppm",
                    "--sppm-iterations", args.sppm_iterations, "--seed", 1, *common)
            vcm, vcm_seconds = photon_cli(
                build, name, tmp / f"{name}_vcm.exr", "--integrator", "vcm", "--vcm-mode", "vcm",
                "--vcm-iterations", args.vcm_iterations, "--vcm-light-paths", args.photons,
                "--seed", 2)
            pm, pm_seconds = photon_cli(
                build, name, tmp / f"{name}_pm.exr", "--integrator", "photon_map", "--samples",
                256, "--photons", 2000000, "--caustic-photons", 4000000, "--seed", 3)
            blend = tmp / f"{name}.blend"
            cycles, cycles_seconds = blender_render(
                args.blender, addon_dir, blend, "CYCLES", tmp / f"{name}_cycles_",
                f"import bpy; bpy.context.scene.cycles.samples = {args.cycles_samples}")
            in_blender, _ = blender_render(
                args.blender, addon_dir, blend, "PHOTON", tmp / f"{name}_blender_",
                "import bpy; p = bpy.context.scene.photon; p.seed = 1; "
                f"p.sppm_iterations = 32; p.sppm_photons_per_iteration = {args.photons}")
            native, _ = photon_cli(build, name, tmp / f"{name}_native.exr", "--integrator", "sppm",
                                   "--sppm-iterations", 32, "--seed", 1, *common)
            entry = {
                "size": [SIZE, SIZE],
                "reference": record[name]["reference"] if args.checks_only else {
                    "integrator": "SPPM", "iterations": args.sppm_iterations,
                    "photons_per_iteration": args.photons, "seed": 1,
                    "seconds": round(ref_seconds, 1), "mean": float(reference.mean())},
                "checks": {
                    "VCM": {"iterations": args.vcm_iterations, "seconds": round(vcm_seconds, 1),
                            **compare(vcm, reference)},
                    "PHOTON_MAP": {"samples": 256, "photons": 2000000, "caustic_photons": 4000000,
                                   "seconds": round(pm_seconds, 1), **compare(pm, reference)},
                    "CYCLES": {"samples": args.cycles_samples, "seconds": round(cycles_seconds, 1),
                               **compare(cycles, reference)},
                    "blender_vs_native_sppm_32": compare(in_blender, native),
                },
            }
            checks = entry["checks"]
            for check, values in checks.items():
                print(f"  {check}: mean {values['mean_rel']:+.4f}, relative RMSE "
                      f"{values['rel_rmse']:.4f}, MAE {values['rel_mae']:.4f}, tiles "
                      f"{values['tile_rel_rms']:.4f} RMS, {values['tile_rel_max']:.4f} max",
                      flush=True)
            if abs(checks["VCM"]["mean_rel"]) > args.mean_tolerance:
                failed.append(name)
                print(f"  {name}: VCM's mean is off the reference by more than "
                      f"{args.mean_tolerance:.0%}: not written", flush=True)
                continue
            if args.checks_only:
                entry["noise"] = record[name].get("noise")
            else:
                write_rgb(HERE / f"{name}.exr", reference)
                entry["noise"] = reference_noise(build, name, tmp, args.sppm_iterations,
                                                 args.photons)
            print(f"  noise: {entry['noise']}", flush=True)
            record[name] = entry
            record_path.write_text(json.dumps(record, indent=2) + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
