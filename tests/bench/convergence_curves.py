#!/usr/bin/python3
"""Error against wall time of PHOTON_MAP, SPPM, VCM and Cycles on the Cornell box, the caustic
box and an SDS scene (the pool), through Blender.

Each method renders each scene at a series of budgets (photon counts and samples; iterations;
Cycles samples), one Blender process per method and scene; each render's wall time is that of
bpy.ops.render.render (scene sync and render, not Blender's start-up). Errors are against the
scene's reference: Cycles at 4096 / 16384 spp for the validation scenes (cornell_gi,
caustic_validation), test_scenes/sds/pool.exr (SPPM, 2048 iterations; see
test_scenes/sds/references.json) for the pool. Cycles renders with another seed than its
references.

Prints per scene a table of (budget, seconds, relative RMSE, relative MAE, mean difference),
the fitted log-log slopes, and the time at which each method first reaches relative RMSE 0.05
and relative MAE 0.05 (interpolated in log-log between budgets; the RMSE of the caustic box
and of SDS scenes is made by a few pixels that see the small light through glass or mirrors),
and writes
  docs/convergence.png   the log-log curves (relative RMSE and relative MAE against seconds);
  docs/sds_scenes.png    per SDS scene: the reference, then SPPM, VCM and Cycles after the same
                         wall time (--equal-seconds), each with its error;
and the SDS scenes' SPPM and VCM errors after 4, 16 and 64 iterations.

    /usr/bin/python3 tests/bench/convergence_curves.py --addon-dir build/stage \\
        [--blender blender] [--scenes cornell caustic pool] [--equal-seconds 20] [--quick]

About 30 minutes on two cores (--quick: the smallest budgets only, to try the script).
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

from loglog_plot import draw_panel, draw_text, new_canvas, save

ROOT = Path(__file__).resolve().parents[2]
VALIDATION = ROOT / "test_scenes" / "validation"
SDS = ROOT / "test_scenes" / "sds"
TARGET = 0.05  # relative RMSE whose time is reported

SCENES = {
    "cornell": ("Cornell box", VALIDATION / "cornell_gi.blend", VALIDATION / "cornell_gi.exr"),
    "caustic": ("Caustic box", VALIDATION / "caustic_validation.blend",
                VALIDATION / "caustic_validation.exr"),
    "pool": ("Pool (SDS)", None, SDS / "pool.exr"),
}
SDS_SCENES = ("glass_light", "mirror_caustic", "pool")
COLORS = {"PHOTON_MAP": (0.55, 0.35, 0.75), "SPPM": (0.85, 0.2, 0.15),
          "VCM": (0.15, 0.35, 0.8), "CYCLES": (0.2, 0.6, 0.25)}


def budgets(quick):
    """Per method: (label, engine, settings) of each render, cheapest first."""
    pm = [(25000, 4), (100000, 16), (400000, 64), (1600000, 256)]
    iterations = [4, 16, 64, 256]
    samples = [16, 64, 256, 1024, 4096]
    if quick:
        pm, iterations, samples = pm[:2], iterations[:2], samples[:2]
    return {
        "PHOTON_MAP": [(f"{p // 1000}k photons, {s} spp", "PHOTON",
                        {"photon.integrator": "PHOTON_MAP", "photon.photons": p,
                         "photon.caustic_photons": p // 2, "photon.samples": s})
                       for p, s in pm],
        "SPPM": [(f"{k} iterations", "PHOTON",
                  {"photon.integrator": "SPPM", "photon.sppm_iterations": k,
                   "photon.sppm_photons_per_iteration": 100000}) for k in iterations],
        "VCM": [(f"{k} iterations", "PHOTON",
                 {"photon.integrator": "VCM", "photon.vcm_mode": "VCM",
                  "photon.vcm_iterations": k, "photon.vcm_light_paths": 100000})
                for k in iterations],
        "CYCLES": [(f"{s} spp", "CYCLES", {"cycles.samples": s, "cycles.seed": 99})
                   for s in samples],
    }


def read_rgb(path):
    return oiio.ImageBuf(str(path)).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)


def errors(image, reference):
    m = reference.mean()
    return {"rel_rmse": float(np.sqrt(np.mean((image - reference) ** 2)) / m),
            "rel_mae": float(np.mean(np.abs(image - reference)) / m),
            "mean": float(image.mean() / m - 1.0)}


def run_series(blender, addon_dir, blend, items, folder, tag):
    """Renders `items` (label, engine, settings) of one .blend in one Blender process, after an
    untimed warm-up render of the first engine (Cycles loads its kernels on the first)."""
    spec = [{"engine": items[0][1], "settings": dict(items[0][2]),
             "out": str(folder / f"{tag}_warmup.exr")}]
    warm = spec[0]["settings"]
    for key in ("photon.sppm_iterations", "photon.vcm_iterations", "cycles.samples",
                "photon.samples"):
        if key in warm:
            warm[key] = 1
    for i, (label, engine, settings) in enumerate(items):
        spec.append({"label": label, "engine": engine, "settings": settings,
                     "out": str(folder / f"{tag}_{i}.exr")})
    spec_path, result_path = folder / f"{tag}_spec.json", folder / f"{tag}_result.json"
    spec_path.write_text(json.dumps(spec))
    cmd = [blender, "-b", "--factory-startup", "--addons", "photon", str(blend), "-P",
           str(Path(__file__).with_name("render_series.py")), "--", str(spec_path),
           str(result_path)]
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if proc.returncode != 0 or not result_path.exists():
        raise SystemExit(f"Blender failed on {blend.name}:\n{proc.stdout[-3000:]}\n"
                         f"{proc.stderr[-3000:]}")
    return json.loads(result_path.read_text())[1:]


def time_to_target(points):
    """First time the (seconds, error) curve crosses TARGET, interpolated in log-log; None if
    it never does."""
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if e0 <= TARGET:
            return t0
        if e1 <= TARGET:
            f = (math.log(e0) - math.log(TARGET)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    return points[0][0] if points and points[0][1] <= TARGET else None


def make_sds_blends(blender, addon_dir, folder):
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(addon_dir))
    subprocess.run([blender, "-b", "--factory-startup", "--addons", "photon", "-P",
                    str(ROOT / "test_scenes" / "sds.py"), "--", "--out", str(folder)],
                   env=env, capture_output=True, text=True, check=True)
    return {name: folder / f"{name}.blend" for name in SDS_SCENES}


def curves(args, blends, folder):
    """Renders every method's budgets on every scene; returns {scene: {method: [row]}}."""
    out = {}
    for key in args.scenes:
        label, blend, ref_path = SCENES[key]
        blend = blend or blends[key]
        reference = read_rgb(ref_path)
        out[key] = {}
        for method, items in budgets(args.quick).items():
            rows = []
            for r in run_series(args.blender, args.addon_dir, blend, items, folder,
                                f"{key}_{method}"):
                rows.append({"budget": r["label"], "seconds": r["seconds"],
                             **errors(read_rgb(r["out"]), reference)})
            out[key][method] = rows
            print(f"{label}, {method}: " + ", ".join(
                f"{r['budget']} {r['seconds']:.1f} s {r['rel_rmse']:.3f}" for r in rows),
                flush=True)
    return out


def report_curves(results):
    for key, methods in results.items():
        print(f"\n{SCENES[key][0]}: relative RMSE / relative MAE / mean difference vs reference")
        print("| method | budget | seconds | rel. RMSE | rel. MAE | mean |")
        print("| --- | --- | ---: | ---: | ---: | ---: |")
        for method, rows in methods.items():
            for r in rows:
                print(f"| {method} | {r['budget']} | {r['seconds']:.1f} | {r['rel_rmse']:.4f} | "
                      f"{r['rel_mae']:.4f} | {r['mean']:+.4f} |")
    print("\nFitted slopes of log error against log seconds (all budgets): RMSE / MAE")
    for key, methods in results.items():
        cells = []
        for method, rows in methods.items():
            t = np.log([r["seconds"] for r in rows])
            fit = [np.polyfit(t, np.log([r[m] for r in rows]), 1)[0]
                   for m in ("rel_rmse", "rel_mae")]
            cells.append(f"{method} {fit[0]:+.2f} / {fit[1]:+.2f}")
        print(f"{SCENES[key][0]}: " + ", ".join(cells))
    for metric, name in (("rel_rmse", "relative RMSE"), ("rel_mae", "relative MAE")):
        print(f"\nTime to {name} {TARGET} (interpolated between budgets)")
        print("| scene | " + " | ".join(COLORS) + " |")
        print("| --- |" + " ---: |" * len(COLORS))
        for key, methods in results.items():
            cells = []
            for method in COLORS:
                rows = methods.get(method, [])
                t = time_to_target([(r["seconds"], r[metric]) for r in rows])
                best = min((r[metric] for r in rows), default=float("nan"))
                longest = max((r["seconds"] for r in rows), default=0.0)
                cells.append(f"{t:.1f} s" if t else f"not in {longest:.0f} s ({best:.3f})")
            print(f"| {SCENES[key][0]} | " + " | ".join(cells) + " |")


def plot_curves(results, path):
    keys = list(results)
    panel_w, panel_h = 620, 460
    canvas = new_canvas(panel_w * len(keys), panel_h * 2)
    for col, key in enumerate(keys):
        for row, (metric, name) in enumerate((("rel_rmse", "relative RMSE"),
                                              ("rel_mae", "relative MAE"))):
            series = [(m, COLORS[m], [(r["seconds"], r[metric]) for r in rows])
                      for m, rows in results[key].items()]
            draw_panel(canvas, (col * panel_w, row * panel_h, panel_w, panel_h), series,
                       "wall seconds", name, f"{SCENES[key][0]}: {name}",
                       hline=TARGET if metric == "rel_rmse" else None, legend_width=170,
                       font=13)
    save(canvas, path)
    print(f"\nwrote {path}")


def sds_iteration_table(args, blends, folder):
    """SPPM and VCM errors on every SDS scene after 4, 16 and 64 iterations (one render each)."""
    print("\nSDS scenes: relative RMSE / relative MAE / mean difference against the reference")
    print("| scene | integrator | 4 iterations | 16 iterations | 64 iterations |")
    print("| --- | --- | --- | --- | --- |")
    for name in SDS_SCENES:
        reference = read_rgb(SDS / f"{name}.exr")
        for integrator in ("SPPM", "VCM"):
            prefix, paths = (("photon.vcm_", "light_paths") if integrator == "VCM" else
                             ("photon.sppm_", "photons_per_iteration"))
            items = [(f"{k}", "PHOTON", {"photon.integrator": integrator,
                                          prefix + "iterations": k, prefix + paths: 100000})
                     for k in ((4, 16) if args.quick else (4, 16, 64))]
            cells = []
            for r in run_series(args.blender, args.addon_dir, blends[name], items, folder,
                                f"iter_{name}_{integrator}"):
                e = errors(read_rgb(r["out"]), reference)
                cells.append(f"{e['rel_rmse']:.3f} / {e['rel_mae']:.3f} / {e['mean']:+.3f}")
            print(f"| {name} | {integrator} | " + " | ".join(cells) + " |", flush=True)


def to_display(rgb, scale):
    v = np.clip(rgb * scale, 0.0, None)
    v = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)
    return np.clip(v, 0.0, 1.0)


def sds_figure(args, blends, folder, path):
    """Per SDS scene: the reference, then SPPM, VCM and Cycles after the same wall time."""
    zoom, label_h = 2, 34
    t = args.equal_seconds
    items = [("SPPM", "PHOTON", {"photon.integrator": "SPPM", "photon.sppm_iterations": 100000,
                                 "photon.sppm_time": t}),
             ("VCM", "PHOTON", {"photon.integrator": "VCM", "photon.vcm_mode": "VCM",
                                "photon.vcm_iterations": 100000, "photon.vcm_time": t}),
             ("Cycles", "CYCLES", {"cycles.samples": 1 << 20, "cycles.time_limit": t,
                                   "cycles.seed": 99})]
    rows = []
    for name in SDS_SCENES:
        reference = read_rgb(SDS / f"{name}.exr")
        renders = []
        for label, engine, settings in items:
            r = run_series(args.blender, args.addon_dir, blends[name],
                           [(label, engine, settings)], folder, f"fig_{name}_{label}")[0]
            image = read_rgb(r["out"])
            renders.append((f"{label} {r['seconds']:.0f} s, RMSE "
                            f"{errors(image, reference)['rel_rmse']:.2f}", image))
        rows.append((name, [("reference", reference)] + renders))
        print(f"{name}: " + "; ".join(label for label, _ in renders[0:]), flush=True)
    size = read_rgb(SDS / f"{SDS_SCENES[0]}.exr").shape[0] * zoom
    canvas = new_canvas(size * 4, (size + label_h) * len(rows))
    for row, (name, images) in enumerate(rows):
        scale = 0.8 / max(np.quantile(images[0][1], 0.99), 1e-6)
        for col, (label, image) in enumerate(images):
            y0, x0 = row * (size + label_h) + label_h, col * size
            tile = np.repeat(np.repeat(to_display(image, scale), zoom, 0), zoom, 1)
            canvas[y0:y0 + size, x0:x0 + size] = tile
            draw_text(canvas, x0 + 4, y0 - 10, f"{name}: {label}" if col == 0 else label, 12,
                      (0.1, 0.1, 0.1))
    save(canvas, path)
    print(f"wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--addon-dir", required=True, type=Path,
                        help="folder holding addons/photon")
    parser.add_argument("--scenes", nargs="+", choices=list(SCENES), default=list(SCENES))
    parser.add_argument("--equal-seconds", type=float, default=20.0,
                        help="wall time of each render in docs/sds_scenes.png")
    parser.add_argument("--out", type=Path, default=ROOT / "docs")
    parser.add_argument("--quick", action="store_true", help="smallest budgets only")
    args = parser.parse_args()
    args.addon_dir = args.addon_dir.resolve()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        blends = make_sds_blends(args.blender, args.addon_dir, folder)
        results = curves(args, blends, folder)
        report_curves(results)
        plot_curves(results, args.out / "convergence.png")
        sds_iteration_table(args, blends, folder)
        sds_figure(args, blends, folder, args.out / "sds_scenes.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
