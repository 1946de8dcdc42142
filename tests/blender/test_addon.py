"""The add-on registers, unregisters and survives a broken native module."""

import shutil


def test_registers_and_unregisters_cleanly(blender):
    result, proc = blender.run_script("addon_register.py")
    assert "exception" not in result, result.get("exception")
    assert result["import_error"] is None
    assert result["engine_registered"] and result["has_settings"] and result["panel_registered"]
    assert result["defaults"] == {"integrator": "PHOTON_MAP", "samples": 64, "max_depth": 8,
                                  "seed": 0, "threads": 0, "tile_size": 64}
    assert result["after_disable"] == {"engine_registered": False, "has_settings": False,
                                       "panel_registered": False}
    assert result["after_enable"] == {"engine_registered": True, "has_settings": True}
    assert "Traceback" not in proc.stderr


def test_missing_native_module_still_registers_and_reports(blender, tmp_path):
    stage = tmp_path / "stage"
    shutil.copytree(blender.stage, stage)
    for so in (stage / "addons" / "photon").glob("_photon*.so"):
        so.unlink()
    result, _ = blender.run_script("addon_register.py", stage=stage)
    assert result["engine_registered"]
    # Says the module is missing and how to build it; Python's own message would blame a
    # circular import.
    assert "is not installed in" in result["import_error"], result["import_error"]
    assert "setup_and_demo.sh" in result["import_error"]
    assert "circular" not in result["import_error"]

    # Rendering then fails with a clear error instead of crashing Blender.
    blend = tmp_path / "empty.blend"
    blender.run_script("make_bad_scene.py", "empty_scene", blend)
    proc = blender.run([str(blend), "-E", "PHOTON", "-o", str(tmp_path / "out_"), "-f", "1"],
                       stage=stage, check=False)
    assert proc.returncode in (0, 1), proc.log  # never a signal (crash)
    assert "is not installed in" in proc.stdout + proc.stderr, proc.log


def test_broken_native_module_reports_the_loaders_message(blender, tmp_path):
    stage = tmp_path / "stage"
    shutil.copytree(blender.stage, stage)
    for so in (stage / "addons" / "photon").glob("_photon*.so"):
        so.write_bytes(b"not an ELF file")
    result, _ = blender.run_script("addon_register.py", stage=stage)
    assert result["engine_registered"]
    assert "native module _photon failed to load: ImportError" in result["import_error"], \
        result["import_error"]


def test_zip_installs_through_preferences(blender, tmp_path):
    """The zip from the photon_addon_zip target installs with Preferences > Add-ons > Install."""
    import subprocess
    build_dir = blender.stage.parent
    subprocess.run(["cmake", "--build", str(build_dir), "--target", "photon_addon_zip"],
                   check=True, capture_output=True)
    zip_path = build_dir / "photon-addon.zip"
    user_scripts = tmp_path / "user_scripts"
    (user_scripts / "addons").mkdir(parents=True)
    script = (
        "import bpy, addon_utils, sys\n"
        f"bpy.ops.preferences.addon_install(filepath={str(zip_path)!r}, overwrite=True)\n"
        "addon_utils.enable('photon', default_set=True)\n"
        "import photon\n"
        "print('PHOTON_FILE', photon.__file__)\n"
        "print('PHOTON_NATIVE_ERROR', photon.NATIVE_IMPORT_ERROR)\n"
        "bpy.context.scene.render.engine = 'PHOTON'\n"
        "print('PHOTON_ENGINE', bpy.context.scene.render.engine)\n")
    env = blender.env(stage=user_scripts)
    proc = subprocess.run([blender.executable, "-b", "--factory-startup", "--python-expr", script],
                          env=env, capture_output=True, text=True, timeout=120)
    assert f"PHOTON_FILE {user_scripts}/addons/photon/__init__.py" in proc.stdout, proc.stdout
    assert "PHOTON_NATIVE_ERROR None" in proc.stdout, proc.stdout
    assert "PHOTON_ENGINE PHOTON" in proc.stdout, proc.stdout
