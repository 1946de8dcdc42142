"""Image loading (OpenImageIO) and the metrics that decide whether a render matches its reference.

All colour metrics use the R, G and B channels only. Alpha is checked on its own: its largest
absolute difference is the `alpha_max` metric (a missing alpha channel counts as 1.0).
"""

import numpy as np
import OpenImageIO as oiio

# Relative errors divide by |reference| + EPS, so black pixels do not blow up: an absolute
# error of 0.01 on a black pixel is a relative error of 1.
EPS = 0.01
# Guard for relative figures whose denominator is the reference's mean (black references).
MEAN_EPS = 1e-6

# Defaults for Photon against its own stored references. Photon is deterministic for a fixed
# seed (any thread count, any tile size), so the same machine reproduces a reference exactly;
# the slack only absorbs floating-point differences between CPUs (Embree picks SSE/AVX kernels
# at run time). A threshold of None is reported but not checked.
DEFAULT_THRESHOLDS = {
    "mean_abs": None,          # mean |a-b| over RGB values (scene-linear units)
    "mean_rel": 1e-3,          # mean |a-b| / (|b| + EPS) over RGB values
    "rmse": None,              # sqrt(mean (a-b)^2)
    "rel_rmse": 1e-3,          # rmse / mean(reference RGB)
    "mean_diff": 5e-4,         # |mean(a) - mean(b)| / mean(b)
    "pixel_threshold": 0.01,   # a pixel "differs" when max_c |a-b| / (|b| + EPS) exceeds this...
    "pixel_fraction": 1e-3,    # ...and at most this fraction of pixels may differ
    "max_error": None,         # max |a-b| over RGB values
    "alpha_max": 1e-3,         # max |alpha_a - alpha_b|
}

# Metric name -> threshold key; every metric here must be <= its threshold.
CHECKED = ["mean_abs", "mean_rel", "rmse", "rel_rmse", "mean_diff", "pixel_fraction",
           "max_error", "alpha_max"]


class ImageError(Exception):
    """An image that cannot be read."""


def read_rgba(path):
    """Returns the float pixels of an image as (height, width, 4) RGBA, top row first.

    Channels are picked by name (R, G, B, A) when present, else by position; a missing alpha
    channel is filled with 1.0.
    """
    buf = oiio.ImageBuf(str(path))
    if buf.has_error:
        raise ImageError(f"cannot read {path}: {buf.geterror()}")
    spec = buf.spec()
    pixels = buf.get_pixels(oiio.FLOAT)
    if buf.has_error or pixels is None or getattr(pixels, "size", 0) == 0:
        raise ImageError(f"cannot read pixels of {path}: {buf.geterror()}")
    pixels = np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels)
    names = list(spec.channelnames)
    if all(c in names for c in "RGB"):
        order = [names.index(c) for c in "RGB"]
    elif spec.nchannels >= 3:
        order = [0, 1, 2]
    else:  # grey: replicate
        order = [0, 0, 0]
    rgb = pixels[:, :, order]
    if "A" in names:
        alpha = pixels[:, :, names.index("A")]
    elif spec.nchannels == 4:
        alpha = pixels[:, :, 3]
    else:
        alpha = np.ones(rgb.shape[:2], dtype=np.float32)
    return np.concatenate([rgb, alpha[:, :, None]], axis=2)


def merged_thresholds(overrides=None):
    """The default thresholds updated with a sidecar's "thresholds" dict (unknown keys fail)."""
    thresholds = dict(DEFAULT_THRESHOLDS)
    for key, value in (overrides or {}).items():
        if key not in thresholds:
            raise ValueError(f"unknown threshold {key!r} (known: {', '.join(thresholds)})")
        thresholds[key] = None if value is None else float(value)
    return thresholds


def compute_metrics(image, reference, pixel_threshold=DEFAULT_THRESHOLDS["pixel_threshold"]):
    """Metrics of `image` against `reference`, both (h, w, 4) float RGBA arrays of equal size."""
    a = np.asarray(image[:, :, :3], dtype=np.float64)
    b = np.asarray(reference[:, :, :3], dtype=np.float64)
    diff = np.abs(a - b)
    rel = diff / (np.abs(b) + EPS)
    mean_a, mean_b = float(a.mean()), float(b.mean())
    denominator = max(abs(mean_b), MEAN_EPS)
    rmse = float(np.sqrt(np.mean(diff ** 2)))
    pixel_error = rel.max(axis=2)
    alpha_a = np.asarray(image[:, :, 3], dtype=np.float64)
    alpha_b = np.asarray(reference[:, :, 3], dtype=np.float64)
    return {
        "mean_abs": float(diff.mean()),
        "mean_rel": float(rel.mean()),
        "rmse": rmse,
        "rel_rmse": rmse / denominator,
        "mean_image": mean_a,
        "mean_reference": mean_b,
        "mean_diff": abs(mean_a - mean_b) / denominator,
        "pixel_fraction": float(np.mean(pixel_error > pixel_threshold)),
        "max_error": float(diff.max()) if diff.size else 0.0,
        "alpha_max": float(np.abs(alpha_a - alpha_b).max()) if alpha_a.size else 0.0,
    }


def check_metrics(metrics, thresholds):
    """Returns the list of failed checks as readable strings (empty when everything passed)."""
    failures = []
    for key in CHECKED:
        limit = thresholds.get(key)
        if limit is not None and not metrics[key] <= limit:
            failures.append(f"{key} {metrics[key]:.4g} > {limit:.4g}")
    return failures


def compare_files(image_path, reference_path, thresholds):
    """Compares two image files. Returns a dict with "ok", "reason" and (when both images were
    readable and of equal size) "metrics"; never raises for bad images."""
    try:
        image = read_rgba(image_path)
    except ImageError as exc:
        return {"ok": False, "reason": f"render unreadable: {exc}"}
    try:
        reference = read_rgba(reference_path)
    except ImageError as exc:
        return {"ok": False, "reason": f"reference unreadable: {exc}"}
    return compare_arrays(image, reference, thresholds)


def compare_arrays(image, reference, thresholds):
    """compare_files for arrays already in memory."""
    if image.shape != reference.shape:
        return {"ok": False, "reason": f"size mismatch: render {image.shape[1]}x{image.shape[0]}, "
                                       f"reference {reference.shape[1]}x{reference.shape[0]}"}
    bad = int(np.count_nonzero(~np.isfinite(image)))
    if bad:
        return {"ok": False, "reason": f"render has {bad} NaN/infinite channel values"}
    bad = int(np.count_nonzero(~np.isfinite(reference)))
    if bad:
        return {"ok": False, "reason": f"reference has {bad} NaN/infinite channel values"}
    metrics = compute_metrics(image, reference, thresholds["pixel_threshold"])
    failures = check_metrics(metrics, thresholds)
    return {"ok": not failures, "reason": "; ".join(failures), "metrics": metrics}


def identical_files(path_a, path_b):
    """True when both files hold bit-identical pixels (metadata may differ)."""
    try:
        a, b = read_rgba(path_a), read_rgba(path_b)
    except ImageError:
        return False
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))
