#!/usr/bin/env python3
"""Writes the image-node conformance textures beside this script: a 16 x 8 RGBA image whose
texels all differ (no symmetry, so a flipped, mirrored or shifted lookup shows), with alpha
from 0 to 1, as an 8-bit PNG (tex.png) and a float EXR (tex.exr, colours up to 2).

usage: /usr/bin/python3 make_image.py
"""

from pathlib import Path

import numpy as np
import OpenImageIO as oiio

WIDTH, HEIGHT = 16, 8
HERE = Path(__file__).resolve().parent


def texels():
    """RGBA in [0, 1], row 0 at the top (as files store it)."""
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH].astype(np.float64)
    r = (x + 0.5) / WIDTH
    g = ((y * 5 + x * 3) % HEIGHT + 0.5) / HEIGHT
    b = ((x * 7 + y * 11) % 13 + 0.5) / 13.0
    a = 0.25 + 0.75 * ((x * 3 + y * 5) % 9) / 8.0
    a[(x.astype(int) + y.astype(int)) % 11 == 0] = 0.0  # fully transparent texels
    return np.stack([r, g, b, a], axis=-1)


def write(path, pixels, fmt):
    spec = oiio.ImageSpec(WIDTH, HEIGHT, 4, fmt)
    if fmt == oiio.UINT8:  # PNG stores straight alpha: write the values as they are (without
        spec.attribute("oiio:UnassociatedAlpha", 1)  # this OpenImageIO would unpremultiply)
    out = oiio.ImageOutput.create(str(path))
    if out is None or not out.open(str(path), spec):
        raise OSError(oiio.geterror())
    out.write_image(pixels)
    out.close()


def main():
    rgba = texels()
    byte = np.round(rgba * 255.0).astype(np.uint8)
    write(HERE / "tex.png", byte, oiio.UINT8)
    hdr = rgba.copy()
    hdr[..., :3] *= 2.0
    write(HERE / "tex.exr", hdr.astype(np.float32), oiio.FLOAT)


if __name__ == "__main__":
    main()
