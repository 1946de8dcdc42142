#!/usr/bin/env python3
"""Packs the staged add-on as a Blender 4.2+ extension: the package's files and
blender_manifest.toml at the zip's top level, without caches of compiled Python.

usage: pack_extension.py STAGED_ADDON_DIR MANIFEST OUT.zip
"""

import sys
import zipfile
from pathlib import Path


def main(staged, manifest, out):
    staged, out = Path(staged), Path(out)
    tmp = out.with_suffix(".zip.partial")
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.write(manifest, "blender_manifest.toml")
        for path in sorted(staged.rglob("*")):
            rel = path.relative_to(staged)
            if path.is_dir() or "__pycache__" in rel.parts or rel.name == "blender_manifest.toml":
                continue
            zf.write(path, rel.as_posix())
    tmp.replace(out)
    print(f"extension: {out} ({out.stat().st_size // 1024} kB)")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
