"""Blender 4.2+ installs Photon as an extension (blender_manifest.toml): the zip that
tools/pack_extension.py makes from the staged add-on installs with `blender --command extension
install-file`, is enabled, and renders. Skipped in Blender 3.4, which has no extensions."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def isolated_env(tmp_path):
    """A Blender that sees no user add-ons, preferences or extensions but its own."""
    env = dict(os.environ)
    for name in ("CONFIG", "SCRIPTS", "EXTENSIONS", "DATAFILES"):
        folder = tmp_path / name.lower()
        folder.mkdir()
        env[f"BLENDER_USER_{name}"] = str(folder)
    return env


def run(cmd, env):
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300,
                          stdin=subprocess.DEVNULL)
    log = f"$ {' '.join(map(str, cmd))}\n{proc.stdout}\n{proc.stderr}"
    return proc, log


def test_extension_installs_enables_and_renders(blender, tmp_path):
    if blender.version < (4, 2):
        pytest.skip("extensions exist from Blender 4.2 (this Blender installs the legacy add-on)")
    zip_path = tmp_path / "photon-extension.zip"
    subprocess.run([sys.executable, str(REPO / "tools" / "pack_extension.py"),
                    str(blender.stage / "addons" / "photon"),
                    str(REPO / "addon" / "photon" / "blender_manifest.toml"), str(zip_path)],
                   check=True)
    env = isolated_env(tmp_path)
    proc, log = run([blender.executable, "-b", "--factory-startup", "--command", "extension",
                     "install-file", "-r", "user_default", "-e", str(zip_path)], env)
    assert proc.returncode == 0, log

    out = tmp_path / "frame.png"
    script = (
        "import bpy, addon_utils\n"
        "mod = 'bl_ext.user_default.photon'\n"
        "assert addon_utils.check(mod)[1], 'extension not enabled'\n"
        "scene = bpy.context.scene\n"
        "scene.render.engine = 'PHOTON'\n"
        "scene.render.resolution_x = scene.render.resolution_y = 32\n"
        "scene.photon.samples = 4\n"
        f"scene.render.filepath = {str(out)!r}\n"
        "bpy.ops.render.render(write_still=True)\n"
        "print('PHOTON_EXTENSION_OK', bpy.context.preferences.addons[mod].module)\n")
    # Not factory settings: the preferences saved by the install keep the extension enabled.
    proc, log = run([blender.executable, "-b", "--python-expr", script], env)
    assert proc.returncode == 0 and "PHOTON_EXTENSION_OK" in proc.stdout, log
    assert "Photon: rendered frame" in proc.stdout, log
    assert out.exists(), log
