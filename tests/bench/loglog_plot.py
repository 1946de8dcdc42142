"""Small log-log line plots drawn with numpy and OpenImageIO (no matplotlib), shared by the
benchmark scripts that write figures into docs/.

    canvas = new_canvas(860, 560)
    draw_panel(canvas, (0, 0, 860, 560), series, "x label", "y label", "title")
    save(canvas, "plot.png")

`series` is a list of (label, (r, g, b), [(x, y), ...]); a label starting with "1 /" is drawn
dashed without markers (a reference slope).
"""

import math

import numpy as np
import OpenImageIO as oiio

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"


def new_canvas(width, height):
    return np.ones((height, width, 3))


def draw_text(canvas, x, y, text, size=15, color=(0, 0, 0)):
    buf = oiio.ImageBuf(oiio.ImageSpec(canvas.shape[1], canvas.shape[0], 3, oiio.FLOAT))
    buf.set_pixels(oiio.ROI(), canvas.astype(np.float32))
    oiio.ImageBufAlgo.render_text(buf, int(x), int(y), text, size, FONT, color)
    canvas[:] = buf.get_pixels(oiio.FLOAT)


def draw_line(canvas, p0, p1, color, width=2, dash=0):
    n = int(max(abs(p1[0] - p0[0]), abs(p1[1] - p0[1]))) + 1
    for i in range(n):
        if dash and (i // dash) % 2:
            continue
        t = i / max(n - 1, 1)
        x, y = p0[0] + (p1[0] - p0[0]) * t, p0[1] + (p1[1] - p0[1]) * t
        x0, y0 = int(round(x)) - width // 2, int(round(y)) - width // 2
        canvas[max(y0, 0):y0 + width, max(x0, 0):x0 + width] = color


def draw_panel(canvas, rect, series, x_label, y_label, title, hline=None, legend_width=330,
               font=14):
    """Draws one log-log panel into rect = (x, y, width, height) of the canvas; `hline` is a y
    value marked by a dotted grey line across the panel (a target error, say)."""
    rx, ry, w, h = rect
    left, right, top, bottom = 90, 30, 50, 70
    xs = [x for _, _, pts in series for x, _ in pts if x > 0]
    ys = [y for _, _, pts in series for _, y in pts if y > 0]
    if hline:
        ys.append(hline)
    x_lo, x_hi = math.floor(math.log10(min(xs))), math.ceil(math.log10(max(xs)))
    y_lo, y_hi = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))
    x_hi, y_hi = max(x_hi, x_lo + 1), max(y_hi, y_lo + 1)

    def to_px(x, y):
        u = (math.log10(x) - x_lo) / (x_hi - x_lo)
        v = (math.log10(y) - y_lo) / (y_hi - y_lo)
        return rx + left + u * (w - left - right), ry + h - bottom - v * (h - top - bottom)

    grey, dark = (0.85, 0.85, 0.85), (0.2, 0.2, 0.2)
    for e in range(x_lo, x_hi + 1):
        for m in range(1, 10):
            if e == x_hi and m > 1:
                break
            x, _ = to_px(m * 10.0 ** e, 10.0 ** y_lo)
            draw_line(canvas, (x, ry + top), (x, ry + h - bottom),
                      grey if m > 1 else (0.7, 0.7, 0.7), 1)
        x, _ = to_px(10.0 ** e, 10.0 ** y_lo)
        draw_text(canvas, x - 16, ry + h - bottom + 22, f"1e{e}", font, dark)
    for e in range(y_lo, y_hi + 1):
        for m in range(1, 10):
            if e == y_hi and m > 1:
                break
            _, y = to_px(10.0 ** x_lo, m * 10.0 ** e)
            draw_line(canvas, (rx + left, y), (rx + w - right, y),
                      grey if m > 1 else (0.7, 0.7, 0.7), 1)
        _, y = to_px(10.0 ** x_lo, 10.0 ** e)
        draw_text(canvas, rx + 30, y + 5, f"1e{e}", font, dark)
    if hline:
        _, y = to_px(10.0 ** x_lo, hline)
        draw_line(canvas, (rx + left, y), (rx + w - right, y), (0.45, 0.45, 0.45), 1, dash=3)
    draw_line(canvas, (rx + left, ry + top), (rx + left, ry + h - bottom), dark, 2)
    draw_line(canvas, (rx + left, ry + h - bottom), (rx + w - right, ry + h - bottom), dark, 2)
    draw_text(canvas, rx + left + (w - left - right) / 2 - 60, ry + h - 15, x_label, font + 2,
              dark)
    draw_text(canvas, rx + 8, ry + top - 18, y_label, font + 2, dark)
    draw_text(canvas, rx + left + 120, ry + 28, title, font + 3, dark)
    for i, (label, color, pts) in enumerate(series):
        px = [to_px(x, y) for x, y in pts if x > 0 and y > 0]
        dashed = label.startswith("1 /")
        for a, b in zip(px, px[1:]):
            draw_line(canvas, a, b, color, 2, dash=8 if dashed else 0)
        if not dashed:
            for x, y in px:
                canvas[int(y) - 4:int(y) + 5, int(x) - 4:int(x) + 5] = color
        ly = ry + top + 20 + 24 * i
        draw_line(canvas, (rx + w - right - legend_width, ly),
                  (rx + w - right - legend_width + 40, ly), color, 3, dash=8 if dashed else 0)
        draw_text(canvas, rx + w - right - legend_width + 50, ly + 5, label, font, dark)


def save(canvas, path):
    out = oiio.ImageBuf(oiio.ImageSpec(canvas.shape[1], canvas.shape[0], 3, oiio.UINT8))
    out.set_pixels(oiio.ROI(), np.clip(canvas, 0, 1).astype(np.float32))
    if not out.write(str(path)):
        raise SystemExit(f"cannot write {path}: {out.geterror()}")


def plot(path, series, x_label, y_label, title):
    """One 860 x 560 panel written to `path`."""
    canvas = new_canvas(860, 560)
    draw_panel(canvas, (0, 0, 860, 560), series, x_label, y_label, title)
    save(canvas, path)
