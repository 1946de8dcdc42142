#!/usr/bin/env python3
"""Shader-node conformance: renders every case of the node manifests (test_scenes/nodes/*.json)
with Photon through tools/node_refs.py and compares each image with the stored Cycles render.

Each case's node output drives an Emission shader, so the image is the node's output. Cycles'
references sample each pixel at its centre; Photon's one sample per pixel lands anywhere in the
pixel. A pixel therefore passes when Photon's value lies within the range of the Cycles values of
the pixel and its eight neighbours (the function between their centres), widened by half that
range and by 2e-3 max(1, |value|). A case passes when at least 99% of its pixels do (a wrong
formula, hash or mode fails nearly every pixel). White Noise of a linked coordinate changes
completely within a pixel, so there the mean and standard deviation must agree (within 0.03). Photon clamps emission at 0 (negative
light), so Cycles' negative values are compared as 0. The report (OUT/report.html) shows Cycles,
Photon and their difference side by side for every case.

The references are those of the Blender the suite runs with: Cycles 3.4's beside each manifest
(test_scenes/nodes/<manifest>/<case>.exr), another Blender's in test_scenes/nodes/<manifest>/
blender-X.Y/ (e.g. blender-4.3), where an image identical to an earlier Blender's is stored once
(same.txt, tools/node_refs_dedup.py). A Blender without references there skips the manifest with a
message; a case that Blender cannot build (<case>.skip there, written by tools/node_refs.py) is
skipped, and so is a manifest whose "min_blender" is newer than the Blender.

usage: node_conformance.py --blender BLENDER --addon-dir STAGE --out DIR [--manifests M.json ...]
"""

import argparse
import html
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

REPO = Path(__file__).resolve().parent.parent
PASS_FRACTION = 0.99
sys.path.insert(0, str(Path(__file__).resolve().parent))
# References of Blenders other than 3.4 live in test_scenes/nodes/<manifest>/blender-X.Y/ (made
# with tools/node_refs.py).
from regress_lib.blender_version import (  # noqa: E402
    REFERENCE_BLENDER, blender_version, version_folder)


def read_rgb(path):
    buf = oiio.ImageBuf(str(path))
    if buf.has_error:
        raise OSError(buf.geterror())
    return buf.get_pixels(oiio.FLOAT)[..., :3]


def write_png(path, rgb):
    rgb = np.clip(np.nan_to_num(rgb), 0.0, 1.0) ** (1.0 / 2.2)
    spec = oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, oiio.UINT8)
    out = oiio.ImageOutput.create(str(path))
    out.open(str(path), spec)
    out.write_image((rgb * 255.0 + 0.5).astype(np.uint8))
    out.close()


def neighbourhood_range(c):
    """Per pixel, the smallest and largest value over the pixel and its eight neighbours."""
    padded = np.pad(c, ((1, 1), (1, 1), (0, 0)), mode='edge')
    h, w = c.shape[:2]
    lo, hi = c.copy(), c.copy()
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            shifted = padded[1 + dy:1 + dy + h, 1 + dx:1 + dx + w]
            lo, hi = np.minimum(lo, shifted), np.maximum(hi, shifted)
    return lo, hi


def compare(reference, rendered, statistical=False):
    c = np.maximum(np.nan_to_num(reference, nan=0.0, posinf=1e30, neginf=0.0), 0.0)
    p = np.nan_to_num(rendered, nan=-1.0)
    if statistical:
        ok = (abs(float(p.mean()) - float(c.mean())) <= 0.03 and
              abs(float(p.std()) - float(c.std())) <= 0.03)
        return ((1.0 if ok else 0.0), float(abs(p.mean() - c.mean()) / max(c.mean(), 1e-3)),
                float('nan'))
    lo, hi = neighbourhood_range(c)
    widen = 0.5 * (hi - lo) + 2e-3 * np.maximum(1.0, np.abs(c))
    ok_pixel = np.all((p >= lo - widen) & (p <= hi + widen), axis=2)
    exact = float(np.all(np.abs(p - c) <= 1e-3 * np.maximum(1.0, np.abs(c)), axis=2).mean())
    scale = max(float(np.sqrt((c ** 2).mean())), 1e-3)
    rel_rmse = float(np.sqrt(((p - c) ** 2).mean()) / scale)
    return float(ok_pixel.mean()), rel_rmse, exact


def render_manifest(manifest, blender, addon_dir, out_dir, timeout):
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(Path(addon_dir).resolve()))
    command = [blender, "-b", "--factory-startup", "--addons", "photon", "--python",
               str(REPO / "tools" / "node_refs.py"), "--", str(manifest), str(out_dir),
               "--engine", "PHOTON"]
    log = out_dir / "render.log"
    with open(log, "w") as f:
        subprocess.run(command, stdout=f, stderr=subprocess.STDOUT, env=env, timeout=timeout,
                       check=False)
    return log


def reference_dir(manifest, version):
    """Where the Cycles references of `manifest` rendered by Blender `version` live: the
    manifest's folder for Blender 3.4 (the first ones), its blender-X.Y subfolder for others."""
    return version_folder(manifest.parent / manifest.stem, version)


def reference_path(references, name):
    """The reference image of case `name` in folder `references`: <name>.exr there, or, when
    the folder's same.txt lists the name (tools/node_refs_dedup.py: an image identical to an
    earlier Blender's), that Blender's image; None when there is none."""
    for _ in range(8):  # a chain of Blenders, each listing names the same as the one before
        image = references / f"{name}.exr"
        if image.exists():
            return image
        listed = references / "same.txt"
        if not listed.exists():
            return None
        lines = listed.read_text().split("\n")
        if name not in lines[1:] or not lines[0].startswith("base: "):
            return None
        references = (references / lines[0][len("base: "):].strip()).resolve()
    return None


def check_manifest(manifest, args):
    family = manifest.stem
    references = reference_dir(manifest, args.version)
    out_dir = Path(args.out) / family
    out_dir.mkdir(parents=True, exist_ok=True)
    data = json.loads(manifest.read_text())
    version_name = f"{args.version[0]}.{args.version[1]}"
    if tuple(args.version) < tuple(data.get("min_blender", (0, 0))):
        reason = f"needs Blender {'.'.join(map(str, data['min_blender']))} or newer"
        return [{"family": family, "name": c["name"], "node": c.get("node"), "status": "SKIP",
                 "reason": reason} for c in data["cases"]], 0.0
    if not (references / "coords.exr").exists():
        reason = f"no Cycles {version_name} references ({references.relative_to(REPO)})"
        return [{"family": family, "name": c["name"], "node": c.get("node"), "status": "SKIP",
                 "reason": reason} for c in data["cases"]], 0.0
    t0 = time.time()
    render_manifest(manifest, args.blender, args.addon_dir, out_dir, args.timeout)
    seconds = time.time() - t0
    results = []
    for case in data["cases"]:
        name = case["name"]
        entry = {"family": family, "name": name, "node": case.get("node"), "status": "PASS",
                 "reason": ""}
        skipped = references / f"{name}.skip"
        if skipped.exists():  # Cycles of this Blender has no such node or setting
            entry.update(status="SKIP", reason=skipped.read_text().strip())
            results.append(entry)
            continue
        if case.get("world"):
            # Seen through an equirectangular panorama, which Photon's camera does not have:
            # the world nodes (the skies) are checked against the same references by the
            # native tests, and lit HDRI scenes by the validation suite.
            entry.update(status="SKIP", reason="panoramic camera")
            results.append(entry)
            continue
        try:
            found = reference_path(references, name)
            reference = read_rgb(found if found is not None else references / f"{name}.exr")
            rendered = read_rgb(out_dir / f"{name}.exr")
        except OSError as error:
            entry.update(status="ERROR", reason=f"no image: {error}")
            results.append(entry)
            continue
        if reference.shape != rendered.shape:
            entry.update(status="ERROR", reason=f"size {rendered.shape} vs {reference.shape}")
            results.append(entry)
            continue
        statistical = (case.get("node") == "ShaderNodeTexWhiteNoise" and
                       case.get("vector", "Vector") is not None)
        fraction, rel_rmse, exact = compare(reference, rendered, statistical)
        entry.update(pixels_ok=fraction, rel_rmse=rel_rmse, pixels_exact=exact)
        if fraction < PASS_FRACTION:
            entry.update(status="FAIL", reason=f"{100 * (1 - fraction):.1f}% of pixels differ "
                                               f"beyond the pixel's own spread")
        stem = Path(args.out) / "images" / f"{family}_{name}"
        stem.parent.mkdir(parents=True, exist_ok=True)
        write_png(f"{stem}_cycles.png", np.maximum(reference, 0.0))
        write_png(f"{stem}_photon.png", rendered)
        write_png(f"{stem}_diff.png", np.abs(rendered - np.maximum(reference, 0.0)) * 10.0)
        entry["images"] = [f"images/{family}_{name}_{kind}.png"
                           for kind in ("cycles", "photon", "diff")]
        results.append(entry)
    return results, seconds


def write_report(path, results):
    rows = []
    for r in results:
        images = "".join(f'<td><img src="{html.escape(i)}" width="96"></td>'
                         for i in r.get("images", []))
        rows.append(f"<tr class='{r['status']}'><td>{html.escape(r['family'])}</td>"
                    f"<td>{html.escape(r['name'])}</td><td>{r['status']}</td>"
                    f"<td>{r.get('pixels_ok', 0):.4f}</td><td>{r.get('pixels_exact', 0):.4f}</td>"
                    f"<td>{r.get('rel_rmse', 0):.2e}</td>"
                    f"<td>{html.escape(r['reason'])}</td>{images}</tr>")
    path.write_text(
        "<html><head><style>.FAIL,.ERROR{background:#fcc} td{font:12px sans-serif}"
        "</style></head><body><h1>Shader-node conformance: Cycles | Photon | |diff| x 10</h1>"
        "<table><tr><th>family</th><th>case</th><th>status</th><th>pixels ok</th>"
        "<th>pixels within 1e-3</th>"
        "<th>rel. RMSE</th><th>reason</th><th>Cycles</th><th>Photon</th><th>diff</th></tr>"
        + "\n".join(rows) + "</table></body></html>")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--addon-dir", required=True,
                        help="the staging folder (BLENDER_USER_SCRIPTS: it holds addons/photon)")
    parser.add_argument("--out", required=True)
    parser.add_argument("--manifests", nargs="*", type=Path,
                        default=sorted((REPO / "test_scenes" / "nodes").glob("*.json")))
    parser.add_argument("--timeout", type=float, default=900.0)
    args = parser.parse_args(argv)
    Path(args.out).mkdir(parents=True, exist_ok=True)
    args.version = blender_version(args.blender)
    print(f"Blender {args.version[0]}.{args.version[1]}: references "
          f"{'beside the manifests' if tuple(args.version) == REFERENCE_BLENDER else 'in blender-%d.%d/ subfolders' % tuple(args.version)}")
    results = []
    for manifest in args.manifests:
        found, seconds = check_manifest(manifest, args)
        results.extend(found)
        failed = sum(r["status"] not in ("PASS", "SKIP") for r in found)
        skipped = sum(r["status"] == "SKIP" for r in found)
        print(f"{manifest.stem}: {len(found) - failed - skipped}/{len(found) - skipped} cases "
              f"pass ({seconds:.0f} s)" + (f", {skipped} skipped" if skipped else ""))
    for r in results:
        if r["status"] not in ("PASS", "SKIP"):
            print(f"  {r['status']} {r['family']}/{r['name']}: {r['reason']}")
    report = Path(args.out) / "report.html"
    write_report(report, results)
    (Path(args.out) / "results.json").write_text(json.dumps(results, indent=1))
    print(f"report: {report}")
    return 0 if all(r["status"] in ("PASS", "SKIP") for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
