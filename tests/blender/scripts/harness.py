"""Shared by the scripts that tests run inside Blender."""

import json
import sys
import traceback


def script_args():
    argv = sys.argv
    return argv[argv.index("--") + 1:] if "--" in argv else []


def run(main):
    """Calls main(*args) and writes its returned dict as JSON to the result path (first arg)."""
    args = script_args()
    result_path, rest = args[0], args[1:]
    try:
        result = main(*rest)
    except Exception:  # noqa: BLE001 - report any failure to the test as data
        result = {"exception": traceback.format_exc()}
        print(result["exception"], file=sys.stderr)
    with open(result_path, "w") as f:
        json.dump(result, f, indent=1)


def read_image(path):
    """RGBA float pixels of an image file as a numpy array (height, width, 4), top row first."""
    import numpy as np
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(str(path))
    pixels = buf.get_pixels(oiio.FLOAT)
    if pixels is None or pixels.size == 0:
        raise RuntimeError(f"cannot read {path}: {buf.geterror()}")
    pixels = np.asarray(pixels, dtype=np.float32)
    if pixels.shape[2] == 3:
        pixels = np.concatenate([pixels, np.ones_like(pixels[:, :, :1])], axis=2)
    return pixels[:, :, :4]
