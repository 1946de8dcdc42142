"""Report output: tone-mapped PNGs of reference, render and difference (via OpenImageIO), and
report.html / report.json."""

import datetime
import html
import json
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

from . import compare

# Display: the reference's 99.5th percentile (brightest channel per pixel) maps to white, so the
# same exposure serves every scene; reference and render always share it.
WHITE_PERCENTILE = 99.5
DIFF_GAIN = 10.0
# Failures first, then changes, then what passed.
STATUS_ORDER = ["ERROR", "FAIL", "CHANGED", "NEW", "PASS", "IDENTICAL"]


def exposure_scale(reference):
    """Linear scale that maps the reference's bright end to display white (1.0 when black)."""
    if reference is None:
        return 1.0
    rgb = np.nan_to_num(reference[:, :, :3], nan=0.0, posinf=0.0, neginf=0.0)
    white = float(np.percentile(rgb.max(axis=2), WHITE_PERCENTILE)) if rgb.size else 0.0
    return 1.0 / white if white > 1e-6 else 1.0


def to_srgb8(linear):
    """Scene-linear RGB (already exposed) -> clamped, sRGB-encoded uint8."""
    x = np.clip(np.nan_to_num(linear, nan=0.0, posinf=1.0, neginf=0.0), 0.0, 1.0)
    srgb = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)
    return np.round(srgb * 255.0).astype(np.uint8)


def write_png(path, linear_rgb):
    """Writes an exposed linear RGB array as an sRGB PNG through OpenImageIO."""
    pixels = np.ascontiguousarray(to_srgb8(linear_rgb))
    height, width = pixels.shape[:2]
    buf = oiio.ImageBuf(oiio.ImageSpec(width, height, 3, oiio.UINT8))
    buf.set_pixels(oiio.ROI(0, width, 0, height, 0, 1, 0, 3), pixels)
    if not buf.write(str(path)):
        raise RuntimeError(f"cannot write {path}: {buf.geterror()}")


def load_or_none(path):
    if path is None or not Path(path).exists():
        return None
    try:
        return compare.read_rgba(path)
    except compare.ImageError:
        return None


def write_images(out_dir, stem, reference_path, render_path, gain=DIFF_GAIN):
    """Writes STEM_reference.png, STEM_render.png and STEM_diff.png (|a-b| x gain) into
    OUT/images for whichever images are readable; returns {kind: path relative to out_dir}."""
    images_dir = Path(out_dir) / "images"
    images_dir.mkdir(parents=True, exist_ok=True)
    reference, render = load_or_none(reference_path), load_or_none(render_path)
    scale = exposure_scale(reference if reference is not None else render)
    written = {}
    for kind, pixels in (("reference", reference), ("render", render)):
        if pixels is not None:
            name = f"{stem}_{kind}.png"
            write_png(images_dir / name, pixels[:, :, :3] * scale)
            written[kind] = f"images/{name}"
    if reference is not None and render is not None and reference.shape == render.shape:
        name = f"{stem}_diff.png"
        write_png(images_dir / name, np.abs(render[:, :, :3] - reference[:, :, :3]) * scale * gain)
        written["diff"] = f"images/{name}"
    written["exposure_stops"] = round(float(np.log2(scale)), 3)
    return written


def sort_results(results):
    return sorted(results, key=lambda r: (STATUS_ORDER.index(r["status"]), r["name"]))


def write_json(out_dir, summary, results):
    path = Path(out_dir) / "report.json"
    path.write_text(json.dumps({"summary": summary, "scenes": sort_results(results)}, indent=1,
                               default=str))
    return path


def fmt(value):
    if value is None:
        return "&ndash;"
    if isinstance(value, float):
        return f"{value:.4g}"
    return html.escape(str(value))


CSS = """
body { font-family: sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 0.4em 0; }
td, th { border: 1px solid #bbb; padding: 2px 8px; text-align: left; font-size: 90%; }
.ERROR, .FAIL { background: #f8c9c4; } .CHANGED, .NEW { background: #fbe7b5; }
.PASS, .IDENTICAL { background: #cdeccd; } .bad { color: #b00; font-weight: bold; }
figure { display: inline-block; margin: 0 10px 0 0; }
figure img { width: 256px; image-rendering: pixelated; border: 1px solid #888; }
section { border-top: 2px solid #888; margin-top: 1.2em; }
.reason { font-family: monospace; white-space: pre-wrap; }
"""


def metrics_table(frame):
    metrics, thresholds = frame.get("metrics"), frame.get("thresholds") or {}
    if not metrics:
        return ""
    rows = ["<tr><th>metric</th><th>value</th><th>threshold</th></tr>"]
    for key, value in metrics.items():
        limit = thresholds.get(key)
        bad = key in compare.CHECKED and limit is not None and not value <= limit
        rows.append(f"<tr><td>{key}</td><td class='{'bad' if bad else ''}'>{fmt(value)}</td>"
                    f"<td>{'&le; ' + fmt(limit) if limit is not None else '&ndash;'}</td></tr>")
    if "pixel_threshold" in thresholds:
        rows.append(f"<tr><td>pixel_threshold</td><td></td>"
                    f"<td>{fmt(thresholds['pixel_threshold'])}</td></tr>")
    return "<table>" + "".join(rows) + "</table>"


def frame_html(frame):
    parts = [f"<h4 class='{frame['status']}'>frame {frame['frame']}: {frame['status']}</h4>"]
    if frame.get("reason"):
        parts.append(f"<p class='reason'>{html.escape(frame['reason'])}</p>")
    parts.append(metrics_table(frame))
    images = frame.get("images", {})
    labels = (("reference", "reference"), ("render", "new render"),
              ("diff", f"|render &minus; reference| &times; {DIFF_GAIN:g}"))
    figures = [f"<figure><img src='{html.escape(images[k])}'><figcaption>{label}</figcaption>"
               f"</figure>" for k, label in labels if k in images]
    if figures:
        parts.append("<div>" + "".join(figures) + "</div>")
        parts.append(f"<p>display exposure {images.get('exposure_stops', 0):+g} stops, "
                     f"clamped, sRGB</p>")
    return "\n".join(parts)


def write_html(out_dir, summary, results):
    """Writes OUT/report.html: a summary table, then one section per scene, failures first."""
    ordered = sort_results(results)
    rows = ["<tr><th>scene</th><th>status</th><th>time</th><th>reason</th></tr>"]
    for r in ordered:
        rows.append(f"<tr class='{r['status']}'><td><a href='#{html.escape(r['name'])}'>"
                    f"{html.escape(r['name'])}</a></td><td>{r['status']}</td>"
                    f"<td>{r.get('seconds', 0):.1f} s</td>"
                    f"<td class='reason'>{html.escape(r.get('reason', ''))}</td></tr>")
    sections = []
    for r in ordered:
        kind = "validation (reference: " + r["reference_engine"] + ")" if r.get("validation") \
            else "regression (reference: PHOTON)"
        head = (f"<section id='{html.escape(r['name'])}'><h2 class='{r['status']}'>"
                f"{html.escape(r['name'])}: {r['status']}</h2>"
                f"<p>{html.escape(str(r.get('blend', '')))} &mdash; {kind}; "
                f"{r.get('seconds', 0):.1f} s; <a href='{html.escape(r.get('log', ''))}'>log</a>"
                f"</p>")
        if r.get("description"):
            head += f"<p><i>{html.escape(r['description'])}</i></p>"
        if r.get("reason"):
            head += f"<p class='reason'>{html.escape(r['reason'])}</p>"
        sections.append(head + "\n".join(frame_html(f) for f in r.get("frames", []))
                        + "</section>")
    counts = ", ".join(f"{n} {s}" for s, n in summary["counts"].items())
    page = (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Photon regression "
            f"report</title><style>{CSS}</style></head><body>"
            f"<h1>Photon regression report{' (update)' if summary.get('update') else ''}</h1>"
            f"<p>{html.escape(summary['date'])} &mdash; {len(results)} scenes: {counts}; "
            f"total {summary['seconds']:.1f} s</p><table>{''.join(rows)}</table>"
            + "\n".join(sections) + "</body></html>")
    path = Path(out_dir) / "report.html"
    path.write_text(page)
    return path


def make_summary(results, seconds, update):
    counts = {}
    for status in STATUS_ORDER:
        n = sum(r["status"] == status for r in results)
        if n:
            counts[status] = n
    return {"date": datetime.datetime.now().isoformat(timespec="seconds"), "counts": counts,
            "seconds": seconds, "update": update,
            "ok": not any(r["status"] in ("ERROR", "FAIL") for r in results)}
