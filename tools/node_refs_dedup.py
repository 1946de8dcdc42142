#!/usr/bin/env python3
"""Stores each Cycles reference image once: in a test_scenes/nodes/<manifest>/blender-X.Y/ folder,
every <case>.exr bit-identical to the same case's reference of an earlier Blender (FOLDER's
parent, or another blender-*/ folder named with --base) is deleted and its name listed in
same.txt, whose first line names that folder ("base: .." or "base: ../blender-4.3").
tools/node_conformance.py resolves listed names there (reference_path()).

usage: node_refs_dedup.py FOLDER [--base NAME]    e.g.
  node_refs_dedup.py test_scenes/nodes/noise/blender-4.3
  node_refs_dedup.py test_scenes/nodes/noise/blender-5.2 --base ../blender-4.3
"""

import argparse
import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

sys.path.insert(0, str(Path(__file__).resolve().parent))
from node_conformance import reference_path  # noqa: E402


def pixels(path):
    buf = oiio.ImageBuf(str(path))
    return None if buf.has_error else buf.get_pixels(oiio.FLOAT)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=Path)
    parser.add_argument("--base", default="..")
    args = parser.parse_args(argv)
    base = (args.folder / args.base).resolve()
    listed = args.folder / "same.txt"
    names = []
    if listed.exists():
        lines = listed.read_text().split("\n")
        if lines[0] != f"base: {args.base}":
            sys.exit(f"{listed} lists images of another folder ({lines[0]}); one base a folder")
        names = [n for n in lines[1:] if n]
    for image in sorted(args.folder.glob("*.exr")):
        if image.stem == "coords":
            continue
        other = reference_path(base, image.stem)
        if other is None or not other.exists():
            continue
        a, b = pixels(image), pixels(other)
        if a is not None and b is not None and a.shape == b.shape and np.array_equal(a, b):
            image.unlink()
            names.append(image.stem)
    names = sorted(set(names))
    if names:
        listed.write_text(f"base: {args.base}\n" + "\n".join(names) + "\n")
    print(f"{args.folder}: {len(names)} references the same as {args.base}")


if __name__ == "__main__":
    main()
