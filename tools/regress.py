#!/usr/bin/python3
"""Photon's image regression suite: renders every NAME.blend in the given folders headless with
the Photon add-on, compares each frame with the stored reference NAME.exr (NAME_####.exr for
animations) and writes OUT/report.html and OUT/report.json.

    python3 tools/regress.py test_scenes/regression test_scenes/validation \\
        --blender blender --addon-dir build/stage --out build/regression [--update]

A sidecar NAME.json next to a .blend may set "thresholds", "frames", "timeout",
"reference_engine" (CYCLES marks a validation scene), "reference_samples" and "description".
References rendered by Blender 3.4 sit beside the scenes; another Blender X.Y's in blender-X.Y/.
See docs/regression.md. Exit status 0 only when every scene passed (or, with --update, when
every reference was rendered).
"""

import argparse
import shutil
import sys
import time
import traceback
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from regress_lib import compare, render, report  # noqa: E402
from regress_lib.blender_version import REFERENCE_BLENDER, blender_version  # noqa: E402


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folders", nargs="+", type=Path, help="folders holding NAME.blend files")
    parser.add_argument("--blender", default="blender", help="Blender executable")
    parser.add_argument("--addon-dir", required=True, type=Path,
                        help="BLENDER_USER_SCRIPTS folder that holds addons/photon")
    parser.add_argument("--out", required=True, type=Path, help="folder for renders and report")
    parser.add_argument("--update", action="store_true",
                        help="re-render and replace the references (with each scene's "
                             "reference engine)")
    parser.add_argument("--timeout", type=float, default=render.DEFAULT_TIMEOUT,
                        help="default per-scene wall-clock limit in seconds (sidecar 'timeout' "
                             "overrides)")
    parser.add_argument("--only", nargs="+", metavar="NAME", help="run only these scenes")
    parser.add_argument("-j", "--jobs", type=int, default=1, help="scenes rendered at once")
    parser.add_argument("--threads", type=int, help="pass -t THREADS to Blender (Cycles threads; "
                                                    "Photon uses scene.photon.threads)")
    return parser.parse_args(argv)


def scene_result(scene):
    return {"name": scene.name, "blend": str(scene.blend), "status": "PASS", "reason": "",
            "seconds": 0.0, "description": scene.description, "validation": scene.is_validation,
            "reference_engine": scene.reference_engine, "frames": [], "log": ""}


def check_scene(scene, args):
    """Renders one scene with Photon and compares every frame with its reference."""
    result = scene_result(scene)
    try:
        if scene.sidecar_error:
            raise ValueError(scene.sidecar_error)
        thresholds = compare.merged_thresholds(scene.sidecar.get("thresholds"))
    except ValueError as exc:
        result.update(status="ERROR", reason=str(exc))
        return result
    rendered = render.render_scene(scene, args.blender, args.addon_dir, args.out, args.timeout,
                                   threads=args.threads)
    result.update(seconds=rendered["seconds"], log=relative(rendered["log"], args.out))
    reasons = []
    if rendered["error"]:
        result["status"] = "ERROR"
        reasons.append(rendered["error"])
    for frame in scene.frames:
        reference = scene.reference_path(frame)
        output = rendered["outputs"].get(frame)
        entry = {"frame": frame, "reference": str(reference), "render": str(output or ""),
                 "thresholds": thresholds, "status": "PASS", "reason": ""}
        if not reference.exists():
            entry.update(status="ERROR", reason=f"missing reference {reference.name} "
                                                f"(create it with --update)")
        elif output is None:
            entry.update(status="ERROR", reason="no render")
        else:
            outcome = compare.compare_files(output, reference, thresholds)
            entry["metrics"] = outcome.get("metrics")
            if not outcome["ok"]:
                entry.update(status="FAIL", reason=outcome["reason"])
        entry["images"] = report.write_images(args.out, f"{scene.name}_{frame:04d}",
                                              reference if reference.exists() else None, output)
        result["frames"].append(entry)
        if entry["status"] != "PASS":
            if entry["reason"] != "no render":
                reasons.append(f"frame {frame}: {entry['reason']}" if len(scene.frames) > 1
                               else entry["reason"])
            if result["status"] != "ERROR":
                result["status"] = entry["status"]
    result["reason"] = "; ".join(reasons)
    return result


def update_scene(scene, args):
    """Re-renders one scene with its reference engine and replaces its reference(s)."""
    result = scene_result(scene)
    if scene.sidecar_error:
        result.update(status="ERROR", reason=scene.sidecar_error)
        return result
    rendered = render.render_scene(scene, args.blender, args.addon_dir, args.out, args.timeout,
                                   update=True, threads=args.threads)
    result.update(seconds=rendered["seconds"], log=relative(rendered["log"], args.out))
    if rendered["error"]:
        result.update(status="ERROR", reason=rendered["error"] + " (references left unchanged)")
        return result
    changes = []
    thresholds = compare.merged_thresholds(None)
    for frame in scene.frames:
        reference, output = scene.reference_path(frame), rendered["outputs"][frame]
        entry = {"frame": frame, "reference": str(reference), "render": str(output),
                 "thresholds": thresholds}
        if not reference.exists():
            entry.update(status="NEW", reason=f"new reference {reference.name}")
        elif compare.identical_files(output, reference):
            entry.update(status="IDENTICAL", reason="")
        else:
            outcome = compare.compare_files(output, reference, thresholds)
            entry["metrics"] = outcome.get("metrics")
            m = outcome.get("metrics")
            detail = (f"rel_rmse {m['rel_rmse']:.3g}, mean {m['mean_reference']:.4g} -> "
                      f"{m['mean_image']:.4g} ({m['mean_diff']:.2%}), max_error "
                      f"{m['max_error']:.3g}") if m else outcome["reason"]
            entry.update(status="CHANGED", reason=f"{reference.name} changed: {detail}")
        entry["images"] = report.write_images(args.out, f"{scene.name}_{frame:04d}",
                                              reference if reference.exists() else None, output)
        reference.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(output, reference)
        result["frames"].append(entry)
        changes.append(entry)
    statuses = [c["status"] for c in changes]
    result["status"] = next(s for s in ("CHANGED", "NEW", "IDENTICAL") if s in statuses)
    result["reason"] = "; ".join(c["reason"] for c in changes if c["reason"])
    return result


def safe(work):
    """Wraps check_scene/update_scene so an unexpected error fails one scene, not the run."""
    def run(scene, args):
        try:
            return work(scene, args)
        except Exception as exc:  # noqa: BLE001 - reported as that scene's error
            result = scene_result(scene)
            result.update(status="ERROR", reason=f"regress.py error: {exc!r}\n"
                                                 f"{traceback.format_exc()}")
            return result
    return run


def relative(path, base):
    try:
        return str(Path(path).resolve().relative_to(Path(base).resolve()))
    except ValueError:
        return str(path)


def print_result(index, total, r):
    line = f"[{index:2d}/{total}] {r['status']:<9} {r['name']:<22} {r['seconds']:6.1f} s"
    metrics = [f["metrics"] for f in r["frames"] if f.get("metrics")]
    if metrics and r["status"] in ("PASS", "FAIL"):
        worst = max(metrics, key=lambda m: m["rel_rmse"])
        line += f"  rel_rmse {worst['rel_rmse']:.3g} mean_diff {worst['mean_diff']:.3g}"
    if r["reason"]:
        line += f"\n          {r['reason']}"
    print(line, flush=True)


def main(argv=None):
    args = parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    missing = [str(f) for f in args.folders if not f.is_dir()]
    if missing:
        print(f"regress: not a folder: {', '.join(missing)}", file=sys.stderr)
        return 2
    version = blender_version(args.blender)
    print(f"regress: Blender {version[0]}.{version[1]}, references "
          f"{'beside the scenes' if version == REFERENCE_BLENDER else 'in blender-%d.%d/' % version}",
          flush=True)
    scenes = render.find_scenes(args.folders, args.only, version)
    if args.only:
        unknown = sorted(set(args.only) - {s.name for s in scenes})
        if unknown:
            print(f"regress: no such scene(s): {', '.join(unknown)}", file=sys.stderr)
            return 2
    if not scenes:
        print("regress: no .blend files found", file=sys.stderr)
        return 2
    mode = "updating references of" if args.update else "checking"
    print(f"regress: {mode} {len(scenes)} scene(s), output in {args.out}", flush=True)
    work = safe(update_scene if args.update else check_scene)
    start = time.monotonic()
    results = []
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = [pool.submit(work, scene, args) for scene in scenes]
        for index, future in enumerate(futures, 1):
            results.append(future.result())
            print_result(index, len(scenes), results[-1])
    summary = report.make_summary(results, time.monotonic() - start, args.update)
    report.write_json(args.out, summary, results)
    html_path = report.write_html(args.out, summary, results)
    counts = ", ".join(f"{n} {s}" for s, n in summary["counts"].items())
    print(f"regress: {counts} in {summary['seconds']:.1f} s")
    print(f"regress: report {html_path.resolve()}")
    return 0 if summary["ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
