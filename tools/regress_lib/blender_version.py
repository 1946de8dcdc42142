"""Which Blender a suite runs with, and where the references that Blender rendered live.

The first references were rendered in Blender 3.4 and sit beside their scenes; those of another
Blender X.Y live in a blender-X.Y/ subfolder of the same folder, because each Blender's Cycles
(and each Blender's reading of a file) can change an image."""

import re
import subprocess
from pathlib import Path

REFERENCE_BLENDER = (3, 4)


def blender_version(blender):
    """(major, minor) of the Blender binary, from `blender --version`."""
    out = subprocess.run([str(blender), "-b", "--factory-startup", "--version"],
                         capture_output=True, text=True, timeout=120, check=False).stdout
    match = re.search(r"Blender (\d+)\.(\d+)", out)
    if match is None:
        raise RuntimeError(f"cannot read the version of {blender}: {out[:200]!r}")
    return int(match.group(1)), int(match.group(2))


def version_folder(folder, version):
    """`folder` itself for Blender 3.4's references, folder/blender-X.Y for Blender X.Y's."""
    if version is None or tuple(version) == REFERENCE_BLENDER:
        return Path(folder)
    return Path(folder) / f"blender-{version[0]}.{version[1]}"
